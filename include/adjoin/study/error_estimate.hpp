#pragma once
// Each run's own error estimate, and the step chosen for a tolerance, for every spec.
//
//     ErrorEstimate e = estimate_error(spec, report);       // a companion run at about 2h
//     TolerantRun t = run_to_tolerance(spec, 1e-6);          // picks h, then as above
//
// estimate_error: Richardson extrapolation. The spec runs again (study/run.hpp) on a grid about
// twice as coarse over the same horizon (N/2 steps of h' = N h / floor(N/2)), and for each
// reported value Q the error of the fine run is estimated as (Q_h - Q_h') / ((h'/h)^p - 1), p
// the scheme's order (solver/options.hpp scheme_order). The companion costs about half the run
// (a quarter with direct history sums). A building's companion integrates with the run's own
// restart rule (Restart::always or never as the run resolved `automatic`): at 2h the automatic
// rule could turn the backward-Euler restart on where the run had it off, and Richardson would
// then compare two methods. Estimated:
//  - a building: the channel peaks refined between samples (structure/channels.hpp
//    PeakRule::refined: displacements A.x3, drifts A.drift2, link strokes link1.stroke): value
//    and time; the others (accelerations, shears, link forces) are the largest samples, whose
//    error is not a power of h, and are left out; each link's force_max and stroke_max, and for
//    friction links the dissipated energy and each switching instant matched by index (when
//    the companion finds another number of switches the instants are not estimated and
//    `switches_note` says so); each contact pair's minimum gap and its time. The energy
//    balance's residual is not estimated: it is itself a measure of the error.
//  - a two-block spec: the peaks that are refined between samples (x1, x2, the stroke, f1, f2,
//    q: values and times), the minimum gap and its time, the friction energy and every
//    switching instant (matched by index; when the companion finds another number of switches
//    the instants are not estimated and the reason says so).
// max_relative_peak is the largest |error| / |value| over the estimated peaks, the number a
// tolerance is held to. The estimate is asymptotic: it is trustworthy when both runs resolve
// the motion (tests check it within a factor 3 of the true error on ladders of the paper's, a
// record's and a building's scene).
//
// run_to_tolerance: a short ladder. From a first step (a building's: the spec's solver.h; a
// two-block spec's: t_end / 2000, and no coarser than a record's sampling interval) it runs,
// estimates, and predicts the step that meets the tolerance from the observed error and the
// order, h <- h (0.7 tol / E)^(1/p), until the largest relative error of the peaks is at most
// the tolerance (at most six rungs). After the first rung the previous rung is the companion
// of the estimate that steers the ladder (free); only a rung it finds within twice the
// tolerance pays for the run at 2h, whose estimate decides and is reported. It reports the
// chosen h, the rungs and the estimate reached.
//
// Values are in the report's units (SI for a building, dimensionless for a two-block spec).
#include <optional>
#include <string>
#include <vector>

#include "adjoin/study/run.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin {

struct PeakError {
  double max_abs = 0.0, t = 0.0;  // estimated absolute errors of a Peak's value and time
};

struct ChannelPeakError {
  std::string channel;  // as in Report::peaks
  PeakError error;      // estimated absolute errors of the peak's value and time
};

struct LinkError {
  double force_max = 0.0, stroke_max = 0.0;
  // Friction links only (0 and empty otherwise):
  double energy = 0.0;            // of the dissipated energy
  bool switches_matched = false;  // the companion found as many switches
  std::vector<double> switches;   // errors of switch_times, when matched
  std::string switches_note;      // why not, when not matched ("" otherwise)
};

struct ContactError {
  double min_gap = 0.0, t_min_gap = 0.0;
};

struct ErrorEstimate {
  bool available = false;
  std::string reason;             // why not, when not available
  double companion_h = 0.0;       // the coarse step
  int order = 2;                  // p
  double companion_wall_seconds = 0.0;
  // The refined peaks by channel, in the report's order (a two-block spec's by its 1 + 1
  // structure's channels: A.x1, B.x1, link1.stroke, A.shear1, B.shear1, link1.force, which io
  // presents as x1, x2, drift, f1, f2, q: structure/two_block.hpp two_block_channel).
  std::vector<ChannelPeakError> peaks;
  std::string worst_channel;            // where max_relative_peak is reached ("" if every peak is zero)
  // A building's (Report's links and contact pairs):
  std::vector<LinkError> links;         // in the structure's order
  std::vector<ContactError> contacts;   // in the structure's order
  // The collapse time's error (SPEC §7), when both runs collapsed (the same storey); else empty.
  std::optional<double> collapse_t;
  // A two-block spec's (Report::two_block):
  double min_gap = 0.0, t_min_gap = 0.0;
  double friction = 0.0;          // of the friction energy
  bool switches_matched = false;  // the companion found the same phases
  std::vector<double> switches;   // errors of phases[1..].t_start, when matched
  // max over the estimated peaks of |error of the value| / |value| (0 for a zero peak).
  double max_relative_peak = 0.0;
};

ErrorEstimate estimate_error(const RunSpec& spec, const Report& fine);

struct TolerantRun {
  Report report;
  ErrorEstimate estimate;
  double tolerance = 0.0;
  double h = 0.0;                // the chosen step
  std::vector<double> ladder;    // the steps tried, in order (the last is h)
  bool met = false;              // estimate.max_relative_peak <= tolerance
};

// The spec's solver.h is a building's first rung (a two-block spec's is ignored); the rest of
// the spec is used as is. `extra` sees the run of every rung tried (its begin() starts each);
// the last one is the run reported. Throws InputError for a tolerance outside (0, 1) and when a
// building rung's history would not fit in memory, NumericalError when a two-block rung's
// would not.
TolerantRun run_to_tolerance(const RunSpec& spec, double tolerance, const RunObservers& extra = {});

}  // namespace adjoin
