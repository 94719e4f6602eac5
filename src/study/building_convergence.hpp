#pragma once
// Convergence of a building run (SPEC §5) on a ladder of steps: every reported quantity's error
// against a much finer run, with its observed order, in the table `adjoin converge` prints
// and writes for two-block scenes (study/convergence.hpp's ConvergenceResult); run_convergence
// calls it for a building.
//
// The ladder is the spec's h times 4, 2, 1, 1/2, 1/4 unless steps are given (each must divide
// the largest an integer number of times); the reference is the structure step at
// reference_factor times the smallest step, with fft history (direct if asked for alone).
// Errors:
//  - error: the trajectory error, max over the coarsest grid's points and every floor of
//    |x - x_ref|, divided by max |x_ref|;
//  - quantities: each channel's peak (relative) and, for the peaks refined between samples
//    (structure/channels.hpp PeakRule::refined), its time (absolute, s); each link's largest
//    force and stroke and, for friction links, the dissipated energy and each switching instant
//    (when the run switches as often as the reference; otherwise switches_differ); each contact
//    pair's smallest gap and its time. The energy balance's residual (relative to the input)
//    is listed as it is: it is itself an error, and tends to 0 at the step's order.
// h and instants are in seconds. Errors of a zero reference value are absolute.
#include <string>
#include <vector>

#include "adjoin/study/convergence.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin::detail {

// `options` valid, its schemes and engines given (run_convergence fills the defaults).
ConvergenceResult building_convergence(const RunSpec& spec, const ConvergenceOptions& options);

}  // namespace adjoin::detail
