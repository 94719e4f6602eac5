#pragma once
// The schemes behind simulate_as_structure() (internal). Each is a stepper (time_loop.hpp) private to its
// source file; these run it through the one time loop, from rest over the grid of `options`,
// reporting every grid point to `observer`.
#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/structure/parameters.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/solver/options.hpp"
#include "time_loop.hpp"

namespace adjoin::detail {

// Each returns the loop's result: steps, wall time, and the bytes its history engines held
// (for the memory benchmarks).
SolverSummary run_paper_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                               StructureObserver& observer);

// "implicit", "implicit-damped" and "implicit-gl", with or without a contact law: the two blocks
// as a structure on the structure solver, reported as its states (a contact law's energy
// checked first).
// `structure`: a model's 1 + 1 structure (structure/two_block.hpp).
SolverSummary run_two_block_on_structure(const SolverOptions& options, const structure::Structure& structure,
                                         const GroundMotion& ground, StructureObserver& observer);

// The friction force a stuck damper must carry: q = (rho f2 - f1) / (rho + 1).
inline double stick_force(const Model& model, double f1, double f2) {
  return (model.rho * f2 - f1) / (model.rho + 1.0);
}

}  // namespace adjoin::detail
