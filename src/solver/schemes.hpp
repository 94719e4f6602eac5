#pragma once
// The schemes behind simulate() (internal). Each integrates from rest over the grid of
// `options` and reports every grid point to `observer`.
#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/model/parameters.hpp"
#include "adjoin/observe/observer.hpp"
#include "adjoin/solver/options.hpp"

namespace adjoin::detail {

// Each returns the bytes its history engines held (for the memory benchmarks).
std::size_t run_paper_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                      Observer& observer);

// "implicit", "implicit-damped" and "implicit-gl".
std::size_t run_implicit_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                         Observer& observer);

// A model with a contact law (model.contact): the two blocks as a structure on the structure
// solver ("implicit" only), reported as two-block States.
std::size_t run_two_block_contact(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                                  Observer& observer);

// The friction force a stuck damper must carry: q = (rho f2 - f1) / (rho + 1).
inline double stick_force(const Model& model, double f1, double f2) {
  return (model.rho * f2 - f1) / (model.rho + 1.0);
}

}  // namespace adjoin::detail
