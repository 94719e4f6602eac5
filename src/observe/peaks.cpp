#include "adjoin/observe/peaks.hpp"

namespace adjoin {

void PeakObserver::observe(const State& s) {
  peaks_.x1.update(s.x1, s.t);
  peaks_.x2.update(s.x2, s.t);
  peaks_.v1.update(s.v1, s.t);
  peaks_.v2.update(s.v2, s.t);
  peaks_.a1.update(s.a1, s.t);
  peaks_.a2.update(s.a2, s.t);
  peaks_.f1.update(s.f1, s.t);
  peaks_.f2.update(s.f2, s.t);
  peaks_.q.update(s.q, s.t);
  peaks_.ag.update(s.ag, s.t);
  peaks_.drift.update(s.x1 - s.x2, s.t);
}

}  // namespace adjoin
