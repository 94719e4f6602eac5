#pragma once
// Time integration of a structure (structure/building.hpp): buildings of any number of
// storeys with springs, dashpots, fractional Zener devices and inherent damping, joined by
// links (friction, dashpot, spring, Zener), on a moving ground. SPEC §5:
//
//     M x'' + C x' + (storey forces) + (link forces) = M 1 a_g,   x relative to the ground.
//
// The step is the `implicit` scheme's, for vectors: trapezoidal mechanics at velocity level;
// each Zener element implicit through its BDF2 convolution-quadrature weight (an effective
// stiffness, so the step matrix A = M + h/2 C + h^2/4 K_eff is constant and factorised once);
// the friction dampers' step forces Q from the box-constrained QP of their Delassus matrix
// S = h B A^-1 B' (solver/box_qp: exact stick, no regularisation). Second order where the
// dampers do not switch. As the implicit schemes have it, the step after a damper's switch
// is taken with backward-Euler mechanics (A = M + h C + h^2 K_eff, also factorised once) when
// the structure's stiffest mode is not resolved by the step, h omega_max > 1: trapezoidal
// mechanics passes such a mode undamped, so what a switch excites rings on and drives the
// dampers through spurious switches; one backward-Euler step damps it by
// 1/sqrt(1 + (omega h)^2) and keeps the step second order (StructureSolverOptions::restart).
//
// Reported at each grid point: displacements, velocities, absolute accelerations, and per
// link its force, stroke (s = x_A,i - x_B,j) and velocity; a friction link's force is its
// value at the grid point (the force that keeps a stuck damper stuck, +-F when slipping), and
// a switch is located inside the step (a slip's end on
// the parabola of the link's grid velocities, an onset on the parabola of its grid stuck
// forces), with the velocity kink at a slip's end integrated exactly.
//
// Cost per step: one product with [A^-1; C A^-1] per building (A and C are block diagonal when
// only friction links join the buildings), O(n_b^2) since modal damping makes C dense (O(n_b^2)
// also for Rayleigh or none: A^-1 is dense); everything else is O(n) (the stiffness is a band
// plus the links' entries) or O(dampers^2); a step allocates nothing. Plus each Zener
// element's history push. The products and the passes over the floors use AVX where the
// processor has it, with the same results bit for bit. The two-block scenes' implicit schemes
// ("implicit", "implicit-damped", "implicit-gl") are this stepper on the 1 + 1 structure
// (solver/simulate.hpp); only the paper's explicit scheme has a stepper of its own.
//
// Inside (src/solver/): structure_model.hpp holds what is constant through a run (the
// assembly, the factorised step matrices, the indexing, the restart rule), structure_workspace
// .hpp what a step changes (the state, the Zener histories, the work vectors), and
// structure_solver.cpp the step in its phases (predict, the dampers' and contacts' local
// solve, correct, locate the switches, report).
#include <Eigen/Dense>
#include <cstddef>
#include <limits>
#include <vector>

#include "adjoin/fractional/history.hpp"
#include "adjoin/solver/options.hpp"
#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/structure/state.hpp"
#include "adjoin/structure/building.hpp"

namespace adjoin {

struct StructureSolverOptions {
  double h = 0.001;     // s
  double t_end = 10.0;  // s
  HistoryEngine history = HistoryEngine::soe;
  // The scheme a run takes (solver/options.hpp): implicit, implicit-damped (restart always),
  // implicit-gl (Grünwald–Letnikov weights) on this stepper; paper (two-block runs only, its
  // own stepper: solver/simulate.hpp). with_scheme() sets restart and quadrature to match.
  Scheme scheme = Scheme::implicit;
  // Two-block runs (solver/simulate.hpp SolverOptions): the located switches, the explicit
  // scheme's stability check.
  bool locate_switches = true;
  bool stability_check = true;
  double history_tolerance = 1e-12;  // soe: the largest relative error of the weights
  // The state at t = 0 (empty: at rest). Free vibration and impact tests start from these; an
  // initial displacement needs a structure without Zener elements and friction links (their
  // state at t = 0 is relaxed and stuck at zero deformation).
  Eigen::VectorXd x0, v0;
  // The backward-Euler step after a damper's switch: `automatic` when the stiffest mode is not
  // resolved (h omega_max > 1, the `implicit` scheme's rule), `always` after every switch (the
  // `implicit-damped` rule), `never` (trapezoidal throughout: for comparisons).
  enum class Restart { automatic, always, never };
  Restart restart = Restart::automatic;
  // The Zener elements' convolution quadrature: BDF2 (second order, the `implicit` schemes'),
  // or the first-order Grünwald–Letnikov weights (the `implicit-gl` scheme's).
  enum class Quadrature { bdf2, grunwald_letnikov };
  Quadrature quadrature = Quadrature::bdf2;
  // A structure of one floor per building joined by one friction damper (the two-block
  // scenes' 1 + 1 structure) is stepped by a step written for it, with the general step's
  // arithmetic (the same results bit for bit) at a third of its cost; false: the general step
  // (tests compare the two).
  bool pair_step = true;
  std::size_t steps() const;
  bool IsValid(std::string* error) const;
};

// `o` with `scheme` and the restart rule and weights it takes.
StructureSolverOptions with_scheme(StructureSolverOptions o, Scheme scheme);

// The solver.scheme these options run, for summaries: "implicit-damped" restarts after every
// switch, "implicit" by the automatic rule.
inline const char* scheme_name(const StructureSolverOptions& o) {
  if (o.quadrature == StructureSolverOptions::Quadrature::grunwald_letnikov) return "implicit-gl";
  return o.restart == StructureSolverOptions::Restart::always ? "implicit-damped"
         : o.restart == StructureSolverOptions::Restart::never ? "implicit (no restart)" : "implicit";
}

// `ground` gives a_g in g against time in seconds (a scene's ground with unit scales). The
// summary's scheme is scheme_name(options).
SolverSummary simulate_structure(const StructureSolverOptions& options, const structure::Structure& s,
                                 const GroundMotion& ground, StructureObserver& observer);

// Whether a run with these options takes the backward-Euler step after a damper's switch
// (Restart::automatic resolved as the run resolves it, h omega_max > 1; always: if the
// structure has a friction link). A run at another step can then be told to take the same
// scheme (Restart::always or never): the error estimate's companion at 2h must integrate
// with the method of the run it estimates, or Richardson compares two different schemes.
bool takes_restarts(const StructureSolverOptions& options, const structure::Structure& s, const GroundMotion& ground);

}  // namespace adjoin
