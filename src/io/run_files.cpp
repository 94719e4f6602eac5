#include "adjoin/io/run_files.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <system_error>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/energy_csv.hpp"
#include "adjoin/io/impacts_csv.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/timeseries_csv.hpp"
#include "adjoin/io/two_block_names.hpp"

namespace adjoin {

const std::vector<std::string>& run_file_names() {
  static const std::vector<std::string> names = {"summary.json", "timeseries.csv", "energy.csv", "spectra.csv",
                                                 "impacts.csv"};
  return names;
}

namespace {

// The streamed writers, started afresh with each run they see: a run to a tolerance streams
// every rung it tries into the same files, and the rung it keeps is the last one written.
// (Cheaper than running the kept rung again with the writers attached.) A structure's writer,
// or a two-block scene's writers (SPEC §3's names) of its 1 + 1 structure.
class RestartingStreams final : public StructureObserver {
 public:
  explicit RestartingStreams(RunOutputs& set) : set_(set) {}
  std::vector<StructureObserver*> writers;

  void begin(const structure::Structure& s, const StructureSolverOptions& o) override {
    restart();
    for (auto* w : writers) w->begin(s, o);
  }
  void observe(const StructureState& st) override {
    for (auto* w : writers) w->observe(st);
  }
  void impact(const Impact& i) override {
    for (auto* w : writers) w->impact(i);
  }
  void end() override {
    for (auto* w : writers) w->end();
  }

 private:
  void restart() {
    if (started_) set_.restart();
    started_ = true;
  }
  RunOutputs& set_;
  bool started_ = false;
};

bool has_contact_law(const Scene& scene) {
  const auto& contacts = scene.structure.contacts;
  return std::any_of(contacts.begin(), contacts.end(),
                     [](const structure::Contact& c) { return c.law.model != structure::ContactModel::none; });
}

// The streamed files a scene asks for, opened in `set`: a structure's timeseries.csv, or a
// two-block scene's timeseries.csv, energy.csv and impacts.csv under SPEC §3's names.
struct Streams {
  std::unique_ptr<ChannelCsvWriter> channels;
  std::vector<std::unique_ptr<StructureObserver>> two_block;
  TimeSeriesCsvWriter* timeseries = nullptr;  // the two-block one
};

Streams open_streams(const Scene& scene, RunOutputs& set, const RunWarning& warn, RestartingStreams& restarting) {
  Streams streams;
  const OutputOptions& asked = scene.output;
  if (!scene.two_block()) {
    if (asked.timeseries) {
      streams.channels = std::make_unique<ChannelCsvWriter>(set.open("timeseries.csv"), scene, warn);
      restarting.writers.push_back(streams.channels.get());
    }
    return streams;
  }
  if (asked.timeseries) {
    auto writer = std::make_unique<TimeSeriesCsvWriter>(set.open("timeseries.csv"), scene.scales, asked.every);
    streams.timeseries = writer.get();
    streams.two_block.push_back(std::move(writer));
  }
  if (asked.energy_history)
    streams.two_block.push_back(std::make_unique<EnergyCsvWriter>(set.open("energy.csv"), scene.scales, asked.every));
  if (has_contact_law(scene)) streams.two_block.push_back(std::make_unique<ImpactsCsvWriter>(set.open("impacts.csv"), scene.scales));
  for (const auto& w : streams.two_block) restarting.writers.push_back(w.get());
  return streams;
}

}  // namespace

RunFiles run_to_folder(const Scene& scene, const std::filesystem::path& dir, const RunWarning& warn) {
  check_output_folder(dir);  // before the run: the folder itself is made by the set's commit
  FolderOutputs set(dir, run_file_names());
  return run_to(scene, set, warn);
}

RunFiles run_to(const Scene& scene, RunOutputs& set, const RunWarning& warn) {
  // Streamed outputs: each writer sees the grid points as they are computed.
  RestartingStreams restarting(set);
  const Streams streams = open_streams(scene, set, warn, restarting);
  const RunObservers extra{restarting.writers.empty() ? nullptr : &restarting};
  RunFiles files;
  if (scene.accuracy.tolerance) {
    files.tolerant = run_to_tolerance(scene, *scene.accuracy.tolerance, extra);
    files.report = files.tolerant->report;
    files.estimate = files.tolerant->estimate;
  } else {
    files.report = run(scene, extra);
    if (scene.accuracy.error_estimate) files.estimate = estimate_error(scene, files.report);
  }
  if (streams.timeseries && !std::isnan(files.report.unmodelled_from())) {
    // A two-block scene without a contact law whose gap closed: its time series gets the
    // outside_model column. The header was written before the contact was known, so the kept
    // run is streamed again (same step, same grid: the same numbers) with the column; a run
    // that never pounds keeps the SPEC header and pays nothing. (A structure's writer flags
    // its rows as it goes.)
    streams.timeseries->set_flag_outside_model(true);
    SolverOptions again = two_block_options(scene);
    again.h = files.report.solver.h;
    simulate_as_structure(again, scene.structure, *scene.ground, restarting);
  }
  if (!files.report.spectra.empty()) set.open("spectra.csv") << (scene.two_block() ? spectra_csv(two_block_signal_names(files.report.spectra))
                                                                                        : spectra_csv(files.report));
  if (!scene.two_block() && has_contact_law(scene)) set.open("impacts.csv") << impacts_csv(files.report);
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
