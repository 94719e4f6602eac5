#include "adjoin/observe/peaks.hpp"

#include <cmath>

namespace adjoin {

void PeakObserver::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  phase_.begin(s, o);
  link_ = !s.links.empty();
  for (SmoothPeak* p : {&shear_[0], &shear_[1], &stuck_force_}) p->reset();
  for (DerivativePeak* p : {&x_[0], &x_[1], &stroke_}) p->reset();
  for (Peak* p : {&link_force_, &v_[0], &v_[1], &a_abs_[0], &a_abs_[1], &ag_}) *p = Peak{};
}

void PeakObserver::observe(const StructureState& s, const PairPhase& phase) {
  const double t_switch = phase.t_switch;
  const double xa = s.x[0], xb = s.x[1], va = s.v[0], vb = s.v[1];
  const double a_abs_a = s.a_abs[0], a_abs_b = s.a_abs[1];
  const double force = link_ ? s.link_force[0] : 0.0;
  // Relative accelerations x'' = (absolute) + a_g.
  const double acc_a = a_abs_a + s.ag, acc_b = a_abs_b + s.ag;
  x_[0].update({s.t, xa, va, acc_a}, t_switch);
  x_[1].update({s.t, xb, vb, acc_b}, t_switch);
  stroke_.update({s.t, xa - xb, va - vb, acc_a - acc_b}, t_switch);
  shear_[0].update(s.storey_force[0], s.t);
  shear_[1].update(s.storey_force[1], s.t);
  v_[0].update(va, s.t);
  v_[1].update(vb, s.t);
  a_abs_[0].update(a_abs_a, s.t);
  a_abs_[1].update(a_abs_b, s.t);
  // The link force reaches a new largest value where the link starts to slip: at the located
  // switch.
  link_force_.update(force, std::isnan(t_switch) ? s.t : t_switch);
  // While stuck, the force is the smooth stick force: refine its peaks between samples (the
  // largest stick force is the threshold below which the link would have slipped).
  if (phase.phase == Phase::stick) {
    stuck_force_.update(force, s.t);
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
