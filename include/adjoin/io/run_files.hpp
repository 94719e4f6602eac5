#pragma once
// A run's files: which ones a run writes is decided here, from the scene's [output], not by
// the command line.
//
//     RunFiles files = run_to_folder(scene, "out/paper-strong");
//
// The step is the scene's solver.h, or chosen for solver.tolerance (run_to_tolerance); the
// run's error is estimated from a companion run at about 2h unless solver.error_estimate =
// false (study/error_estimate.hpp).
//
// Always summary.json (io/summary.hpp); timeseries.csv (output.timeseries, io/timeseries_csv.hpp:
// a structure's channels, or a two-block scene's SPEC §3 columns), energy.csv (a two-block
// scene's output.energy_history), spectra.csv ([output.spectra]) when asked, and impacts.csv
// (io/impacts_csv.hpp) when a contact pair has a contact law. The streamed files are written while the
// solver runs; all of them are committed as one set (io/atomic_file.hpp FileSet): a run that
// fails (bad input, numerical failure, disk full) leaves the folder as it was, and a run that
// succeeds leaves exactly its own files (outputs of an earlier run that this one does not
// write are removed).
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/io/run_outputs.hpp"
#include "adjoin/study/error_estimate.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {

struct RunFiles {
  Report report;
  std::optional<ErrorEstimate> estimate;  // when the scene asks (solver.error_estimate)
  std::optional<TolerantRun> tolerant;    // when the step was chosen for a tolerance (its
                                          // report and estimate are the two above)
  std::vector<std::filesystem::path> written;  // in the order of run_file_names()
};

// Every file name a run may write into its folder.
const std::vector<std::string>& run_file_names();

// Checks `dir` (io/output_place.hpp), runs the scene and commits its files; `dir` is created
// (if it is not there) for the files and removed again if the run fails.
// `warn` is told, before the run starts writing, what is valid but probably unintended
// ("timeseries.csv will be about 504 MB ...").
using RunWarning = std::function<void(const std::string&)>;
RunFiles run_to_folder(const Scene& scene, const std::filesystem::path& dir, const RunWarning& warn = {});
// The same files written to `outputs` (io/run_outputs.hpp: a folder, or memory), committed at
// the end; `written` then names them as the outputs do.
RunFiles run_to(const Scene& scene, RunOutputs& outputs, const RunWarning& warn = {});

}  // namespace adjoin
