#pragma once
// What the solver reports at each grid point t_m = m h, in dimensionless units.
#include <limits>
#include <string>

namespace adjoin {

enum class Phase { stick, slip_right, slip_left };

// "stick", "slip_right", "slip_left" (the words of SPEC §3).
const char* to_string(Phase phase);

struct State {
  double t = 0.0;
  double x1 = 0.0, x2 = 0.0;  // displacements relative to the base
  double v1 = 0.0, v2 = 0.0;  // velocities relative to the base
  double a1 = 0.0, a2 = 0.0;  // absolute accelerations x'' + u'' = x'' - a_g
  double f1 = 0.0, f2 = 0.0;  // rod forces
  double q = 0.0;             // damper force
  double ag = 0.0;            // forcing a_g = -u''
  // The damper's phase: implicit schemes give the phase over the step that ends at t; the
  // paper scheme the phase it decided at t for the step that starts there.
  Phase phase = Phase::stick;
  // If the phase changed during the step that ends at t and the scheme located the switch:
  // its time (t - 2h < t_switch <= t: the onset that ends a stick shorter than a step, which
  // began in the step before, may lie there). Otherwise NaN: the switch is taken at t.
  double t_switch = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace adjoin
