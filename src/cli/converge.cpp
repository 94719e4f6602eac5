// adjoin converge SCENE [--set K=V]... [--unset K]... [--schemes LIST] [--history LIST] [--steps LIST]
//                       [--out DIR] [--plot FILE | --no-plot]
//
// Error against run time for each scheme and history engine on a ladder of steps: prints a
// table, writes DIR/convergence.csv and draws DIR/work-precision.png (gnuplot). A building
// scene's ladder is the structure step's, with every channel's peak among the quantities.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/table_plots.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/io/two_block_names.hpp"
#include "adjoin/study/convergence.hpp"
#include "adjoin/study/run_watch.hpp"
#include "command.hpp"
#include "progress.hpp"

namespace adjoin::cli {
namespace {

struct ConvergeArgs {
  std::string scene, out, plot;
  std::vector<std::string> overrides, unsets, schemes, engines;
  std::vector<double> steps;
  bool no_plot = false;
  bool allow_long = false;
};

std::string cell(double v, const char* format = "%.3e") {
  if (std::isnan(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// convergence-quantities.csv: every reported quantity's error and observed order on each rung
// (instants in the scene's time unit). False (and nothing written: the set then removes an
// earlier run's file) against an analytic reference, which gives only the trajectory.
bool write_quantities(const ConvergenceResult& result, double time_unit, FileSet& files) {
  bool any = false;
  for (const auto& r : result.rows) any = any || !r.quantities.empty();
  if (!any) return false;
  std::ostream& csv = files.open("convergence-quantities.csv");
  csv << "scheme,history,h,quantity,kind,error,order\n";
  for (const auto& r : result.rows)
    for (const auto& q : r.quantities)
      csv << r.scheme << "," << r.history << "," << cell(r.h * time_unit, "%.10g") << "," << q.name << ","
          << (q.instant ? "absolute" : "relative") << "," << cell(q.error * (q.instant ? time_unit : 1.0), "%.6e") << ","
          << (std::isnan(q.order) ? "" : cell(q.order, "%.4f")) << "\n";
  return true;
}

// convergence.csv: a row per rung (h in the scene's time unit).
void write_table(const ConvergenceResult& result, double time_unit, std::ostream& csv) {
  csv << "scheme,history,h,steps,wall_seconds,error,order,err_peak_x1,err_min_gap,err_friction\n";
  for (const auto& r : result.rows) {
    auto v = [](double x) { return std::isnan(x) ? std::string() : std::to_string(x); };
    csv << r.scheme << "," << r.history << "," << cell(r.h * time_unit, "%.10g") << "," << r.steps << "," << v(r.wall_seconds)
        << "," << (std::isnan(r.error) ? "" : cell(r.error, "%.6e")) << "," << v(r.order) << ","
        << (std::isnan(r.peak_a1) ? "" : cell(r.peak_a1, "%.6e")) << ","
        << (std::isnan(r.min_gap) ? "" : cell(r.min_gap, "%.6e")) << ","
        << (std::isnan(r.friction) ? "" : cell(r.friction, "%.6e")) << "\n";
  }
}

// One table per (scheme, history) ladder: a row per quantity, a column per step, "error
// (order)". Switching instants beyond the first 12 are in the CSV only.
void print_quantities(const ConvergenceResult& result, double time_unit) {
  for (std::size_t begin = 0; begin < result.rows.size();) {
    std::size_t end = begin;
    while (end < result.rows.size() && result.rows[end].scheme == result.rows[begin].scheme &&
           result.rows[end].history == result.rows[begin].history)
      ++end;
    const auto& first = result.rows[begin];
    std::printf("\nevery reported quantity, %s/%s: error (observed order); values relative, instants in the "
                "scene's time unit\n%-16s", first.scheme.c_str(), first.history.c_str(), "h =");
    for (std::size_t i = begin; i < end; ++i) std::printf(" %20.4g", result.rows[i].h * time_unit);
    std::printf("\n");
    std::vector<std::string> names;
    for (std::size_t i = begin; i < end; ++i)
      for (const auto& q : result.rows[i].quantities)
        if (std::find(names.begin(), names.end(), q.name) == names.end()) names.push_back(q.name);
    int switches = 0, hidden = 0;
    for (const auto& name : names) {
      if (name.find("switch ") != std::string::npos && ++switches > 12) { ++hidden; continue; }
      std::printf("%-16s", name.c_str());
      for (std::size_t i = begin; i < end; ++i) {
        std::string text = "-";
        for (const auto& q : result.rows[i].quantities)
          if (q.name == name)
            text = cell(q.error * (q.instant ? time_unit : 1.0), "%.2e") + " (" + cell(q.order, "%.2f") + ")";
        std::printf(" %20s", text.c_str());
      }
      std::printf("\n");
    }
    if (hidden > 0) std::printf("(%d more switching instants in convergence-quantities.csv)\n", hidden);
    for (std::size_t i = begin; i < end; ++i)
      if (result.rows[i].switches_differ)
        std::printf("h = %.4g: the sequence of phases differs from the reference's; its switching instants are not compared\n",
                    result.rows[i].h * time_unit);
    begin = end;
  }
  std::printf("\n");
}

// The history engines named by --history (the default when none).
std::vector<HistoryEngine> engines_of(const ConvergeArgs& args, std::vector<HistoryEngine> fallback) {
  if (args.engines.empty()) return fallback;
  std::vector<HistoryEngine> engines;
  for (const auto& name : args.engines) {
    HistoryEngine e;
    if (!parse_enum(name, &e)) throw InputError("--history: " + escaped_excerpt(name) + " must be " + join_names(names<HistoryEngine>(), "", ", ", " or "));
    engines.push_back(e);
  }
  return engines;
}

int write_and_print(const ConvergeArgs& args, const ConvergenceResult& result, const std::string& name, double time_unit);
std::filesystem::path output_folder(const ConvergeArgs& args, const std::string& name);
void check_steps(const ConvergeArgs& args, double scene_h, double t_end, const std::string& unit);

// The schemes named by --schemes (none: run_convergence's defaults). A building scene (SPEC
// §5) runs the structure step: --schemes may name one of its two restart rules (as
// solver.scheme does), instead of the scene's.
std::vector<Scheme> schemes_of(const ConvergeArgs& args, bool two_block) {
  std::vector<Scheme> schemes;
  if (!two_block && args.schemes.size() > 1)
    throw InputError("--schemes: building scenes take one scheme, implicit or implicit-damped");
  for (const auto& name : args.schemes) {
    Scheme s;
    const bool known = parse_enum(name, &s);
    if (!two_block && !(known && (s == Scheme::implicit || s == Scheme::implicit_damped)))
      throw InputError("--schemes: " + escaped_excerpt(name) + ": building scenes run the structure step, implicit or "
                       "implicit-damped; the other schemes are the two-block system's");
    if (!known) throw InputError("--schemes: " + escaped_excerpt(name) + " is not a scheme; expected " + scheme_names());
    schemes.push_back(s);
  }
  return schemes;
}

int converge_command(const ConvergeArgs& args) {
  if (!args.plot.empty()) {  // a bad image name is found before the ladder runs
    PlotStyle style;
    plot_target(args.plot, {}, "", &style, "--plot");
  }
  Scene scene = load_scene(args.scene, args.overrides, args.unsets);
  for (const auto& warning : scene.warnings) std::cerr << "warning: " << warning << "\n";
  const bool two_block = scene.two_block();
  // Steps and instants in the scene's time unit (seconds, or a dimensionless scene's).
  const double time_unit = scene.scales.time;
  RunWatch::Options watching = watch_options(false, args.allow_long);  // each run of the ladder: estimated, shown
  watching.time_scale = time_unit;
  watching.h_unit = scene.scales.si ? " s" : " (dimensionless)";
  RunWatch watch(std::move(watching));
  scene.watch = &watch;
  ConvergenceOptions options;
  options.schemes = schemes_of(args, two_block);
  options.engines = engines_of(args, {two_block ? HistoryEngine::direct : HistoryEngine::soe});
  for (double h : args.steps) options.steps.push_back(h / time_unit);
  std::string error;
  if (!options.IsValid(&error)) throw InputError((two_block ? "--steps/--schemes/--history: " : "--steps/--history: ") + error);
  check_steps(args, scene.solver.h * time_unit, scene.solver.t_end * time_unit, scene.scales.si ? " s" : "");
  check_output_folder(output_folder(args, scene.name));  // before the ladder runs
  ConvergenceResult result = run_convergence(scene, options);
  if (two_block)  // shown under SPEC §3's names (io/two_block_names.hpp)
    for (auto& row : result.rows)
      for (auto& q : row.quantities) q.name = two_block_quantity_name(q.name);
  return write_and_print(args, result, scene.name, time_unit);
}

// The output folder: --out, or out/<scene name>/.
std::filesystem::path output_folder(const ConvergeArgs& args, const std::string& name) {
  return args.out.empty() ? std::filesystem::path("out") / name : std::filesystem::path(args.out);
}

// Every step of the ladder (in the scene's time unit) must fit in the run: a step longer than
// t_end is a run of less than one step.
void check_steps(const ConvergeArgs& args, double scene_h, double t_end, const std::string& unit) {
  const auto steps_of = [&](double h) { return cell(t_end / h, "%.3g"); };
  for (double h : args.steps)
    if (h > t_end)
      throw InputError("--steps " + cell(h, "%g") + ": longer than the run: t_end = " + cell(t_end, "%g") + unit +
                       " is " + steps_of(h) + " steps of it; every step must be at most t_end (several steps per run)");
  if (args.steps.empty() && 4.0 * scene_h > t_end)
    throw InputError("--steps (default: the scene's h times 4,2,1,1/2,1/4): the coarsest step, 4 h = " +
                     cell(4.0 * scene_h, "%g") + unit + ", is longer than the run (t_end = " + cell(t_end, "%g") + unit +
                     "); give --steps no longer than t_end");
}

// Whether the work-precision figure has a point: a rung with an error and a measured time
// (the figure's log axes take positive values only), as convergence.csv spells them.
bool has_figure_point(const ConvergenceResult& result) {
  return std::any_of(result.rows.begin(), result.rows.end(), [](const ConvergenceRow& r) {
    return r.error > 0.0 && std::isfinite(r.error) && std::stod(std::to_string(r.wall_seconds)) > 0.0;
  });
}

// convergence.csv, convergence-quantities.csv and the work-precision figure in --out, and the
// tables on stdout; h and instants in the scene's time unit (`time_unit` per solver unit). The
// CSVs are one set: committed only once the figure is drawn (from the finished table), so a
// failure leaves the folder as it was.
int write_and_print(const ConvergeArgs& args, const ConvergenceResult& result, const std::string& name, double time_unit) {
  const std::filesystem::path dir = output_folder(args, name);
  const auto csv_path = dir / "convergence.csv", quantities_path = dir / "convergence-quantities.csv";
  FileSet files(dir, {"convergence.csv", "convergence-quantities.csv"});
  write_table(result, time_unit, files.open("convergence.csv"));

  std::printf("convergence of %s; errors against %s\n", name.c_str(), result.reference.c_str());
  std::printf("%-12s %-7s %10s %8s %10s %10s %6s %10s %10s %10s\n", "scheme", "history", "h", "steps", "wall [s]",
              "error", "order", "peak x1", "min gap", "friction");
  for (const auto& r : result.rows) {
    if (r.failed) {
      std::printf("%-12s %-7s %10.4g %8zu   stopped: %s\n", r.scheme.c_str(), r.history.c_str(), r.h * time_unit,
                  r.steps, r.message.c_str());
      continue;
    }
    std::printf("%-12s %-7s %10.4g %8zu %10.4g %10s %6s %10s %10s %10s\n", r.scheme.c_str(), r.history.c_str(),
                r.h * time_unit, r.steps, r.wall_seconds, cell(r.error).c_str(), cell(r.order, "%.2f").c_str(),
                cell(r.peak_a1).c_str(), cell(r.min_gap).c_str(), cell(r.friction).c_str());
  }
  const bool quantities = write_quantities(result, time_unit, files);
  if (quantities) print_quantities(result, time_unit);
  std::filesystem::path image;
  if (!args.no_plot) {
    if (!has_figure_point(result))
      throw InputError(csv_path.string() + ": no rung with an error > 0 and a measured run time: nothing to draw on the "
                       "work-precision figure's log axes (see the table above); --no-plot writes the tables alone");
    PlotStyle style;
    image = plot_target(args.plot, dir / "work-precision.png", "", &style, "--plot");
    plot_convergence_csv(files.finish("convergence.csv"), image, style, name + " (reference: " + result.reference + ")");
  }
  files.commit();
  std::printf("wrote %s", csv_path.string().c_str());
  if (quantities) std::printf(", %s", quantities_path.string().c_str());
  if (!image.empty()) std::printf(", %s", image.string().c_str());
  std::printf("\n");
  return 0;
}

const Registration registration(40, "converge", "Error against run time for each scheme and history engine on a ladder of steps",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<ConvergeArgs>();
  sub->add_option("scene", args->scene, "Scene file (TOML)")->required();
  sub->add_option("--set", args->overrides, "Override a scene key by dotted path")->allow_extra_args(false);
  sub->add_option("--unset", args->unsets, "Remove a scene key or section before the --set overrides (e.g. --unset link)")
      ->allow_extra_args(false);
  sub->add_option("--schemes", args->schemes, "Schemes to compare (default paper,implicit-gl,implicit)")->delimiter(',');
  sub->add_option("--history", args->engines, "History engines (default: direct for a two-block scene, soe for a building)")->delimiter(',');
  sub->add_option("--steps", args->steps, "Steps h in the scene's time unit (default: the scene's h times 4,2,1,1/2,1/4)")
      ->delimiter(',');
  sub->add_option("--out", args->out, "Output folder (default out/<scene name>/)");
  sub->add_option("--plot", args->plot, "Work-precision plot file (.png or .svg; default DIR/work-precision.png)");
  sub->add_flag("--no-plot", args->no_plot, "Do not draw the plot");
  sub->add_flag("--allow-long", args->allow_long,
                "Run even when a run is estimated at more than 2 hours (refused otherwise)");
  return [args]() { return converge_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
