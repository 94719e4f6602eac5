#pragma once
// Peak absolute values of the response and the times they occur (first occurrence).
//
// Displacements and the damper stroke are refined between samples from their derivatives (the
// velocities), with the damper's located switching instants as kinks (step_extremum in
// observe/extremum.hpp), so their peaks and times are second order even where a peak sits on a
// switch. Rod forces are refined by the cubic through the four samples around a local
// maximum of |y| (observe/extremum.hpp cubic_extremum). Velocities and accelerations have kinks or jumps at phase changes; their
// peaks are the largest samples. q is refined by a parabola while stuck (the stick force is
// smooth), and its time is the located switch where it reaches its limit.
#include <cmath>

#include "adjoin/observe/extremum.hpp"
#include "adjoin/structure/observer.hpp"

namespace adjoin {

struct Peak {
  double max_abs = 0.0;
  double t = 0.0;
  // Ties go to the first time: a value must exceed the peak by more than rounding (1e-12
  // relative) to move it, so a plateau (a stuck damper's constant stroke) keeps its start.
  void update(double value, double time) {
    const double a = value < 0.0 ? -value : value;
    if (a > max_abs * (1.0 + 1e-12)) { max_abs = a; t = time; }
  }
};

// A peak of a smooth signal, refined between samples. Feed samples in order.
class SmoothPeak {
 public:
  void reset() { *this = SmoothPeak{}; }
  void update(double value, double time) {
    const double a = value < 0.0 ? -value : value;
    if (count_ >= 2 && a1_ >= a0_ && a1_ > a && a1_ >= peak_.max_abs) {
      // |y| has a local maximum at the middle sample; refine on the signed samples: the cubic
      // through it, the two before and the new one (time O(h^3)), or with only three samples
      // the parabola.
      const double h = time - t1_;
      const Vertex v = count_ >= 3 ? cubic_extremum(t1_ - 2.0 * h, h, ym_, y0_, y1_, value)
                                   : parabola_vertex(t1_, h, y0_, y1_, value);
      const double refined = v.y < 0.0 ? -v.y : v.y;
      if (refined >= a1_) { peak_.max_abs = refined; peak_.t = v.t; }
    }
    peak_.update(value, time);
    ym_ = y0_;
    y0_ = y1_; a0_ = a1_;
    y1_ = value; a1_ = a; t1_ = time;
    ++count_;
  }
  const Peak& peak() const { return peak_; }

 private:
  Peak peak_;
  double ym_ = 0.0, y0_ = 0.0, y1_ = 0.0, a0_ = 0.0, a1_ = 0.0, t1_ = 0.0;
  int count_ = 0;
};

// A peak of |y| for a signal whose derivative is sampled too (Sample), refined in each step
// where the derivative changes sign; `t_kink` is the located switch inside the step that ends
// at the sample (NaN if none).
class DerivativePeak {
 public:
  void reset() { *this = DerivativePeak{}; }
  void update(const Sample& s, double t_kink) {
    if (have_ && previous_.dy != 0.0 && previous_.dy * s.dy <= 0.0) {
      if (s.dy == 0.0 && std::isfinite(t_kink)) {
        // The signal stops at the kink (the damper sticks: a plateau from t_kink on). The
        // plateau's value is the sample's, its start the kink.
        peak_.update(s.y, t_kink);
        previous_ = s;
        return;
      }
      const Vertex v = step_extremum(previous_, s, t_kink);
      const double refined = std::abs(v.y);
      if (refined >= std::abs(previous_.y) && refined >= std::abs(s.y)) peak_.update(v.y, v.t);
    }
    peak_.update(s.y, s.t);
    previous_ = s;
    have_ = true;
  }
  const Peak& peak() const { return peak_; }

 private:
  Peak peak_;
  Sample previous_{};
  bool have_ = false;
};

struct Peaks {
  Peak x1, x2, v1, v2, a1, a2, f1, f2, q, ag;
  Peak drift;  // |x1 - x2|, the damper's stroke
};

class PeakObserver final : public Observer {
 public:
  void begin(const RunInfo&) override;
  void observe(const State& s) override;
  const Peaks& peaks() const;

 private:
  // The refined peaks (x1, x2, f1, f2, drift) are the trackers' own and copied in only when
  // peaks() is asked, not at every step; the others are kept here.
  mutable Peaks peaks_;
  SmoothPeak f1_, f2_, stuck_q_;
  DerivativePeak x1_, x2_, drift_;
};

}  // namespace adjoin
