#pragma once
// Each run's own error estimate, and the step chosen for a tolerance.
//
//     ErrorEstimate e = estimate_error(scene, report);       // a companion run at about 2h
//     TolerantRun t = run_to_tolerance(scene, 1e-6);          // picks h, then as above
//
// estimate_error: Richardson extrapolation. The scene runs again on a grid about twice as
// coarse over the same horizon (N/2 steps of h' = N h / floor(N/2)), and for each reported
// value Q the error of the fine run is estimated as (Q_h - Q_h') / ((h'/h)^p - 1), p the
// scheme's order (solver/options.hpp scheme_order). The companion costs about half the run
// (a quarter with direct history sums). Estimated: the peaks that are refined between samples
// (x1, x2, the stroke, f1, f2, q: values and times), the minimum gap and its time, the
// friction energy and every switching instant (matched by index; when the companion finds
// another number of switches the instants are not estimated and the reason says so). The
// estimate is asymptotic: it is trustworthy when both runs resolve the motion (tests check it
// within a factor 3 of the true error on ladders of the paper's and of a record scene).
//
// run_to_tolerance: a short ladder. From a first step h0 (t_end / 2000, and no coarser than a
// record's sampling interval) it runs, estimates, and predicts the step that meets the
// tolerance from the observed error and the order, h <- h (0.7 tol / E)^(1/p), until the
// largest relative error of the peaks, E = max |error| / |peak|, is at most the tolerance
// (at most six rungs). After the first rung the previous rung is the companion of the
// estimate that steers the ladder (free); only a rung it finds within twice the tolerance
// pays for the run at 2h, whose estimate decides and is reported. It reports the chosen h,
// the rungs and the estimate reached.
//
// All values are dimensionless (io/summary.hpp converts them).
#include <string>
#include <vector>

#include "adjoin/study/run_spec.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {

struct PeakError {
  double max_abs = 0.0, t = 0.0;  // estimated absolute errors of a Peak's value and time
};

struct ErrorEstimate {
  bool available = false;
  std::string reason;             // why not, when not available
  double companion_h = 0.0;       // the coarse step
  int order = 2;                  // p
  double companion_wall_seconds = 0.0;
  PeakError x1, x2, drift, f1, f2, q;
  double min_gap = 0.0, t_min_gap = 0.0;
  double friction = 0.0;          // of the friction energy
  bool switches_matched = false;  // the companion found the same phases
  std::vector<double> switches;   // errors of phases[1..].t_start, when matched
  // max over the estimated peaks of |error of the value| / |value| (0 for a zero peak).
  double max_relative_peak = 0.0;
};

ErrorEstimate estimate_error(const RunSpec& scene, const RunReport& fine);

struct TolerantRun {
  RunReport report;
  ErrorEstimate estimate;
  double tolerance = 0.0;
  double h = 0.0;                // the chosen step (dimensionless)
  std::vector<double> ladder;    // the steps tried, in order (the last is h)
  bool met = false;              // estimate.max_relative_peak <= tolerance
};

// `scene.solver.h` is ignored; the rest of the scene is used as is. `extra` sees the run of
// every rung tried (its begin() starts each); the last one is the run reported.
TolerantRun run_to_tolerance(const RunSpec& scene, double tolerance, Observer* extra = nullptr);

}  // namespace adjoin
