// adjoin ida SCENE --suite RECORD|FOLDER... --im pga|sa:T --levels L1,L2,...|--trace
//            [--edp CH1,...] [--capacity "EXPR"] [--units U] [--jobs N] --out DIR
//
// Incremental dynamic analysis (SPEC §9; study/ida.hpp, io/ida_files.hpp). Each record is
// scaled (ground.scale) so that its IM, of the record as read, equals each level:
//  - stripes (--levels): one sweep over the (record, level) pairs, run by the sweep machinery
//    (threads; the journal DIR/sweep.partial.csv, so an interrupted IDA resumes); the sweep's
//    whole table is written too (DIR/sweep.csv, sweep.json);
//  - --trace: hunt and fill per record up to its capacity event (the run's collapse, a
//    numerical failure, or --capacity), the records in parallel.
// Writes DIR/ida.csv (record,im,scale,<edp>...) and DIR/ida.png (the curves with their 16/50/84 %
// fractiles), and a line per record on the terminal.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/folder_lock.hpp"
#include "adjoin/io/ida_files.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/study/ida.hpp"
#include "command.hpp"
#include "progress.hpp"
#include "sweep_shard.hpp"

namespace adjoin::cli {
namespace {

namespace fs = std::filesystem;

struct IdaArgs {
  std::string scene, im, levels, edp, capacity, units, out, format = "png";
  std::vector<std::string> suite;
  bool trace = false, quiet = false;
  unsigned jobs = 0;
  TraceOptions trace_options;
};

std::vector<double> parse_levels(const std::string& text) {
  std::vector<double> levels;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    double v = 0.0;
    if (!parse_finite(text.substr(start, comma - start), &v) || !(v > 0.0))
      throw InputError("--levels " + text_excerpt(text) + ": expected IM levels in g, numbers > 0 separated by commas (e.g. 0.1,0.2,0.4)");
    if (std::find(levels.begin(), levels.end(), v) != levels.end())
      throw InputError("--levels " + text_excerpt(text) + ": the level " + sweep_number_cell(v) + " appears twice");
    levels.push_back(v);
    start = comma + 1;
  }
  return levels;
}

std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    out.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

std::vector<IdaRecord> read_suite(const IdaArgs& args, const IntensityMeasure& im) {
  std::vector<std::string> skipped;
  auto records = read_ida_suite(args.suite, args.units, im, &skipped, "--units");
  for (const auto& s : skipped) std::cerr << "warning: --suite: " << s << " is not a record a reader recognises; skipped\n";
  return records;
}

std::string g(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.4g", v);
  return s;
}

// ---- stripes ----

std::vector<IdaRow> stripes(const IdaArgs& args, const std::vector<IdaRecord>& records, const std::vector<double>& levels,
                            std::vector<std::string>* edps, const fs::path& dir) {
  const SweepSpec spec = ida_sweep(args.scene, ida_stripe_motions(records, levels), args.units, "adjoin ida " + args.scene);
  if (edps->empty()) *edps = ida_default_edps(spec);
  check_ida_edps(spec, *edps, "--edp");
  const IdaCapacity capacity = ida_capacity(spec, args.capacity, "--capacity");
  check_sweep_memory(spec, spec.runs());
  auto cells = run_shard(spec, SweepShard{}, dir, args.jobs, !args.quiet, !args.quiet).rows;
  std::vector<IdaRow> rows = ida_stripe_rows(spec, cells, records, levels, *edps, capacity);
  write_sweep_table(sweep_table_file(spec, SweepTable{sweep_columns(spec), std::move(cells)}, SweepShard{}), dir / "sweep.csv",
                    dir / "sweep.json");
  std::filesystem::remove(dir / (sweep_file_stem(SweepShard{}) + ".partial.csv"));  // the journal
  return rows;
}

// ---- tracing ----

std::vector<IdaRow> traces(const IdaArgs& args, const std::vector<IdaRecord>& records, std::vector<std::string>* edps,
                           std::vector<Trace>* found) {
  Progress progress(!args.quiet, 0, records.size(), "records");
  IdaTraceRequest request;
  request.scene = args.scene;
  request.units = args.units;
  request.capacity = args.capacity;
  request.options = args.trace_options;
  request.jobs = args.jobs;
  request.name = "adjoin ida " + args.scene;
  request.on_record = [&] { progress.tick(); };
  std::vector<IdaRow> rows = ida_traces(request, records, edps, found);
  progress.finish();
  return rows;
}

// ---- the terminal ----

void summary(const IdaArgs& args, const std::vector<IdaRecord>& records, const std::vector<IdaRow>& rows,
             const std::vector<std::string>& edps, const std::vector<Trace>& found, const IntensityMeasure& im) {
  if (args.quiet) return;
  for (std::size_t k = 0; k < records.size(); ++k) {
    std::size_t runs = 0, events = 0, failed = 0;
    double edp_max = 0.0;
    for (const auto& r : rows) {
      if (r.record != records[k].name) continue;
      ++runs;
      events += r.event ? 1 : 0;
      failed += r.error.empty() ? 0 : 1;
      double v = 0.0;
      if (!r.edps.empty() && parse_finite(r.edps[0], &v)) edp_max = std::max(edp_max, v);
    }
    std::printf("%s: %s = %s g as read, %zu runs, largest %s %s", records[k].name.c_str(), im.text().c_str(),
                g(records[k].im).c_str(), runs, edps.empty() ? "" : edps[0].c_str(), g(edp_max).c_str());
    if (args.trace) {
      const Trace& t = found[k];
      if (t.bracketed()) {
        std::printf(", capacity between %s and %s g", g(*t.low).c_str(), g(*t.high).c_str());
        if (*t.high - *t.low > args.trace_options.tolerance * *t.low) std::printf(" (wider than --trace-tol: the run budget ran out)");
      }
      else std::printf(", no capacity event up to %s g (the run budget)", g(t.low ? *t.low : 0.0).c_str());
    } else {
      std::printf(", capacity events at %zu of %zu levels", events, runs);
    }
    if (failed) std::printf(" (%zu numerical failures, counted as capacity)", failed);
    std::printf("\n");
  }
}

int ida_command(const IdaArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  const IntensityMeasure im = parse_intensity_measure(args.im);
  if (args.trace == !args.levels.empty())
    throw InputError(args.trace ? "--levels and --trace: give one (stripes at given levels, or tracing per record)"
                                : "adjoin ida: expected --levels L1,L2,... (stripes) or --trace (hunt and fill per record)");
  std::vector<double> levels;
  if (!args.trace) levels = parse_levels(args.levels);
  else args.trace_options.check();
  std::vector<std::string> edps;
  if (!args.edp.empty()) edps = split_names(args.edp);
  const std::string extension = plot_extension(args.format);
  check_output_folder(args.out);
  const std::vector<IdaRecord> records = read_suite(args, im);
  const fs::path dir(args.out);
  OutputFolder folder(dir);
  folder.keep();
  // One writer at a time for the folder's journal and tables (the lock `adjoin sweep` takes).
  const FolderLock lock(dir, "sweep.lock", "adjoin ida " + args.scene + " --out " + args.out);
  std::vector<Trace> found;
  const std::vector<IdaRow> rows = args.trace ? traces(args, records, &edps, &found) : stripes(args, records, levels, &edps, dir);
  {
    AtomicFile csv(dir / "ida.csv");
    csv.stream() << ida_csv(edps, rows);
    csv.commit();
  }
  summary(args, records, rows, edps, found, im);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const fs::path image = dir / ("ida" + extension);
  PlotStyle style;
  style.format = args.format;
  const bool si = rows.empty() || rows[0].units == "SI";  // the demands are in the scene's units
  const std::string title = "IDA of " + fs::path(args.scene).stem().string();
  const auto draw = [&] { plot_ida(rows, 0, edps[0], im.text(), si, title, image, style); };
  const int status = edps.empty() ? 0 : draw_figure(draw, (dir / "ida.csv").string() + " written");
  if (!args.quiet)
    std::printf("ida: %zu runs in %.3g s (%.3g runs/s)\nwrote %s%s\n", rows.size(), seconds,
                static_cast<double>(rows.size()) / seconds, (dir / "ida.csv").string().c_str(),
                status ? "" : (", " + image.string()).c_str());
  return status;
}

const Registration registration(49, [](CLI::App& app) -> Runner {
  auto args = std::make_shared<IdaArgs>();
  auto* sub = app.add_subcommand("ida", "Incremental dynamic analysis: a scene x a suite x IM levels (stripes or tracing): ida.csv");
  sub->add_option("scene", args->scene, "Base scene (TOML); its ground is replaced by each record")->required();
  sub->add_option("--suite", args->suite, "Records: files, or folders of them (files a reader recognises)")->required();
  sub->add_option("--im", args->im, "Intensity measure: pga, or sa:T (the 5 %-damped PSA at T s), in g")->required();
  sub->add_option("--levels", args->levels, "Stripes: IM levels in g, e.g. 0.1,0.2,0.4");
  sub->add_flag("--trace", args->trace, "Hunt and fill per record up to its capacity event");
  sub->add_option("--edp", args->edp, "Demands: sweep-table columns, e.g. A.drift_ratio_max,contact1.impacts (default: docs/reference/cli.md)");
  sub->add_option("--capacity", args->capacity, "--trace: the capacity event, an expression as fragility's --event, e.g. \"A.drift_ratio_max > 0.05 or contact1.impacts > 0\"");
  sub->add_option("--trace-start", args->trace_options.start, "--trace: the first IM [g] (default 0.1)");
  sub->add_option("--trace-factor", args->trace_options.factor, "--trace: the hunt's step factor (default 1.5)");
  sub->add_option("--trace-tol", args->trace_options.tolerance, "--trace: the capacity bracket's relative width (default 0.05)");
  sub->add_option("--trace-runs", args->trace_options.budget, "--trace: runs per record (default 20)");
  sub->add_option("--units", args->units, "Units of records that do not state theirs (g, m/s2, cm/s2, mm/s2)");
  sub->add_option("--jobs,-j", args->jobs, "Threads (default: all local cores)");
  sub->add_option("--format", args->format, "Figure format: png (default) or svg");
  sub->add_option("--out", args->out, "Output folder: ida.csv, ida.png (stripes: sweep.csv, sweep.json)")->required();
  sub->add_flag("--quiet,-q", args->quiet, "No progress bar and no summary");
  return [args]() { return ida_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
