#include "fftw_planner.hpp"

namespace adjoin::detail {

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace adjoin::detail
