// adjoin run SCENE.toml [--out DIR] [--set KEY=VALUE]... [--unset KEY]... [--quiet]
//
// Solves one scene and writes its files into DIR as one set (io/run_files.hpp decides which,
// from the scene's [output]). Prints a short summary on stdout unless --quiet.
#include <filesystem>
#include <iostream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/run_files.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/run_watch.hpp"
#include "command.hpp"
#include "progress.hpp"

namespace adjoin::cli {
namespace {

struct RunArgs {
  std::string scene;
  std::string out;
  std::vector<std::string> overrides;
  std::vector<std::string> unsets;
  bool quiet = false;
  bool allow_long = false;
};

int run_command(const RunArgs& args) {
  Scene scene = load_scene(args.scene, args.overrides, args.unsets);
  const auto warn = [](const std::string& warning) { std::cerr << "warning: " << warning << "\n"; };
  for (const auto& warning : scene.warnings) warn(warning);
  check_memory(scene);  // before the output folder is touched
  RunWatch::Options watching = watch_options(args.quiet, args.allow_long);
  watching.time_scale = scene.scales.time;
  watching.h_unit = scene.scales.si ? " s" : " (dimensionless)";
  RunWatch watch(std::move(watching));
  scene.watch = &watch;
  const std::filesystem::path dir = args.out.empty() ? std::filesystem::path("out") / scene.name : std::filesystem::path(args.out);
  const RunFiles files = run_to_folder(scene, dir, warn);
  if (!args.quiet) {
    std::cout << brief_report(scene, files.report, files.estimate ? &*files.estimate : nullptr,
                              files.tolerant ? &*files.tolerant : nullptr);
    std::cout << "wrote ";
    for (std::size_t i = 0; i < files.written.size(); ++i) std::cout << (i ? ", " : "") << files.written[i].string();
    std::cout << "\n";
  }
  return 0;
}

const Registration registration(10, "run", "Solve a scene: writes summary.json (and timeseries.csv if asked)",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<RunArgs>();
  sub->add_option("scene", args->scene, "Scene file (TOML)")->required();
  sub->add_option("--out", args->out, "Output folder (default out/<scene name>/)");
  sub->add_option("--set", args->overrides, "Override a scene key by dotted path, e.g. --set solver.h=0.001")
      ->allow_extra_args(false);
  sub->add_option("--unset", args->unsets,
                  "Remove a scene key or section before the --set overrides, e.g. --unset ground.scale_pga")
      ->allow_extra_args(false);
  sub->add_flag("--quiet,-q", args->quiet, "Print nothing on success");
  sub->add_flag("--allow-long", args->allow_long,
                "Run even when the run is estimated at more than 2 hours (refused otherwise)");
  return [args]() { return run_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
