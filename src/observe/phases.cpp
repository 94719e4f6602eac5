#include "adjoin/observe/phases.hpp"

namespace adjoin {

const char* to_string(Phase phase) {
  switch (phase) {
    case Phase::stick: return "stick";
    case Phase::slip_right: return "slip_right";
    case Phase::slip_left: return "slip_left";
  }
  return "?";
}

void PhaseObserver::observe(const State& s) {
  if (intervals_.empty() || intervals_.back().state != s.phase) {
    if (!intervals_.empty()) intervals_.back().t_end = s.t;
    intervals_.push_back(PhaseInterval{s.phase, s.t, s.t});
  } else {
    intervals_.back().t_end = s.t;
  }
}

}  // namespace adjoin
