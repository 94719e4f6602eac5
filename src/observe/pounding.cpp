#include "adjoin/observe/pounding.hpp"

#include <algorithm>
#include <cmath>

#include "adjoin/observe/extremum.hpp"

namespace adjoin {

void PoundingObserver::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  phase_.begin(s, o);
  gap0_ = s.contacts.at(0).gap;
  started_ = false;
  sampled_force_max_ = sampled_t_force_max_ = sampled_penetration_ = 0.0;
  margin_ = PoundingMargin{};
  margin_.model = s.contacts.at(0).law.model;
}

void PoundingObserver::impact(const Impact& i) { margin_.impacts.push_back(i); }

void PoundingObserver::end() {
  if (!margin_.has_law()) return;
  if (margin_.impacts.empty()) {
    margin_.force_max = sampled_force_max_;
    margin_.t_force_max = sampled_t_force_max_;
    margin_.penetration_max = margin_.model == structure::ContactModel::impact ? 0.0 : sampled_penetration_;
    return;
  }
  // The impacts' own (located) values, so that the totals agree with impacts.csv.
  margin_.force_max = 0.0;
  margin_.t_force_max = margin_.impacts.front().t_force_max;
  margin_.penetration_max = 0.0;
  for (const Impact& i : margin_.impacts) {
    if (i.force_max > margin_.force_max) {
      margin_.force_max = i.force_max;
      margin_.t_force_max = i.t_force_max;
    }
    margin_.penetration_max = std::max(margin_.penetration_max, i.penetration_max);
    margin_.impulse += i.impulse;
    margin_.impulse_max = std::max(margin_.impulse_max, i.impulse);
  }
  if (margin_.model == structure::ContactModel::impact) {
    // g >= 0 holds exactly: the gap's minimum is the first touch. (The refinement between
    // samples would extrapolate across the velocity jump of the impact to below 0.)
    margin_.min_gap = 0.0;
    margin_.t_min_gap = margin_.impacts.front().start;
  }
  // The first touch, located inside its step (the Newton law never lets the gap below 0).
  margin_.contact = true;
  margin_.t_first_contact = margin_.impacts.front().start;
}

void PoundingObserver::observe(const StructureState& s, const PairPhase& phase) {
  const double t_switch = phase.t_switch;
  const Sample now{s.t, gap0_ + s.x[1] - s.x[0], s.v[1] - s.v[0], s.a_abs[1] - s.a_abs[0]};
  // A minimum inside the step: the gap's derivative (the relative velocity) turns from
  // negative to non-negative; refined from the derivatives, with the located switch as a kink
  // (extremum.hpp).
  bool plateau = false;
  if (started_ && previous_.dy < 0.0 && now.dy >= 0.0) {
    if (now.dy == 0.0 && std::isfinite(t_switch)) {
      // The gap stops closing at the kink (the damper sticks: a plateau from t_switch on).
      // The plateau's value is the sample's, its start the kink.
      if (now.y < margin_.min_gap - 1e-13 * (1.0 + std::abs(margin_.min_gap))) {
        margin_.min_gap = now.y;
        margin_.t_min_gap = t_switch;
      }
      plateau = true;
    } else if (const Vertex v = step_extremum(previous_, now, t_switch);
               v.y < margin_.min_gap && v.y <= previous_.y && v.y <= now.y) {
      margin_.min_gap = v.y;
      margin_.t_min_gap = v.t;
    }
  }
  // A sample below the minimum; a stuck, constant gap does not move its time (ties go to the
  // first time the minimum was reached).
  if (!started_ || (!plateau && now.y < margin_.min_gap - 1e-13 * (1.0 + std::abs(margin_.min_gap)))) {
    margin_.min_gap = now.y;
    margin_.t_min_gap = s.t;
  }
  if (!margin_.contact && now.y <= 0.0) {
    margin_.contact = true;
    double t = s.t;
    if (started_ && previous_.y > 0.0) t = previous_.t + (s.t - previous_.t) * previous_.y / (previous_.y - now.y);
    margin_.t_first_contact = t;
  }
  if (margin_.has_law()) {
    const double force = s.contact_force[0];
    if (force > sampled_force_max_) {
      sampled_force_max_ = force;
      sampled_t_force_max_ = s.t;
    }
    sampled_penetration_ = std::max(sampled_penetration_, -now.y);
    margin_.dissipated = s.contact_dissipated[0];
  }
  previous_ = now;
  started_ = true;
}

}  // namespace adjoin
