#pragma once
// A building run's files, committed as a set (io/atomic_file.hpp): summary.json (scene,
// solver, ground, structure: periods, damping ratios and mode shapes of each building and the
// coupled periods; peaks by channel; links; contact pairs) and, if output.timeseries,
// timeseries.csv (t, a_g and every floor's displacement and absolute acceleration, each link's
// force and stroke, each contact pair's gap; SI units). No NaN or Inf is written (exit 3).
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/io/building_scene.hpp"
#include "adjoin/study/building_run.hpp"

namespace adjoin {

struct BuildingFiles {
  BuildingReport report;
  std::vector<std::filesystem::path> written;
};

std::string building_summary_json(const BuildingScene& scene, const BuildingReport& report);
std::string building_brief_report(const BuildingScene& scene, const BuildingReport& report);
BuildingFiles run_building_to_folder(const BuildingScene& scene, const std::filesystem::path& dir);

}  // namespace adjoin
