#include "adjoin/observe/peaks.hpp"

#include <cmath>

namespace adjoin {

void PeakObserver::begin(const RunInfo&) {
  for (SmoothPeak* p : {&shear_[0], &shear_[1], &stuck_force_}) p->reset();
  for (DerivativePeak* p : {&x_[0], &x_[1], &stroke_}) p->reset();
  for (Peak* p : {&link_force_, &v_[0], &v_[1], &a_abs_[0], &a_abs_[1], &ag_}) *p = Peak{};
}

void PeakObserver::observe(const State& s) {
  // Relative accelerations x'' = (absolute) + a_g.
  const double acc_a = s.a1 + s.ag, acc_b = s.a2 + s.ag;
  x_[0].update({s.t, s.x1, s.v1, acc_a}, s.t_switch);
  x_[1].update({s.t, s.x2, s.v2, acc_b}, s.t_switch);
  stroke_.update({s.t, s.x1 - s.x2, s.v1 - s.v2, acc_a - acc_b}, s.t_switch);
  shear_[0].update(s.f1, s.t);
  shear_[1].update(s.f2, s.t);
  v_[0].update(s.v1, s.t);
  v_[1].update(s.v2, s.t);
  a_abs_[0].update(s.a1, s.t);
  a_abs_[1].update(s.a2, s.t);
  // The link force reaches a new largest value where the link starts to slip: at the located
  // switch.
  link_force_.update(s.q, std::isnan(s.t_switch) ? s.t : s.t_switch);
  // While stuck, the force is the smooth stick force: refine its peaks between samples (the
  // largest stick force is the threshold below which the link would have slipped).
  if (s.phase == Phase::stick) {
    stuck_force_.update(s.q, s.t);
    if (stuck_force_.peak().max_abs > link_force_.max_abs) link_force_ = stuck_force_.peak();
  } else {
    stuck_force_.reset();
  }
  ag_.update(s.ag, s.t);
}

std::vector<ChannelPeak> PeakObserver::peaks() const {
  return {{"A.x1", x_[0].peak()},       {"B.x1", x_[1].peak()},   {"link1.stroke", stroke_.peak()},
          {"A.shear1", shear_[0].peak()}, {"B.shear1", shear_[1].peak()}, {"link1.force", link_force_},
          {"A.v1", v_[0]},               {"B.v1", v_[1]},          {"A.a1_abs", a_abs_[0]},
          {"B.a1_abs", a_abs_[1]},       {"ag", ag_}};
}

}  // namespace adjoin
