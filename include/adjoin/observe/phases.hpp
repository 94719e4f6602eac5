#pragma once
// The damper's phase intervals (stick, slip right, slip left) and their switching instants.
//
// On a grid, a phase that the solver assigns to t_m starts an interval at t_m; the previous
// interval ends there. Schemes that locate switching instants inside a step report them
// through State::t of the sample where the phase changes (see the scheme's documentation).
#include <vector>

#include "adjoin/structure/observer.hpp"

namespace adjoin {

struct PhaseInterval {
  Phase state = Phase::stick;
  double t_start = 0.0;
  double t_end = 0.0;
};

class PhaseObserver final : public Observer {
 public:
  void begin(const RunInfo&) override { intervals_.clear(); }
  void observe(const State& s) override;
  const std::vector<PhaseInterval>& intervals() const { return intervals_; }
  // Number of phase changes (intervals - 1).
  std::size_t switches() const { return intervals_.empty() ? 0 : intervals_.size() - 1; }

 private:
  std::vector<PhaseInterval> intervals_;
};

}  // namespace adjoin
