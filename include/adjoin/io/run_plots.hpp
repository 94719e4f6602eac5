#pragma once
// Figures of run folders (io/plots.hpp lists them): a two-block run's, a building run's, and
// chosen channels of one or several runs.
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/io/plot_style.hpp"

namespace adjoin {

struct RunPlots {
  std::vector<std::filesystem::path> images;  // in the order io/plots.hpp lists them
  std::vector<std::string> notes;             // e.g. why the energy figure was skipped
};

// Figures for the run folder `dir`, written to `prefix` + name + extension (e.g. prefix
// "out/paper-strong/" gives out/paper-strong/displacements.png). Parent folders are created.
RunPlots plot_run(const std::filesystem::path& dir, const std::string& prefix, const PlotStyle& style);

// A building run's folder (summary.json with "structure" and floor peaks): `profiles` (peak
// displacement by floor and peak drift by storey, A and B side by side) and, with a
// timeseries.csv, `roofs` (the roofs' displacements and the links' forces against time).
// plot_run hands such folders here.
bool is_building_run(const std::filesystem::path& dir);
RunPlots plot_building_run(const std::filesystem::path& dir, const std::string& prefix, const PlotStyle& style);

// Chosen channels of any run folder (columns of its timeseries.csv: A.x5, link1.force, x1, fd,
// ...) against time, one panel each, stacked with a shared time axis, to `image`. At most 8
// channels; a name that is not a column is an InputError naming `option` and listing the
// columns there are.
void plot_run_channels(const std::filesystem::path& dir, const std::vector<std::string>& channels,
                       const std::filesystem::path& image, const PlotStyle& style,
                       const std::string& option = "--channels");
// The same channels of several run folders in one figure: a panel per channel, a curve per
// run (legend: scene and folder), each run on its own time grid. At most 24 runs.
void plot_runs_channels(const std::vector<std::filesystem::path>& dirs, const std::vector<std::string>& channels,
                        const std::filesystem::path& image, const PlotStyle& style,
                        const std::string& option = "--channels");

}  // namespace adjoin
