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

  std::unique_ptr<AtomicFile> csv_file;
  std::unique_ptr<TimeSeriesCsvWriter> csv;
  if (scene.output.timeseries) {
    csv_file = std::make_unique<AtomicFile>(dir / "timeseries.csv");
    csv = std::make_unique<TimeSeriesCsvWriter>(csv_file->stream(), scene.scales, scene.output.every);
  }
  const RunReport report = run_scene(scene, csv.get());
  if (csv_file) csv_file->commit();

  AtomicFile summary(dir / "summary.json");
  summary.stream() << summary_json(scene, report);
  summary.commit();

  if (!args.quiet) {
    std::cout << brief_report(scene, report);
    std::cout << "wrote " << (dir / "summary.json").string();
    if (scene.output.timeseries) std::cout << ", " << (dir / "timeseries.csv").string();
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
