#pragma once
// A building run's files, committed as a set (io/atomic_file.hpp): summary.json (scene,
// solver, ground, structure: periods, damping ratios and mode shapes of each building and the
// coupled periods; peaks by channel; links; contact pairs) and, if output.timeseries,
// timeseries.csv (t, a_g and every floor's displacement and absolute acceleration, each link's
// force and stroke, each contact pair's gap and force, and `outside_model` (0, then 1 from the
// first overlap of a pair without a contact law) when a pair has model none; SI units) and,
// when a contact pair has a contact law, impacts.csv (one row per impact, in the order they
// started; contact is 1-based). No NaN or Inf is written (exit 3).
//
// The step is the scene's solver.h, or chosen for solver.tolerance (run_to_tolerance); the
// run's error is estimated from a companion run at about 2h unless solver.error_estimate =
// false (study/building_error_estimate.hpp); the summary's `error_estimate` holds it.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/io/building_scene.hpp"
#include "adjoin/study/building_error_estimate.hpp"
#include "adjoin/study/building_run.hpp"

namespace adjoin {

struct BuildingFiles {
  BuildingReport report;
  std::optional<BuildingErrorEstimate> estimate;  // when the scene asks (solver.error_estimate)
  std::optional<BuildingTolerantRun> tolerant;    // when the step was chosen for a tolerance (its
                                                  // report and estimate are the two above)
  std::vector<std::filesystem::path> written;
};

std::string building_summary_json(const BuildingScene& scene, const BuildingReport& report,
                                  const BuildingErrorEstimate* estimate = nullptr, const BuildingTolerantRun* tolerant = nullptr);
std::string building_brief_report(const BuildingScene& scene, const BuildingReport& report,
                                  const BuildingErrorEstimate* estimate = nullptr, const BuildingTolerantRun* tolerant = nullptr);
// impacts.csv: contact,start,duration,force_max,t_force_max,penetration_max,approach_speed,
// rebound_speed,impulse,complete (SI; complete: true or false).
std::string building_impacts_csv(const BuildingReport& report);
BuildingFiles run_building_to_folder(const BuildingScene& scene, const std::filesystem::path& dir);

}  // namespace adjoin
