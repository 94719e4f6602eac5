#include "adjoin/io/run_files.hpp"

#include <algorithm>
#include <memory>
#include <system_error>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/building_files.hpp"
#include "adjoin/io/energy_csv.hpp"
#include "adjoin/io/impacts_csv.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/timeseries_csv.hpp"

namespace adjoin {

const std::vector<std::string>& run_file_names() {
  static const std::vector<std::string> names = {"summary.json", "timeseries.csv", "energy.csv", "spectra.csv",
                                                 "impacts.csv"};
  return names;
}

namespace {

// The streamed writers, started afresh with each run they see: a run to a tolerance streams
// every rung it tries into the same files, and the rung it keeps is the last one written.
// (Cheaper than running the kept rung again with the writers attached.)
class RestartingStreams final : public Observer {
 public:
  RestartingStreams(RunOutputs& set, ObserverList& writers) : set_(set), writers_(writers) {}
  void begin(const RunInfo& info) override {
    if (started_) set_.restart();
    started_ = true;
    writers_.begin(info);
  }
  void observe(const State& s) override { writers_.observe(s); }
  void impact(const Impact& i) override { writers_.impact(i); }
  void end() override { writers_.end(); }

 private:
  RunOutputs& set_;
  ObserverList& writers_;
  bool started_ = false;
};

}  // namespace

RunFiles run_to_folder(const Scene& scene, const std::filesystem::path& dir, const RunWarning& warn) {
  check_output_folder(dir);  // before the run: the folder itself is made by the set's commit
  FolderOutputs set(dir, run_file_names());
  return run_to(scene, set, warn);
}

RunFiles run_to(const Scene& scene, RunOutputs& set, const RunWarning& warn) {
  if (!scene.two_block()) return run_building_to(scene, set, warn);
  // Streamed outputs: each writer sees the grid points as they are computed.
  std::vector<std::unique_ptr<Observer>> writers;
  ObserverList streams;
  TimeSeriesCsvWriter* timeseries = nullptr;
  if (scene.output.timeseries) {
    auto writer = std::make_unique<TimeSeriesCsvWriter>(set.open("timeseries.csv"), scene.scales, scene.output.every);
    timeseries = writer.get();
    writers.push_back(std::move(writer));
    streams.add(writers.back().get());
  }
  if (scene.output.energy_history) {
    writers.push_back(std::make_unique<EnergyCsvWriter>(set.open("energy.csv"), scene.scales, scene.output.every));
    streams.add(writers.back().get());
  }
  if (scene.model->contact.model != structure::ContactModel::none) {
    writers.push_back(std::make_unique<ImpactsCsvWriter>(set.open("impacts.csv"), scene.scales));
    streams.add(writers.back().get());
  }
  RunFiles files;
  RestartingStreams restarting(set, streams);
  const RunObservers extra{nullptr, writers.empty() ? nullptr : &restarting};
  if (scene.accuracy.tolerance) {
    files.tolerant = run_to_tolerance(scene, *scene.accuracy.tolerance, extra);
    files.report = files.tolerant->report;
    files.estimate = files.tolerant->estimate;
  } else {
    files.report = run(scene, extra);
    if (scene.accuracy.error_estimate) files.estimate = estimate_error(scene, files.report);
  }
  if (files.report.two_block->outside_model_from && timeseries) {
    // No contact law and the gap closed: the time series gets its outside_model column. Its
    // header was written before the contact was known, so the kept run is streamed again
    // (same step, same grid: the same numbers) with the column; a run that never pounds keeps
    // the SPEC header and pays nothing.
    timeseries->set_flag_outside_model(true);
    SolverOptions again = two_block_options(scene);
    again.h = files.report.solver.h;
    simulate(again, *scene.model, *scene.ground, restarting);
  }
  if (!files.report.spectra.empty()) set.open("spectra.csv") << spectra_csv(files.report);
  set.open("summary.json") << summary_json(scene, files.report, files.estimate ? &*files.estimate : nullptr,
                                           files.tolerant ? &*files.tolerant : nullptr);
  files.written = set.commit();
  const auto rank = [](const std::filesystem::path& p) {
    const auto& names = run_file_names();
    return std::find(names.begin(), names.end(), p.filename().string()) - names.begin();
  };
  std::sort(files.written.begin(), files.written.end(), [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
  return files;
}

}  // namespace adjoin
