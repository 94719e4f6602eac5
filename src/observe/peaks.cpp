#include "adjoin/observe/peaks.hpp"

namespace adjoin {

void PeakObserver::begin(const RunInfo&) {
  peaks_ = Peaks{};
  for (SmoothPeak* p : {&x1_, &x2_, &f1_, &f2_, &drift_}) p->reset();
}

void PeakObserver::observe(const State& s) {
  x1_.update(s.x1, s.t);
  x2_.update(s.x2, s.t);
  f1_.update(s.f1, s.t);
  f2_.update(s.f2, s.t);
  drift_.update(s.x1 - s.x2, s.t);
  peaks_.x1 = x1_.peak();
  peaks_.x2 = x2_.peak();
  peaks_.f1 = f1_.peak();
  peaks_.f2 = f2_.peak();
  peaks_.drift = drift_.peak();
  peaks_.v1.update(s.v1, s.t);
  peaks_.v2.update(s.v2, s.t);
  peaks_.a1.update(s.a1, s.t);
  peaks_.a2.update(s.a2, s.t);
  peaks_.q.update(s.q, s.t);
  peaks_.ag.update(s.ag, s.t);
}

}  // namespace adjoin
