#pragma once
// The minimum seismic joint: the smallest clear gap at rest with which a scene's floors never
// touch (issue 13, "Studies").
//
//     SeismicJoint j = seismic_joint(scene, SeismicJointOptions{});            // two-block
//     SeismicJoint j = seismic_joint(building_scene, SeismicJointOptions{});   // building
//
// The gap that varies is the two-block scene's model.gap0, or the gap of a building scene's
// contact pair `contact` (1-based). Every run leaves that pair without a contact law (model
// none: the floors would pass through each other); a run "touches" when the pair's minimum
// gap is below 0. Two independent answers:
//
//  - bisection over runs: from the bracket [0, 2 s_max] (widened by doubling while its top
//    still touches), each run with the bracket's midpoint as the gap, until the bracket is
//    narrower than the tolerance; the joint is the bracket's top (a gap that does not touch).
//    It uses only whether each run touches;
//  - direct: without a contact law the response does not depend on the gap, so the joint is
//    s_max, the largest relative displacement s = x_A,i - x_B,j (two-block: x1 - x2) of one
//    run, read from that run's minimum gap (s_max = gap - min_gap; the run is made at gap 0,
//    where s_max = -min_gap exactly, and serves as the bracket's bottom).
//
// The minimum gap is refined between grid points: a two-block run's as its summary refines it
// (observe/pounding.hpp); a building run's on the parabola the structure solver integrates
// the pair's relative motion on within a step (constant acceleration: where it locates a
// contact law's first touch, solver/contact_step.hpp), so that with a gap of joint + tol a run
// with any contact law has no impact. The floors' peak displacements are refined alike.
//
// They agree to the tolerance (|joint - s_max| <= tol, joint >= s_max). The report also gives
// the codes' simple rules from the same run's peak displacements of the two floors
// (|x_A,i|max, |x_B,j|max): their square root of the sum of squares (ASCE 7-16 §12.12.3,
// adjacent structures on the same property: delta_MT = sqrt(delta_M1^2 + delta_M2^2)) and
// their absolute sum (the conservative rule), for comparison with the exact s_max.
//
// The other contact pairs of a building scene keep their gaps and laws (they do not depend on
// this pair's gap); one without a law that touches puts the run outside the model from its
// first contact on, which the notes say.
//
// Every pair at once (`contact = 0`, a building scene): every pair without its law and at one
// uniform gap; a run touches when any pair does. The bisection finds the smallest uniform gap;
// the direct run gives each pair's own s_max (its joint, were the others wide enough: without
// contact laws the response does not depend on the gaps), and the uniform joint is their
// largest, the critical pair's. The top-level fields are then the critical pair's. Lengths are in the scene's units (m for building
// and SI scenes, the scene's length unit for dimensionless ones), times in its time unit.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "adjoin/study/run_spec.hpp"

namespace adjoin {

struct SeismicJointOptions {
  // Building scenes: the contact pair (1-based) whose gap is the joint; 0: every pair at once
  // (one uniform gap).
  int contact = 1;
  // The bisection's tolerance in the scene's length unit; NaN: 1e-6 of s_max.
  double tol = std::numeric_limits<double>::quiet_NaN();
  int max_runs = 200;  // a bound on the bisection's runs (a guard; ~25 are needed)
  bool IsValid(std::string* error) const;
};

// One contact pair's own joint, from the direct run: its s_max and the codes' rules.
struct PairJoint {
  int contact = 1;                 // 1-based
  int floor_a = 1, floor_b = 1;
  double s_max = 0.0, t_critical = 0.0;
  double peak_a = 0.0, t_peak_a = 0.0, peak_b = 0.0, t_peak_b = 0.0;
  double srss = 0.0, abs_sum = 0.0;
};

struct SeismicJoint {
  std::string scene;
  bool building = false;   // a building scene (else two-block)
  bool every_pair = false; // every pair at once, at one uniform gap (options.contact = 0)
  int contact = 1;         // the pair (1 for two-block scenes); every_pair: the critical pair
  int floor_a = 1, floor_b = 1;
  std::string gap_key;     // the scene key of the gap: "model.gap0", "contact.N.gap" or "contact.*.gap"
  std::string length_unit, time_unit;  // "m", "s" (or the dimensionless scene's "X0", "T0")

  // Bisection.
  double joint = 0.0;        // the smallest gap found that does not touch
  double joint_low = 0.0;    // the largest gap found that touches (the bracket's bottom)
  double tol = 0.0;          // the tolerance used
  std::size_t runs = 0;      // every run: the direct one (at gap 0, the bracket's bottom) and the bisection's
  std::size_t widenings = 0; // times the bracket's top was doubled
  double bracket_top = 0.0;  // the bracket's top after widening

  // Direct: one run without contact.
  double s_max = 0.0;        // the largest relative displacement s (closing the gap when > 0)
  double t_critical = 0.0;   // its time (the critical approach)
  double difference = 0.0;   // joint - s_max
  bool agree = false;        // 0 <= joint - s_max <= tol (up to rounding)

  // The codes' simple rules from the same run's peak floor displacements.
  double peak_a = 0.0, t_peak_a = 0.0;  // |x_A,i| max (two-block: |x1|)
  double peak_b = 0.0, t_peak_b = 0.0;  // |x_B,j| max (two-block: |x2|)
  double srss = 0.0;                    // sqrt(peak_a^2 + peak_b^2)
  double abs_sum = 0.0;                 // peak_a + peak_b

  // Each pair sized (one, or every pair: each its own s_max from the direct run).
  std::vector<PairJoint> pairs;

  double wall_seconds = 0.0;            // every run together
  std::vector<std::string> notes;       // what the reader should know (other pairs, horizon)
};

// A building (SPEC §5): the joint is contact `options.contact`'s gap, or every pair's at once
// (contact 0); InputError if the scene has no contact pair or `contact` is out of range (the
// message names "contact N"). A two-block
// spec (SPEC §3): the joint is model.gap0 (the scene's [model.contact] is not used).
// InputError if the options are not valid.
SeismicJoint seismic_joint(const RunSpec& scene, const SeismicJointOptions& options = {});

}  // namespace adjoin
