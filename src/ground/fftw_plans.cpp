// Cached FFTW plans for the synthesis (see fftw_plans.hpp).
#include "synthesis_detail.hpp"

#include <map>
#include <mutex>

#include "../detail/fftw_planner.hpp"
#include <new>

namespace adjoin::detail {
namespace {


enum class Direction { forward, inverse };

fftw_plan cached_plan(std::size_t n, Direction direction) {
  // Plans live for the whole process. The cache is never destroyed (a destroyed map would leave
  // the plans unreachable at exit, which LeakSanitizer reports, and destroying the plans at
  // exit would race with the destruction of the planner mutex).
  static auto& plans = *new std::map<std::pair<std::size_t, Direction>, fftw_plan>();
  std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
  auto it = plans.find({n, direction});
  if (it != plans.end()) return it->second;
  RealArray real = real_array(n);
  ComplexArray spectrum = complex_array(n / 2 + 1);
  const int len = static_cast<int>(n);
  fftw_plan plan = direction == Direction::inverse
                       ? fftw_plan_dft_c2r_1d(len, spectrum.get(), real.get(), FFTW_ESTIMATE)
                       : fftw_plan_dft_r2c_1d(len, real.get(), spectrum.get(), FFTW_ESTIMATE);
  if (!plan) throw std::bad_alloc();
  plans.emplace(std::make_pair(n, direction), plan);
  return plan;
}

}  // namespace

RealArray real_array(std::size_t n) {
  void* p = fftw_malloc(sizeof(double) * (n ? n : 1));
  if (!p) throw std::bad_alloc();
  return RealArray(static_cast<double*>(p));
}

ComplexArray complex_array(std::size_t n) {
  void* p = fftw_malloc(sizeof(fftw_complex) * (n ? n : 1));
  if (!p) throw std::bad_alloc();
  return ComplexArray(static_cast<fftw_complex*>(p));
}

void inverse_real_fft(std::size_t n, fftw_complex* in, double* out) {
  fftw_execute_dft_c2r(cached_plan(n, Direction::inverse), in, out);
}

void forward_real_fft(std::size_t n, double* in, fftw_complex* out) {
  fftw_execute_dft_r2c(cached_plan(n, Direction::forward), in, out);
}

std::size_t smooth_fft_length(std::size_t n) {
  for (std::size_t m = n < 2 ? 2 : n + (n & 1);; m += 2) {
    std::size_t r = m;
    for (std::size_t p : {2u, 3u, 5u, 7u})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

}  // namespace adjoin::detail
