#pragma once
// The two-block entry point of the solver:
//
//     SolverSummary summary = simulate_as_structure(options, model, ground, observer);
//
// integrates the model of SPEC §1 from rest at t = 0 to options.t_end on the grid
// t_m = m h, and reports every grid point to `observer` as it goes. The model and the
// options must be valid (IsValid); an invalid one is an InputError.
//
// Numerical trouble (a non-finite value, an explicit scheme beyond its stability bound)
// throws NumericalError with the time and what to change; no non-finite value is ever
// passed to an observer.
//
// Every scheme is a stepper driven by the same time loop (src/solver/time_loop.hpp), so the
// observer sees the same order whichever runs: begin once, the grid points t_0..t_N in order
// (a step's impacts just before its state), end once; a throw ends the run without end().
// SolverSummary::wall_seconds is the loop's: the scheme's set-up (weights) included.
//
// The solver never reads files and never prints.
#include <cstddef>
#include <string>

#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/structure/parameters.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/solver/options.hpp"

namespace adjoin {

// SolverSummary: solver/options.hpp. The run is reported as the model's 1 + 1 structure's
// states (structure/two_block.hpp two_block_structure(model), in its dimensionless units), so
// that the observers of any structure watch it: the implicit schemes' states as the structure
// stepper makes them, the paper scheme's made the same way (its damper as link 1, its phase as
// link 1's; without a damper the observers see no link). begin() is told the options with locate_switches as given
// for the implicit schemes, false for the paper scheme (it does not locate its switches).
SolverSummary simulate_as_structure(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                                    StructureObserver& observer);
// The same run given the model's 1 + 1 structure in its dimensionless units (a run
// description's, study/run_spec.hpp); any other structure is an InputError saying what it has
// that the model has not (structure/two_block.hpp two_block_model()).
SolverSummary simulate_as_structure(const SolverOptions& options, const structure::Structure& structure,
                                    const GroundMotion& ground, StructureObserver& observer);

// An upper bound of the memory simulate_as_structure() will hold (SolverSummary::history_bytes:
// the rods' history engines, which grow with the number of steps), known before the run, so
// that a run too large for the machine can be refused up front rather than fail after minutes.
double estimated_history_bytes(const SolverOptions& options, const Model& model);
double estimated_history_bytes(const SolverOptions& options, const structure::Structure& structure);

// The machine's physical memory in bytes (0 if unknown).
double physical_memory_bytes();

// The rule every run is held to before it starts (two-block and building runs alike): what it
// will hold must fit in 80 % of the machine's physical memory. Returns "" when it fits (or the
// memory is unknown), else the reason, "would need about 12.3 GB of memory (WHAT), more than
// the 6.4 GB this machine can give (80 % of 8 GB)", for the caller to put after what is refused.
std::string memory_problem(double need_bytes, const std::string& what);

}  // namespace adjoin
