#include "adjoin/observe/peaks.hpp"

#include <cmath>

namespace adjoin {

void PeakObserver::begin(const RunInfo&) {
  peaks_ = Peaks{};
  for (SmoothPeak* p : {&f1_, &f2_, &stuck_q_}) p->reset();
  for (DerivativePeak* p : {&x1_, &x2_, &drift_}) p->reset();
}

void PeakObserver::observe(const State& s) {
  // Relative accelerations x'' = (absolute) + a_g.
  const double acc1 = s.a1 + s.ag, acc2 = s.a2 + s.ag;
  x1_.update({s.t, s.x1, s.v1, acc1}, s.t_switch);
  x2_.update({s.t, s.x2, s.v2, acc2}, s.t_switch);
  drift_.update({s.t, s.x1 - s.x2, s.v1 - s.v2, acc1 - acc2}, s.t_switch);
  f1_.update(s.f1, s.t);
  f2_.update(s.f2, s.t);
  peaks_.v1.update(s.v1, s.t);
  peaks_.v2.update(s.v2, s.t);
  peaks_.a1.update(s.a1, s.t);
  peaks_.a2.update(s.a2, s.t);
  // q reaches a new largest value where the damper starts to slip: at the located switch.
  peaks_.q.update(s.q, std::isnan(s.t_switch) ? s.t : s.t_switch);
  // While stuck, q is the smooth stick force: refine its peaks between samples (the largest
  // stick force is the threshold below which the damper would have slipped).
  if (s.phase == Phase::stick) {
    stuck_q_.update(s.q, s.t);
    if (stuck_q_.peak().max_abs > peaks_.q.max_abs) peaks_.q = stuck_q_.peak();
  } else {
    stuck_q_.reset();
  }
  peaks_.ag.update(s.ag, s.t);
}

const Peaks& PeakObserver::peaks() const {
  peaks_.x1 = x1_.peak();
  peaks_.x2 = x2_.peak();
  peaks_.f1 = f1_.peak();
  peaks_.f2 = f2_.peak();
  peaks_.drift = drift_.peak();
  return peaks_;
}

}  // namespace adjoin
