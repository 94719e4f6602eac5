#include "adjoin/observe/pounding.hpp"

#include "adjoin/observe/extremum.hpp"

namespace adjoin {

void PoundingObserver::begin(const RunInfo& info) {
  gap0_ = info.model.gap0;
  started_ = false;
  samples_ = 0;
  margin_ = PoundingMargin{};
}

void PoundingObserver::observe(const State& s) {
  const double gap = gap0_ + s.x2 - s.x1;
  // A local minimum at the previous sample: refine it between samples (extremum.hpp).
  if (samples_ >= 2 && previous_gap_ <= before_previous_gap_ && previous_gap_ < gap &&
      previous_gap_ <= margin_.min_gap) {
    const Vertex v = parabola_vertex(previous_t_, s.t - previous_t_, before_previous_gap_, previous_gap_, gap);
    if (v.y <= margin_.min_gap) {
      margin_.min_gap = v.y;
      margin_.t_min_gap = v.t;
    }
  }
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
  before_previous_gap_ = previous_gap_;
  previous_gap_ = gap;
  previous_t_ = s.t;
  started_ = true;
  ++samples_;
}

}  // namespace adjoin
