// adjoin run SCENE.toml [--out DIR] [--set KEY=VALUE]... [--quiet]
//
// Solves one scene and writes DIR/summary.json (always) and DIR/timeseries.csv (when the
// scene asks for output.timeseries), each by temporary file and rename. Prints a short
// summary on stdout unless --quiet.
#include <filesystem>
#include <iostream>
#include <memory>

#include "adjoin/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/energy_csv.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/timeseries_csv.hpp"
#include "adjoin/study/run.hpp"
#include "command.hpp"

namespace adjoin::cli {
namespace {

struct RunArgs {
  std::string scene;
  std::string out;
  std::vector<std::string> overrides;
  bool quiet = false;
};

int run_command(const RunArgs& args) {
  const Scene scene = load_scene(args.scene, args.overrides);
  const std::filesystem::path dir = args.out.empty() ? std::filesystem::path("out") / scene.name : std::filesystem::path(args.out);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw InputError(dir.string() + ": cannot create the output folder: " + error.message());

  // Streamed outputs: each writer sees the grid points as they are computed.
  std::vector<std::unique_ptr<AtomicFile>> files;
  std::vector<std::unique_ptr<Observer>> writers;
  ObserverList streams;
  if (scene.output.timeseries) {
    files.push_back(std::make_unique<AtomicFile>(dir / "timeseries.csv"));
    writers.push_back(std::make_unique<TimeSeriesCsvWriter>(files.back()->stream(), scene.scales, scene.output.every));
    streams.add(writers.back().get());
  }
  if (scene.output.energy_history) {
    files.push_back(std::make_unique<AtomicFile>(dir / "energy.csv"));
    writers.push_back(std::make_unique<EnergyCsvWriter>(files.back()->stream(), scene.scales, scene.output.every));
    streams.add(writers.back().get());
  }
  const RunReport report = run_scene(scene, writers.empty() ? nullptr : &streams);
  for (auto& file : files) file->commit();
  if (!report.spectra.empty()) {
    AtomicFile spectra(dir / "spectra.csv");
    spectra.stream() << spectra_csv(report);
    spectra.commit();
  }

  AtomicFile summary(dir / "summary.json");
  summary.stream() << summary_json(scene, report);
  summary.commit();

  if (!args.quiet) {
    std::cout << brief_report(scene, report);
    std::cout << "wrote " << (dir / "summary.json").string();
    if (scene.output.timeseries) std::cout << ", " << (dir / "timeseries.csv").string();
    if (scene.output.energy_history) std::cout << ", " << (dir / "energy.csv").string();
    if (!report.spectra.empty()) std::cout << ", " << (dir / "spectra.csv").string();
    std::cout << "\n";
  }
  return 0;
}

const Registration registration(10, [](CLI::App& app) -> Runner {
  auto args = std::make_shared<RunArgs>();
  auto* sub = app.add_subcommand("run", "Solve a scene: writes summary.json (and timeseries.csv if asked)");
  sub->add_option("scene", args->scene, "Scene file (TOML)")->required();
  sub->add_option("--out", args->out, "Output folder (default out/<scene name>/)");
  sub->add_option("--set", args->overrides, "Override a scene key by dotted path, e.g. --set solver.h=0.001")
      ->allow_extra_args(false);
  sub->add_flag("--quiet,-q", args->quiet, "Print nothing on success");
  return [args]() { return run_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
