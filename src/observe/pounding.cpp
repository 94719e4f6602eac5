#include "adjoin/observe/pounding.hpp"

namespace adjoin {

void PoundingObserver::begin(const RunInfo& info) {
  gap0_ = info.model.gap0;
  started_ = false;
  margin_ = PoundingMargin{};
}

void PoundingObserver::observe(const State& s) {
  const double gap = gap0_ + s.x2 - s.x1;
  if (!started_ || gap < margin_.min_gap) {
    margin_.min_gap = gap;
    margin_.t_min_gap = s.t;
  }
  if (!margin_.contact && gap <= 0.0) {
    margin_.contact = true;
    double t = s.t;
    if (started_ && previous_gap_ > 0.0)
      t = previous_t_ + (s.t - previous_t_) * previous_gap_ / (previous_gap_ - gap);
    margin_.t_first_contact = t;
  }
  previous_gap_ = gap;
  previous_t_ = s.t;
  started_ = true;
}

}  // namespace adjoin
