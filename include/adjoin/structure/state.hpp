#pragma once
// What the solver reports at each grid point t_m = m h: StructureState, in the structure's
// units (SI; a two-block scene's 1 + 1 structure, structure/two_block.hpp, in its
// dimensionless ones), and each impact of a contact pair.
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "adjoin/core/enum_names.hpp"  // Phase: "stick", "slip_right", "slip_left" (the words of SPEC §3)

namespace adjoin {

// One impact of a contact pair, from the first touch (located inside its step) to separation.
// In the structure's units, like StructureState.
struct Impact {
  int contact = 0;                 // 0-based contact index
  double start = 0.0;              // first touch [s]
  double duration = 0.0;           // [s] (0 for the Newton law)
  double force_max = 0.0;          // [N] (0 for the Newton law)
  double t_force_max = 0.0;        // [s]
  double penetration_max = 0.0;    // [m] (0 for the Newton law)
  double approach_speed = 0.0;     // closing speed at first touch [m/s]
  double rebound_speed = 0.0;      // opening speed at separation [m/s]
  double impulse = 0.0;            // integral of the force [N s]
  bool complete = true;            // false: still in contact at the end of the run
};

struct StructureState {
  double t = 0.0;
  double ag = 0.0;                 // a_g = -(ground acceleration) [m/s^2]
  Eigen::VectorXd x, v, a_abs;     // per floor, A's floors first then B's [m, m/s, m/s^2]
  // Per link [N], acting -q on A's floor, +q on B's; after the links, per ground slider
  // (Structure::ground_sliders(): an isolated base's, a base friction's) its force, acting -q
  // on its dof, and its stroke and velocity (the dof's), phase and switch likewise.
  Eigen::VectorXd link_force;
  Eigen::VectorXd link_stroke;     // x_A,i - x_B,j [m]
  Eigen::VectorXd link_velocity;   // [m/s]
  std::vector<Phase> link_phase;   // friction links: stick or slip direction (others: slip_*)
  std::vector<double> link_switch; // the located switch inside the step ending here, or NaN
  Eigen::VectorXd storey_force;    // per storey, A's then B's: spring + devices (its shear) [N]
  // Per storey, A's then B's: its bilinear law's hysteretic variable z [m] (SPEC §7; 0 for an
  // elastic storey), and the instant it yielded inside the step ending here (located), or NaN.
  Eigen::VectorXd hyst;
  std::vector<double> hyst_yield;
  // Per contact pair: its gap g = gap - s [m] (negative: the floors overlap), its force at the
  // grid point [N] (compressive > 0; 0 for the Newton law, whose impacts are impulses), and,
  // accumulated from t = 0, the work the floors have done on it [J] (its stored elastic
  // energy plus what it dissipated) and the part dissipated [J].
  Eigen::VectorXd contact_gap, contact_force, contact_work, contact_dissipated;
};

}  // namespace adjoin
