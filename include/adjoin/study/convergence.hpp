#pragma once
// Convergence and work-precision: error against run time for each scheme and history engine
// on a ladder of steps, for any spec.
//
//     ConvergenceResult result = run_convergence(scene, options);
//
// The reference is, in order of preference:
//  - analytic: when the ground is the decaying sine and the problem is linear — no damper
//    (mu = 0), or a damper that the finest run of the default scheme shows stuck throughout
//    (then |q| < mu is checked on the exact solution too) — the exact solution by Laplace
//    inversion (study/linear_reference.hpp);
//  - otherwise a much finer run of the best scheme (implicit, fft history) at
//    reference_factor times smaller than the smallest step of the ladder.
// Errors (all relative, dimensionless):
//  - error: max over the coarsest grid's points of |x1 - x1_ref|, |x2 - x2_ref|, divided by
//    max |x_ref|: a trajectory error in the max norm;
//  - peak_a1, min_gap, friction: relative errors of those summary values (against the fine
//    run; against the exact solution only the trajectory error is given).
// The observed order is log2 of the ratio of successive errors over a halving of h.
//
// Against a finer run, every reported quantity is compared too (ConvergenceRow::quantities),
// by the scene's presentation. A two-block scene's (its 1 + 1 structure's, labelled by channel;
// `adjoin converge` shows them under SPEC §3's names, io/two_block_names.hpp): the peaks of the
// floors A.x1, B.x1, link 1's stroke, the storeys' forces A.shear1, B.shear1 and link 1's force
// with their times, the minimum gap and its time, the friction link's work, its last force
// (final link1.force), and each switching instant (when the run has the
// reference's sequence of phases; otherwise the row says the switches differ). A structure's (SPEC §5): each channel's peak and, for the peaks refined
// between samples (structure/channels.hpp PeakRule::refined), its time; each link's largest
// force and stroke and, for friction links, the dissipated energy and each switching instant
// (when the run switches as often as the reference); each contact pair's smallest gap and its
// time; and the energy balance's residual relative to the input (an error in itself, listed as
// it is). Values are relative errors (absolute against a zero reference), instants absolute;
// each with its observed order.
//
// A structure's ladder runs one scheme, the structure step with the scene's restart rule or
// the one asked for (implicit or implicit-damped); its reference is that step at
// reference_factor times the smallest step, with the fft history (direct if asked for alone),
// and its trajectory error is taken over every floor.
#include <string>
#include <vector>

#include "adjoin/study/run_spec.hpp"

namespace adjoin {

struct ConvergenceOptions {
  // The schemes compared. Empty: a two-block spec's paper, implicit-gl and implicit; a
  // building's own scheme. A building takes one, implicit or implicit-damped (the structure
  // step's two restart rules).
  std::vector<Scheme> schemes;
  // The history engines compared. Empty: direct for a two-block spec, fft for a building.
  std::vector<HistoryEngine> engines;
  // In the spec's time unit (dimensionless for a two-block spec, s for a building); empty: the
  // spec's h times 4, 2, 1, 1/2, 1/4.
  std::vector<double> steps;
  double reference_factor = 8.0;
  bool IsValid(std::string* error) const;
};

struct QuantityError {
  std::string name;     // "peak A.x1", "t peak A.x1", "min gap", "switch 3", ...
  bool instant = false;  // an instant (absolute error in time) rather than a value (relative)
  double error = 0.0;
  double order = 0.0;    // NaN for the first rung or when the previous rung lacks it
};

struct ConvergenceRow {
  std::string scheme, history;
  double h = 0.0;  // dimensionless
  std::size_t steps = 0;
  double wall_seconds = 0.0;
  double error = 0.0;
  double order = 0.0;  // NaN for the first row of a (scheme, history) ladder
  // A two-block run's summary values (the peak of A.x1, the minimum gap, the friction work):
  // relative errors against the reference; NaN if not available (convergence.csv: err_peak_x1, ...).
  double peak_a1 = 0.0, min_gap = 0.0, friction = 0.0;
  std::vector<QuantityError> quantities;  // empty against an analytic reference
  bool switches_differ = false;  // the run's sequence of phases is not the reference's
  bool failed = false;  // the run stopped with a NumericalError (e.g. the paper scheme beyond its bound)
  std::string message;
};

struct ConvergenceResult {
  std::string reference;  // what the errors are measured against, in words
  std::vector<ConvergenceRow> rows;
};

ConvergenceResult run_convergence(const RunSpec& scene, const ConvergenceOptions& options);

}  // namespace adjoin
