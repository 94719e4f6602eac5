#include "adjoin/observe/phases.hpp"

#include <cmath>

namespace adjoin {

void PhaseObserver::observe(const State& s) {
  if (intervals_.empty() || intervals_.back().state != s.phase) {
    const double t = std::isnan(s.t_switch) || intervals_.empty() ? s.t : s.t_switch;
    if (!intervals_.empty()) intervals_.back().t_end = t;
    intervals_.push_back(PhaseInterval{s.phase, t, s.t});
  } else {
    intervals_.back().t_end = s.t;
  }
}

}  // namespace adjoin
