#pragma once
// A building run described in code (SPEC §4, §5): its ground and the run-level rules a scene
// file's reader applies too (io/building_scene.hpp) — the step and horizon chosen when not
// given, with their rules in words (h_rule, t_end_rule), and a record scaled to a PGA.
//
//     structure::Structure s = ...;                        // structure/builder.hpp
//     BuildingRunOptions o;
//     o.h = 0.002;                                         // or leave it: chosen for a tolerance
//     RunSpec spec = building_run_spec(std::move(s), record_ground("RSN1044.AT2"), o);
//     Report report = run(spec);          // study/run.hpp
//
// Errors are FieldError (adjoin/core/errors.hpp) naming the field: "ground.scale_pga", "solver.h".
// Every value in SI units (s, m, g for the ground's a_g).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin {

// Without a step and a tolerance a building run's step is chosen for this relative error of
// its reported peaks: three significant digits, what a structural engineer reads (two-block
// scenes keep 1e-6: their steps cost nanoseconds).
inline constexpr double kBuildingDefaultTolerance = 1e-3;

// ---- grounds: a building run's ground gives a_g in g at times in s ----

// A record file read by the ground readers (ground/record_file.hpp; the format from the file
// unless `format` says it), scaled so its peak ground acceleration is `scale_pga` [g] when
// given (the scene's ground.scale_pga).
std::shared_ptr<const GroundMotion> record_ground(const std::filesystem::path& file, std::optional<double> scale_pga = {},
                                                  const RecordFormat& format = {});
// (Any ground times a plain factor, the scene's ground.scale: scale_ground(ground, factor),
// ground/ground_motion.hpp.)
// The paper's decaying sine a_g = u0 omega^2 e^{-k t} sin(omega t), in SI: u0 [m],
// omega [rad/s], k [1/s] (the scene's source = "decaying-sine").
std::shared_ptr<const GroundMotion> decaying_sine_ground(double u0, double omega, double k);

// ---- the run-level rules ----

// A value chosen by a rule, and the rule in words (for the summary and the terminal).
struct Chosen {
  double value = 0.0;
  std::string rule;
};
// How the step is found when not given: "chosen for solver.tolerance = 1e-05", or with
// `given` false the default's rule (kBuildingDefaultTolerance).
std::string tolerance_rule(double tolerance, bool given);
// The first step for a tolerance: the shortest fundamental period of the buildings / 200, no
// coarser than the record's sampling interval `record_dt` (0: not a record); its rule begins
// with `tolerance_rule`.
Chosen default_building_step(const structure::Structure& s, double record_dt, const std::string& tolerance_rule);
// The horizon when not given: the motion's duration + 5 x the longest period (of the
// buildings and, with B, of the coupled system with the links free), or 20 x that period for
// a motion without an end.
Chosen default_building_horizon(const structure::Structure& s, double duration);

// ---- a run ----

struct BuildingRunOptions {
  std::string name = "building";
  std::optional<double> h;          // s; not given: chosen for the tolerance
  std::optional<double> tolerance;  // the relative error of the peaks the step is chosen for
                                    // (not with h; neither: kBuildingDefaultTolerance)
  std::optional<double> t_end;      // s; not given: default_building_horizon
  bool error_estimate = true;       // a companion run at about 2h estimates the error
  HistoryEngine history = HistoryEngine::soe;
  StructureSolverOptions::Restart restart = StructureSolverOptions::Restart::automatic;
  OutputOptions output;
};

// The run of `structure` on `ground`: its step and horizon given or chosen by the rules above,
// checked (FieldError "solver.h", "solver.t_end", "solver.tolerance"). Warnings for valid but
// probably unintended choices (a step coarser than the record's samples) in .warnings.
RunSpec building_run_spec(structure::Structure structure, std::shared_ptr<const GroundMotion> ground,
                                  const BuildingRunOptions& options = {});

}  // namespace adjoin
