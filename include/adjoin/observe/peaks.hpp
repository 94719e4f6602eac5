#pragma once
// Peak absolute values of the response and the times they occur (first occurrence).
//
// Displacements and the link's stroke are refined between samples from their derivatives (the
// velocities), with the friction link's located switching instants as kinks (step_extremum in
// observe/extremum.hpp), so their peaks and times are second order even where a peak sits on a
// switch. Storey forces are refined by the cubic through the four samples around a local
// maximum of |y| (observe/extremum.hpp cubic_extremum). Velocities and accelerations have kinks
// or jumps at phase changes; their peaks are the largest samples. The link force is refined by
// a parabola while stuck (the stick force is smooth), and its time is the located switch where
// it reaches its limit.
#include <cmath>
#include <string>
#include <vector>

#include "adjoin/observe/extremum.hpp"
#include "adjoin/observe/pair_phase.hpp"
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

// A channel's peak (its name as structure/channels.hpp names it).
struct ChannelPeak {
  std::string channel;
  Peak peak;
};

// The peak of `channel` in `peaks`, or a zero peak if none has that name.
inline Peak find_peak(const std::vector<ChannelPeak>& peaks, const std::string& channel) {
  for (const ChannelPeak& p : peaks)
    if (p.channel == channel) return p.peak;
  return Peak{};
}

// The peaks of a run of the 1 + 1 structure (the two blocks, structure/two_block.hpp), refined
// as the paper's values need: named by the structure's channels A.x1, B.x1 (floors),
// link1.stroke (x_A1 - x_B1), A.shear1, B.shear1 (storey forces), link1.force, and sampled
// A.v1, B.v1 (velocities), A.a1_abs, B.a1_abs, ag. Building A's values are index 0, B's 1.
class PeakObserver final : public StructureObserver {
 public:
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& s) override { phase_.update(s); observe(s, phase_); }
  // The same with link 1's phase at s given (the report's observers share one PairPhase).
  void observe(const StructureState& s, const PairPhase& phase);
  // In the order above (the refined ones first).
  std::vector<ChannelPeak> peaks() const;

 private:
  PairPhase phase_;  // link 1's phase and located switch (the kinks)
  bool link_ = false;
  SmoothPeak shear_[2], stuck_force_;
  DerivativePeak x_[2], stroke_;
  Peak link_force_, v_[2], a_abs_[2], ag_;
};

}  // namespace adjoin
