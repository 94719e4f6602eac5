#pragma once
// Peak absolute values of the response and the times they occur (first occurrence).
//
// Displacements, rod forces and the damper stroke are smooth, so their peaks are refined
// between samples by a parabola through the three samples around a local maximum of |y|
// (observe/extremum.hpp). Velocities, accelerations and q have kinks or jumps at phase
// changes; their peaks are the largest samples.
#include "adjoin/observe/extremum.hpp"
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

// A peak of a smooth signal, refined between samples. Feed samples in order.
class SmoothPeak {
 public:
  void reset() { *this = SmoothPeak{}; }
  void update(double value, double time) {
    const double a = value < 0.0 ? -value : value;
    if (count_ >= 2 && a1_ >= a0_ && a1_ > a && a1_ >= peak_.max_abs) {
      // |y| has a local maximum at the middle sample; refine on the signed samples.
      const Vertex v = parabola_vertex(t1_, time - t1_, y0_, y1_, value);
      const double refined = v.y < 0.0 ? -v.y : v.y;
      if (refined >= a1_) { peak_.max_abs = refined; peak_.t = v.t; }
    }
    peak_.update(value, time);
    y0_ = y1_; a0_ = a1_;
    y1_ = value; a1_ = a; t1_ = time;
    ++count_;
  }
  const Peak& peak() const { return peak_; }

 private:
  Peak peak_;
  double y0_ = 0.0, y1_ = 0.0, a0_ = 0.0, a1_ = 0.0, t1_ = 0.0;
  int count_ = 0;
};

struct Peaks {
  Peak x1, x2, v1, v2, a1, a2, f1, f2, q, ag;
  Peak drift;  // |x1 - x2|, the damper's stroke
};

class PeakObserver final : public Observer {
 public:
  void begin(const RunInfo&) override;
  void observe(const State& s) override;
  const Peaks& peaks() const { return peaks_; }

 private:
  Peaks peaks_;
  SmoothPeak x1_, x2_, f1_, f2_, drift_;
};

}  // namespace adjoin
