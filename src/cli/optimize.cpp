// adjoin optimize STUDY.toml [--jobs N] --out DIR [--format png|svg] [--quiet]
//
// Design optimisation (SPEC §9; io/optimize_study.hpp reads the study and runs it,
// study/optimize.hpp searches): writes DIR/evaluations.csv (every design evaluated),
// DIR/optimum.json (the best design, its objective, the count of evaluations, the searches and
// the convergence history) and DIR/optimum.png (the convergence, or the Pareto front). Each
// design's suite runs on --jobs threads. DIR/evaluations.cache.csv keeps every design's
// demands: a rerun of the same study with the same --out takes them from there.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "adjoin/io/folder_lock.hpp"
#include "adjoin/io/optimize_study.hpp"
#include "adjoin/io/output_place.hpp"
#include "command.hpp"

namespace adjoin::cli {
namespace {

namespace fs = std::filesystem;

struct OptimizeArgs {
  std::string study, out, format = "png";
  unsigned jobs = 0;
  bool quiet = false;
};

void report(const OptimizeStudy& study, const OptimizeOutcome& outcome) {
  const OptimizeResult& r = outcome.result;
  std::printf("optimize %s: %s, %zu designs x %zu runs (%zu runs now, %zu designs from the cache) in %.3g s\n",
              study.name.c_str(), study.options.method.c_str(), r.evaluations.size(), study.runs(), outcome.runs,
              outcome.from_cache, outcome.seconds);
  if (!r.best) return;
  const Evaluation& b = r.evaluations[*r.best];
  std::printf("%s: %s = %.6g at", study.objectives.size() == 2 ? "front's first point" : "optimum",
              study.objectives[0].name().c_str(), b.values.objectives[0]);
  if (!study.placements.empty()) std::printf(" %s", study.choice_label(b.choice).c_str());
  for (std::size_t i = 0; i < study.variables.size(); ++i)
    std::printf("%s %s = %.6g", i || !study.placements.empty() ? "," : "", study.variables[i].key.c_str(), b.x[i]);
  std::printf("%s\n", b.feasible ? "" : " (no design meets the constraints: the least violating)");
  if (study.objectives.size() == 2) std::printf("Pareto front: %zu designs\n", r.pareto.size());
}

int optimize_command(const OptimizeArgs& args) {
  const std::string extension = plot_extension(args.format);
  check_output_folder(args.out);
  std::vector<std::string> skipped;
  const OptimizeStudy study = load_optimize_study(args.study, &skipped);
  for (const auto& s : skipped) std::cerr << "warning: suite: " << s << " is not a record a reader recognises; skipped\n";
  const fs::path dir(args.out);
  OutputFolder folder(dir);
  folder.keep();
  const FolderLock lock(dir, "optimize.lock", "adjoin optimize " + args.study + " --out " + args.out);
  OptimizeRequest request;
  request.jobs = args.jobs;
  request.dir = dir;
  if (!args.quiet)
    request.on_evaluation = [](std::size_t n, bool cached) {
      std::fprintf(stderr, "\rdesign %zu%s   ", n, cached ? " (cache)" : "");
      std::fflush(stderr);
    };
  const OptimizeOutcome outcome = run_optimize_study(study, request);
  if (!args.quiet) std::fprintf(stderr, "\n");
  write_optimize_files(study, outcome, dir);
  const fs::path image = dir / ("optimum" + extension);
  PlotStyle style;
  style.format = args.format;
  const int status = draw_figure([&] { plot_optimize(study, outcome, image, style); },
                                 (dir / "optimum.json").string() + " written");
  if (!args.quiet) {
    report(study, outcome);
    std::printf("wrote %s, %s%s\n", (dir / "optimum.json").string().c_str(), (dir / "evaluations.csv").string().c_str(),
                status ? "" : (", " + image.string()).c_str());
  }
  return status;
}

const Registration registration(55, "optimize", "Optimise damper parameters and placements over a suite (a study file): optimum.json",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<OptimizeArgs>();
  sub->add_option("study", args->study, "Study file (TOML, [optimize]: docs/reference/study-file.md)")->required();
  sub->add_option("--jobs,-j", args->jobs, "Threads for each design's runs (default: all local cores)");
  sub->add_option("--format", args->format, "Figure format: png (default) or svg");
  sub->add_option("--out", args->out, "Output folder: optimum.json, evaluations.csv, optimum.png, evaluations.cache.csv")->required();
  sub->add_flag("--quiet,-q", args->quiet, "No progress and no summary");
  return [args]() { return optimize_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
