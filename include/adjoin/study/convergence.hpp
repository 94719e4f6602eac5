#pragma once
// Convergence and work-precision: error against run time for each scheme and history engine
// on a ladder of steps.
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
//  - peak_x1, min_gap, friction: relative errors of those summary values (against the fine
//    run; against the exact solution only the trajectory error is given).
// The observed order is log2 of the ratio of successive errors over a halving of h.
#include <string>
#include <vector>

#include "adjoin/io/scene.hpp"

namespace adjoin {

struct ConvergenceOptions {
  std::vector<Scheme> schemes = {Scheme::paper, Scheme::implicit_gl, Scheme::implicit};
  std::vector<HistoryEngine> engines = {HistoryEngine::direct};
  std::vector<double> steps;  // dimensionless h; empty: the scene's h times 4, 2, 1, 1/2, 1/4
  double reference_factor = 8.0;
  bool IsValid(std::string* error) const;
};

struct ConvergenceRow {
  std::string scheme, history;
  double h = 0.0;  // dimensionless
  std::size_t steps = 0;
  double wall_seconds = 0.0;
  double error = 0.0;
  double order = 0.0;  // NaN for the first row of a (scheme, history) ladder
  double peak_x1 = 0.0, min_gap = 0.0, friction = 0.0;  // relative errors; NaN if not available
  bool failed = false;  // the run stopped with a NumericalError (e.g. the paper scheme beyond its bound)
  std::string message;
};

struct ConvergenceResult {
  std::string reference;  // what the errors are measured against, in words
  std::vector<ConvergenceRow> rows;
};

ConvergenceResult run_convergence(const Scene& scene, const ConvergenceOptions& options);

}  // namespace adjoin
