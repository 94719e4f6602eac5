#pragma once
// A building run's own error estimate, and the step chosen for a tolerance: the two-block
// runs' method (study/error_estimate.hpp) applied to a building run's report.
//
//     BuildingErrorEstimate e = estimate_error(spec, report);       // a companion run at about 2h
//     BuildingTolerantRun t = run_to_tolerance(spec, 1e-4);          // picks h, then as above
//
// estimate_error: the run again over the same horizon on a grid about twice as coarse (N/2
// steps of h' = N h / floor(N/2)); each reported value Q gets the error estimate
// (Q_h - Q_h') / ((h'/h)^p - 1), p = 2 (the building step is trapezoidal). Estimated:
//  - the channel peaks refined between samples (structure/channels.hpp PeakRule::refined:
//    displacements A.x3, drifts A.drift2, link strokes link1.stroke): value and time; the
//    others (accelerations, shears, link forces) are the largest samples, whose error is not a
//    power of h, and are left out;
//  - each link's force_max and stroke_max, and for friction links the dissipated energy and
//    each switching instant matched by index: when the companion finds another number of
//    switches the instants are not estimated and `switches_note` says so;
//  - each contact pair's minimum gap and its time.
// The energy balance's residual is not estimated: it is itself a measure of the error.
// max_relative_peak is the largest |error| / |value| over the estimated channel peaks, the
// number a tolerance is held to. The estimate is asymptotic: trustworthy when both runs
// resolve the motion.
//
// run_to_tolerance: the two-block scenes' ladder (at most six rungs, each step predicted from
// the observed error and the order) from the spec's solver.h as the first step, until
// max_relative_peak is at most the tolerance.
//
// All values are SI (m, N, J, s), as the report's.
#include <string>
#include <vector>

#include "adjoin/study/building_run.hpp"
#include "adjoin/study/error_estimate.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin {

struct ChannelPeakError {
  std::string channel;  // as in BuildingReport::peaks
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

struct BuildingErrorEstimate {
  bool available = false;
  std::string reason;  // why not, when not available
  double companion_h = 0.0;
  int order = 2;
  double companion_wall_seconds = 0.0;
  std::vector<ChannelPeakError> peaks;  // the refined channels, in the report's order
  std::vector<LinkError> links;         // in the structure's order
  std::vector<ContactError> contacts;   // in the structure's order
  double max_relative_peak = 0.0;       // over `peaks` (a zero peak counts 0)
  std::string worst_channel;            // where it is reached ("" if every peak is zero)
};

BuildingErrorEstimate estimate_error(const BuildingRunSpec& spec, const BuildingReport& fine);

struct BuildingTolerantRun {
  BuildingReport report;
  BuildingErrorEstimate estimate;
  double tolerance = 0.0;
  double h = 0.0;              // the chosen step [s]
  std::vector<double> ladder;  // the steps tried [s], in order (the last is h)
  bool met = false;            // estimate.max_relative_peak <= tolerance
};

// `spec.solver.h` is the first rung's step; the rest of the spec is used as is. `extra` sees the
// run of every rung tried (its begin() starts each); the last one is the run reported.
// Throws InputError for a tolerance outside (0, 1), NumericalError when a rung's history would
// not fit in memory.
BuildingTolerantRun run_to_tolerance(const BuildingRunSpec& spec, double tolerance, StructureObserver* extra = nullptr);

}  // namespace adjoin
