#pragma once
// A building run's files, committed as a set (io/atomic_file.hpp): summary.json (scene,
// solver, ground, structure: periods, damping ratios and mode shapes of each building and the
// coupled periods; peaks by channel; links; contact pairs) and, if output.timeseries,
// timeseries.csv (its rows: building_output_every below; t, a_g and every floor's displacement and absolute acceleration, each link's
// force and stroke, each contact pair's gap and force, and `outside_model` (0, then 1 from the
// first overlap of a pair without a contact law) when a pair has model none; SI units) and,
// when a contact pair has a contact law, impacts.csv (one row per impact, in the order they
// started; contact is 1-based). No NaN or Inf is written (exit 3).
//
// The step is the scene's solver.h, or chosen for solver.tolerance (run_to_tolerance); the
// run's error is estimated from a companion run at about 2h unless solver.error_estimate =
// false (study/error_estimate.hpp); the summary's `error_estimate` holds it.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/run_files.hpp"
#include "adjoin/study/error_estimate.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {


std::string building_summary_json(const BuildingScene& scene, const Report& report,
                                  const ErrorEstimate* estimate = nullptr, const TolerantRun* tolerant = nullptr);
std::string building_brief_report(const BuildingScene& scene, const Report& report,
                                  const ErrorEstimate* estimate = nullptr, const TolerantRun* tolerant = nullptr);
// impacts.csv: contact,start,duration,force_max,t_force_max,penetration_max,approach_speed,
// rebound_speed,impulse,complete (SI; complete: true or false).
std::string building_impacts_csv(const Report& report);
// Told, before a run starts writing, what is valid but probably unintended ("timeseries.csv
// will be about 504 MB ..."): the command line prints it on stderr as a warning.
// A building scene's files (io/run_files.hpp run_to calls it).
RunFiles run_building_to(const BuildingScene& scene, RunOutputs& outputs, const RunWarning& warn = {});

// The rows of timeseries.csv: every output.every-th grid point when the scene gives it; else,
// with a step the scene gives (solver.h), every grid point; else (a step chosen for a
// tolerance) a row every building_output_interval: 1/200 s (200 Hz: 10 samples a cycle up to
// 20 Hz, above a building's modes of interest), 1/1000 s when a contact pair has a law (impacts
// last milliseconds), in whole steps of h (the row interval is at most that). The summary's
// peaks are taken at every step whatever the rows. 0 when the rule does not apply.
double building_output_interval(const BuildingScene& scene);
std::size_t building_output_every(const BuildingScene& scene, double h);

}  // namespace adjoin
