#pragma once
// The phase of a run of the 1 + 1 structure (structure/two_block.hpp) at each grid point, as the
// two-block observers read it: link 1's phase and its located switch when the structure has a
// link; without one the sign of the floors' relative velocity v_A - v_B, a change located where
// it crosses zero (linear interpolation, second order; not in the first step, which starts from
// rest). Switches are located only when the run asks (StructureSolverOptions::locate_switches);
// otherwise t_switch stays NaN and a switch is taken at the grid point.
#include <algorithm>
#include <cstddef>
#include <limits>

#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/structure/state.hpp"

namespace adjoin {

class PairPhase {
 public:
  void begin(const structure::Structure& s, const StructureSolverOptions& o) {
    *this = PairPhase{};
    link_ = !s.links.empty();
    locate_ = o.locate_switches;
  }
  void update(const StructureState& s) {
    t_switch = std::numeric_limits<double>::quiet_NaN();
    if (link_) {
      phase = s.link_phase[0];
      if (locate_) t_switch = s.link_switch[0];
      return;
    }
    const double w = s.v[0] - s.v[1];
    const Phase now = w > 0.0 ? Phase::slip_right : (w < 0.0 ? Phase::slip_left : Phase::stick);
    if (locate_ && points_ >= 2 && now != phase && w_ != w)
      t_switch = t_previous_ + std::clamp(w_ / (w_ - w), 0.0, 1.0) * (s.t - t_previous_);
    phase = now;
    w_ = w;
    t_previous_ = s.t;
    ++points_;
  }
  Phase phase = Phase::stick;
  double t_switch = std::numeric_limits<double>::quiet_NaN();

 private:
  bool link_ = false, locate_ = true;
  double w_ = 0.0, t_previous_ = 0.0;
  std::size_t points_ = 0;
};

}  // namespace adjoin
