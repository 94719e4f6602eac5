#include "adjoin/observe/phases.hpp"

#include <cmath>

namespace adjoin {

void PhaseObserver::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  phase_.begin(s, o);
  intervals_.clear();
}

void PhaseObserver::change(const StructureState& s, const PairPhase& phase) {
  const double t = std::isnan(phase.t_switch) || intervals_.empty() ? s.t : phase.t_switch;
  if (!intervals_.empty()) intervals_.back().t_end = t;
  intervals_.push_back(PhaseInterval{phase.phase, t, s.t});
}

}  // namespace adjoin
