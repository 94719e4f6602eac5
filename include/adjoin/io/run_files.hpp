#pragma once
// A run's files: which ones a run writes is decided here, from the scene's [output], not by
// the command line.
//
//     RunFiles files = run_to_folder(scene, "out/paper-strong");
//
// Always summary.json; timeseries.csv (output.timeseries), energy.csv (output.energy_history)
// and spectra.csv ([output.spectra]) when asked. The streamed files are written while the
// solver runs; all of them are committed as one set (io/atomic_file.hpp FileSet): a run that
// fails (bad input, numerical failure, disk full) leaves the folder as it was, and a run that
// succeeds leaves exactly its own files (outputs of an earlier run that this one does not
// write are removed).
#include <filesystem>
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {

struct RunFiles {
  RunReport report;
  std::vector<std::filesystem::path> written;  // in the order of run_file_names()
};

// Every file name a run may write into its folder.
const std::vector<std::string>& run_file_names();

// Creates `dir` if needed, runs the scene and commits its files.
RunFiles run_to_folder(const Scene& scene, const std::filesystem::path& dir);

}  // namespace adjoin
