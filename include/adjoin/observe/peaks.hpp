#pragma once
// Peak absolute values of the response and the times they occur (first occurrence).
#include "adjoin/observe/observer.hpp"

namespace adjoin {

struct Peak {
  double max_abs = 0.0;
  double t = 0.0;
  void update(double value, double time) {
    const double a = value < 0.0 ? -value : value;
    if (a > max_abs) { max_abs = a; t = time; }
  }
};

struct Peaks {
  Peak x1, x2, v1, v2, a1, a2, f1, f2, q, ag;
  Peak drift;  // |x1 - x2|, the damper's stroke
};

class PeakObserver final : public Observer {
 public:
  void begin(const RunInfo&) override { peaks_ = Peaks{}; }
  void observe(const State& s) override;
  const Peaks& peaks() const { return peaks_; }

 private:
  Peaks peaks_;
};

}  // namespace adjoin
