#include "adjoin/observe/phases.hpp"

#include <cmath>

namespace adjoin {

void PhaseObserver::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  phase_.begin(s, o);
  intervals_.clear();
}

void PhaseObserver::observe(const StructureState& s, const PairPhase& phase) {
  const Phase now = phase.phase;
  if (intervals_.empty() || intervals_.back().state != now) {
    const double t = std::isnan(phase.t_switch) || intervals_.empty() ? s.t : phase.t_switch;
    if (!intervals_.empty()) intervals_.back().t_end = t;
    intervals_.push_back(PhaseInterval{now, t, s.t});
  } else {
    intervals_.back().t_end = s.t;
  }
}

}  // namespace adjoin
