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
// MPI (built with -DADJOIN_WITH_MPI=ON, under mpirun with more than one rank; mpi_ranks.hpp):
// stripes are shared out as `adjoin sweep` shares its runs (rank r runs shard r/size of the
// sweep, with its own journal), traces by record (rank r traces records k with k mod size ==
// r, in threads); rank 0 gathers the rows and writes every file, the same ida.csv whatever the
// number of ranks.
// Writes DIR/ida.csv (record,im,scale,<edp>...) and DIR/ida.png (the curves with their 16/50/84 %
// fractiles), and a line per record on the terminal.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/core/number_text.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/folder_lock.hpp"
#include "adjoin/io/ida_files.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/study/ida.hpp"
#include "command.hpp"
#include "mpi_ranks.hpp"
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

// What every process reads and checks before its runs.
struct IdaPlan {
  IntensityMeasure im;
  std::vector<double> levels;      // stripes
  std::vector<std::string> edps;   // as given (empty: the defaults, filled in with the runs)
  std::vector<IdaRecord> records;
};

IdaPlan plan_ida(const IdaArgs& args) {
  IdaPlan plan;
  plan.im = parse_intensity_measure(args.im);
  if (args.trace == !args.levels.empty())
    throw InputError(args.trace ? "--levels and --trace: give one (stripes at given levels, or tracing per record)"
                                : "adjoin ida: expected --levels L1,L2,... (stripes) or --trace (hunt and fill per record)");
  if (!args.trace) plan.levels = parse_levels(args.levels);
  else args.trace_options.check();
  if (!args.edp.empty()) plan.edps = split_names(args.edp);
  (void)plot_extension(args.format);
  check_output_folder(args.out);
  plan.records = read_suite(args, plan.im);
  return plan;
}

std::string lock_text(const IdaArgs& args) { return "adjoin ida " + args.scene + " --out " + args.out; }

// ---- stripes ----

// The stripes' sweep and its capacity event; `edps` filled in with the defaults when empty.
struct StripeSweep {
  SweepSpec spec;
  IdaCapacity capacity;
};

StripeSweep stripe_sweep(const IdaArgs& args, const IdaPlan& plan, std::vector<std::string>* edps) {
  StripeSweep s;
  s.spec = ida_sweep(args.scene, ida_stripe_motions(plan.records, plan.levels), args.units, "adjoin ida " + args.scene);
  if (edps->empty()) *edps = ida_default_edps(s.spec);
  check_ida_edps(s.spec, *edps, "--edp");
  s.capacity = ida_capacity(s.spec, args.capacity, "--capacity");
  check_sweep_memory(s.spec, s.spec.runs());
  return s;
}

// The rows of the whole sweep table `cells`; its sweep.csv and sweep.json written too.
std::vector<IdaRow> stripe_rows(const StripeSweep& s, const IdaPlan& plan, const std::vector<std::string>& edps,
                                std::vector<std::vector<std::string>> cells, const fs::path& dir) {
  std::vector<IdaRow> rows = ida_stripe_rows(s.spec, cells, plan.records, plan.levels, edps, s.capacity);
  write_sweep_table(sweep_table_file(s.spec, SweepTable{sweep_columns(s.spec), std::move(cells)}, SweepShard{}), dir / "sweep.csv",
                    dir / "sweep.json");
  return rows;
}

std::vector<IdaRow> stripes(const IdaArgs& args, const IdaPlan& plan, std::vector<std::string>* edps, const fs::path& dir) {
  const StripeSweep s = stripe_sweep(args, plan, edps);
  auto cells = run_shard(s.spec, SweepShard{}, dir, args.jobs, !args.quiet, !args.quiet).rows;
  std::vector<IdaRow> rows = stripe_rows(s, plan, *edps, std::move(cells), dir);
  std::filesystem::remove(dir / (sweep_file_stem(SweepShard{}) + ".partial.csv"));  // the journal
  return rows;
}

// ---- tracing ----

std::vector<IdaRow> traces(const IdaArgs& args, const std::vector<IdaRecord>& records, std::vector<std::string>* edps,
                           std::vector<Trace>* found, bool progress_bar) {
  Progress progress(progress_bar, 0, records.size(), "records");
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

// ---- the files and the terminal ----

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

// DIR/ida.csv, the terminal's lines and the figure; the figure's status (0 when drawn).
int write_ida(const IdaArgs& args, const IdaPlan& plan, const std::vector<IdaRow>& rows, const std::vector<std::string>& edps,
              const std::vector<Trace>& found, const fs::path& dir, std::chrono::steady_clock::time_point start, int ranks) {
  {
    AtomicFile csv(dir / "ida.csv");
    csv.stream() << ida_csv(edps, rows);
    csv.commit();
  }
  summary(args, plan.records, rows, edps, found, plan.im);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const fs::path image = dir / ("ida" + plot_extension(args.format));
  PlotStyle style;
  style.format = args.format;
  const bool si = rows.empty() || rows[0].units == "SI";  // the demands are in the scene's units
  const std::string title = "IDA of " + fs::path(args.scene).stem().string();
  const auto draw = [&] { plot_ida(rows, 0, edps[0], plan.im.text(), si, title, image, style); };
  const int status = edps.empty() ? 0 : draw_figure(draw, (dir / "ida.csv").string() + " written");
  if (!args.quiet) {
    std::printf("ida: %zu runs in %.3g s (%.3g runs/s)", rows.size(), seconds, static_cast<double>(rows.size()) / seconds);
    if (ranks > 1) std::printf(" on %d MPI ranks", ranks);
    std::printf("\nwrote %s%s\n", (dir / "ida.csv").string().c_str(), status ? "" : (", " + image.string()).c_str());
  }
  return status;
}

int ida_local(const IdaArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  const IdaPlan plan = plan_ida(args);
  const fs::path dir(args.out);
  OutputFolder folder(dir);
  folder.keep();
  // One writer at a time for the folder's journal and tables (the lock `adjoin sweep` takes).
  const FolderLock lock(dir, "sweep.lock", lock_text(args));
  std::vector<std::string> edps = plan.edps;
  std::vector<Trace> found;
  const std::vector<IdaRow> rows = args.trace ? traces(args, plan.records, &edps, &found, !args.quiet) : stripes(args, plan, &edps, dir);
  return write_ida(args, plan, rows, edps, found, dir, start, 1);
}

#ifdef ADJOIN_WITH_MPI
// ---- MPI ----

// A rank's traces as text for the gather: per record (its index k in the suite) a line
// "T,k,low,high" (empty: none) and its rows "R,k,im,scale,units,error,event,edp...", numbers
// in their shortest round-trip form.
std::string trace_text(const std::vector<std::size_t>& indices, const std::vector<IdaRow>& rows, const std::vector<Trace>& found,
                       const std::vector<IdaRecord>& records) {
  const auto maybe = [](const std::optional<double>& v) { return v ? shortest_text(*v) : std::string(); };
  std::string text;
  for (std::size_t j = 0; j < indices.size(); ++j) {
    const std::string k = std::to_string(indices[j]);
    text += csv_line({"T", k, maybe(found[j].low), maybe(found[j].high)}) + "\n";
    for (const IdaRow& r : rows) {
      if (r.record != records[indices[j]].name) continue;
      std::vector<std::string> cells{"R", k, shortest_text(r.im), shortest_text(r.scale), r.units, r.error, r.event ? "1" : "0"};
      cells.insert(cells.end(), r.edps.begin(), r.edps.end());
      text += csv_line(cells) + "\n";
    }
  }
  return text;
}

// Rank 0: every rank's traces back in the suite's order.
std::vector<IdaRow> traces_from_text(const std::vector<std::string>& parts, const std::vector<IdaRecord>& records,
                                     std::vector<Trace>* found) {
  std::vector<std::vector<IdaRow>> per_record(records.size());
  found->assign(records.size(), Trace{});
  const auto number = [](const std::string& cell) {
    double v = 0.0;
    parse_finite(cell, &v);
    return v;
  };
  for (const std::string& part : parts) {
    std::istringstream in(part);
    for (std::string line; std::getline(in, line);) {
      std::vector<std::string> c;
      split_csv_line(line, &c);
      std::size_t k = 0;
      parse_count(c.at(1), &k);
      if (c[0] == "T") {
        if (!c.at(2).empty()) (*found)[k].low = number(c[2]);
        if (!c.at(3).empty()) (*found)[k].high = number(c[3]);
        continue;
      }
      IdaRow row;
      row.record = records.at(k).name;
      row.im = number(c.at(2));
      row.scale = number(c.at(3));
      row.units = c.at(4);
      row.error = c.at(5);
      row.event = c.at(6) == "1";
      row.edps.assign(c.begin() + 7, c.end());
      per_record[k].push_back(std::move(row));
    }
  }
  std::vector<IdaRow> rows;
  for (auto& r : per_record) rows.insert(rows.end(), r.begin(), r.end());
  return rows;
}

int exit_status_of(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const InputError&) {
    return kExitInputError;
  } catch (...) {
    return kExitNumericalError;
  }
}

int ida_mpi(const IdaArgs& args, const MpiSession& mpi) {
  const auto start = std::chrono::steady_clock::now();
  const bool root = mpi.rank == 0;
  const SweepShard shard{static_cast<std::size_t>(mpi.rank), static_cast<std::size_t>(mpi.size)};
  const fs::path dir(args.out);
  int status = 0;
  std::string message;
  IdaPlan plan;
  std::vector<std::string> edps;
  StripeSweep sweep;
  std::vector<std::vector<std::string>> mine;  // stripes: this shard's sweep rows
  std::string traced;                          // traces: this rank's records
  std::unique_ptr<OutputFolder> folder;
  std::unique_ptr<FolderLock> shard_lock, table_lock;  // held to the end, as in ida_local
  try {
    plan = plan_ida(args);
    edps = plan.edps;
    folder = std::make_unique<OutputFolder>(dir);
    folder->keep();
    shard_lock = std::make_unique<FolderLock>(dir, sweep_file_stem(shard) + ".lock", lock_text(args) + " (MPI rank " + std::to_string(mpi.rank) + ")");
    if (root) table_lock = std::make_unique<FolderLock>(dir, "sweep.lock", lock_text(args));
    if (args.trace) {
      std::vector<std::size_t> indices;
      std::vector<IdaRecord> records;
      for (std::size_t k = shard.index; k < plan.records.size(); k += shard.count) {
        indices.push_back(k);
        records.push_back(plan.records[k]);
      }
      if (!records.empty()) {
        IdaArgs own = args;
        own.jobs = threads_per_rank(args.jobs, mpi);
        std::vector<Trace> found;
        const std::vector<IdaRow> rows = traces(own, records, &edps, &found, !args.quiet && root);
        traced = trace_text(indices, rows, found, plan.records);
      }
    } else {
      sweep = stripe_sweep(args, plan, &edps);
      mine = run_shard(sweep.spec, shard, dir, threads_per_rank(args.jobs, mpi), !args.quiet && root, !args.quiet).rows;
    }
  } catch (const std::exception&) {
    status = caught_status(&message);
  }
  if (const int worst = worst_status(status, message, mpi)) return worst;
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> parts;
  if (args.trace) parts = gather_text(traced, mpi);
  else cells = gather_rows(mine, mpi);
  int outcome = 0, failed = 0;  // rank 0's figure status; its failure's exit status
  std::exception_ptr failure;
  if (root) {
    try {
      std::vector<Trace> found;
      const std::vector<IdaRow> rows =
          args.trace ? traces_from_text(parts, plan.records, &found) : stripe_rows(sweep, plan, edps, std::move(cells), dir);
      outcome = write_ida(args, plan, rows, edps, found, dir, start, mpi.size);
    } catch (...) {
      failure = std::current_exception();
      failed = exit_status_of(failure);
    }
  }
  if (share_status(failed, mpi)) {
    if (failure) std::rethrow_exception(failure);
    return failed;  // the ranks' journals stay: run again, it resumes
  }
  if (!args.trace) std::filesystem::remove(dir / (sweep_file_stem(shard) + ".partial.csv"));  // this rank's journal
  return outcome;
}
#endif

int ida_command(const IdaArgs& args) {
#ifdef ADJOIN_WITH_MPI
  MpiSession mpi;
  if (mpi.size > 1) return ida_mpi(args, mpi);
#else
  refuse_mpi_launcher_without_mpi("adjoin ida", "study", "it uses every local core");
#endif
  return ida_local(args);
}

const Registration registration(49, "ida", "Incremental dynamic analysis: a scene x a suite x IM levels (stripes or tracing): ida.csv",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<IdaArgs>();
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
  sub->add_option("--jobs,-j", args->jobs, "Threads (default: all local cores; under MPI, cores per local rank)");
  sub->add_option("--format", args->format, "Figure format: png (default) or svg");
  sub->add_option("--out", args->out, "Output folder: ida.csv, ida.png (stripes: sweep.csv, sweep.json)")->required();
  sub->add_flag("--quiet,-q", args->quiet, "No progress bar and no summary");
  return [args]() { return ida_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
