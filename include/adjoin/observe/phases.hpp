#pragma once
// The damper's phase intervals (stick, slip right, slip left) and their switching instants.
//
// On a grid, a phase that the solver assigns to t_m starts an interval at t_m; the previous
// interval ends there. Schemes that locate switching instants inside a step report them
// through the switch time of the sample where the phase changes (see the scheme's
// documentation).
#include <vector>

#include "adjoin/observe/pair_phase.hpp"
#include "adjoin/structure/observer.hpp"

namespace adjoin {

struct PhaseInterval {
  Phase state = Phase::stick;
  double t_start = 0.0;
  double t_end = 0.0;
};

// Of a run of the 1 + 1 structure (structure/two_block.hpp): link 1's phases, or without a link
// the sign of the floors' relative velocity (observe/pair_phase.hpp).
class PhaseObserver final : public StructureObserver {
 public:
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& s) override { phase_.update(s); observe(s, phase_); }
  // The same with the phase at s given (the report's observers share one PairPhase). Inline:
  // at almost every sample the phase goes on and only the last interval's end moves, a few
  // instructions against about twenty for the call and its frame; a change goes out of line.
  void observe(const StructureState& s, const PairPhase& phase) {
    if (!intervals_.empty() && intervals_.back().state == phase.phase) {
      intervals_.back().t_end = s.t;
      return;
    }
    change(s, phase);
  }
  const std::vector<PhaseInterval>& intervals() const { return intervals_; }
  // Number of phase changes (intervals - 1).
  std::size_t switches() const { return intervals_.empty() ? 0 : intervals_.size() - 1; }

 private:
  // A new interval from s (the first, or the phase changed at s).
  void change(const StructureState& s, const PairPhase& phase);
  PairPhase phase_;
  std::vector<PhaseInterval> intervals_;
};

}  // namespace adjoin
