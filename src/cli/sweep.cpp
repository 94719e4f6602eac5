// adjoin sweep SWEEP.toml [--out DIR] [--jobs N] [--shard I/N] [--quiet]
// adjoin sweep merge DIR...|FILE... --out FILE      (also: adjoin sweep-merge ...)
//
// Runs every point of a sweep (study/sweep.hpp) on all local cores and writes DIR/sweep.csv and
// DIR/sweep.json (the same rows). Each finished run is appended to a journal,
// DIR/sweep.partial.csv, flushed per row: a rerun skips the runs it holds, and the final files
// are written (temporary file + rename) only when every run is done; the journal is then removed.
//
// --shard I/N runs only the indices i with i mod N == I (I from 0 to N-1) and writes
// DIR/sweep.shard-I-of-N.{csv,json}; `adjoin sweep merge` combines the shards into the table a
// single run would have written.
//
// MPI (built with -DADJOIN_WITH_MPI=ON): under mpirun with more than one rank, rank r runs shard
// r/size (with its own journal, so an interrupted MPI sweep resumes), and rank 0 gathers the rows
// and writes DIR/sweep.{csv,json}. Each rank uses (local cores / local ranks) threads unless --jobs.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/folder_lock.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/study/sweep.hpp"
#include "command.hpp"
#include "mpi_ranks.hpp"
#include "progress.hpp"
#include "sweep_shard.hpp"

#ifdef ADJOIN_WITH_MPI
#include <mpi.h>
#endif

namespace adjoin::cli {

ShardRows run_shard(const SweepSpec& spec, const SweepShard& shard, const std::filesystem::path& dir, unsigned jobs,
                    bool progress_bar, bool verbose) {
  std::vector<std::string> dropped;
  SweepJournal journal(spec, shard, dir, &dropped);
  constexpr std::size_t kShown = 10;
  for (std::size_t i = 0; i < dropped.size() && i < kShown; ++i)
    std::cerr << "warning: " << printable_message(dropped[i]) << "; that row is dropped and its run done again\n";
  if (dropped.size() > kShown)
    std::cerr << "warning: " << dropped.size() - kShown << " more rows of " << journal.path().string()
              << " dropped the same way (" << dropped.size() << " in all)\n";
  const std::size_t from_journal = journal.from_journal();
  if (from_journal > 0 && verbose)
    std::cerr << "resuming: " << from_journal << " runs from the journal " << journal.path().string() << "\n";
  if (!journal.pending().empty()) {
    Progress progress(progress_bar, journal.from_journal(), journal.from_journal() + journal.pending().size());
    SweepOptions options;
    options.jobs = jobs;
    options.indices = journal.pending();
    options.sink = &journal;
    options.on_row = [&](const SweepRow&) { progress.tick(); };
    try {
      run_sweep(spec, options);
    } catch (...) {
      progress.finish();
      throw;
    }
    progress.finish();
  }
  return ShardRows{journal.rows(), from_journal};
}

namespace {

struct SweepArgs {
  std::string sweep, out, shard;
  unsigned jobs = 0;
  bool quiet = false;
};

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string out;
};

SweepShard parse_shard(const std::string& text) {
  SweepShard shard;
  const auto slash = text.find('/');
  if (slash == std::string::npos || !parse_count(std::string_view(text).substr(0, slash), &shard.index) ||
      !parse_count(std::string_view(text).substr(slash + 1), &shard.count) || shard.count < 1 || shard.index >= shard.count)
    throw InputError("--shard " + text_excerpt(text) + ": expected I/N with 0 <= I < N (0-based: --shard 0/2 and --shard 1/2 make a whole)");
  return shard;
}

// The command as the lock file records it, for the message of a second sweep that finds it.
std::string command_text(const SweepArgs& args, const SweepShard& shard) {
  std::string text = "adjoin sweep " + args.sweep;
  if (!args.out.empty()) text += " --out " + args.out;
  if (!shard.whole()) text += " --shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count);
  return text;
}


// The runs of one shard (all runs for a whole sweep).
std::size_t shard_runs(const SweepSpec& spec, const SweepShard& shard) {
  return spec.runs() / shard.count + (shard.index < spec.runs() % shard.count ? 1 : 0);
}

std::size_t count_failed(const SweepTable& table) {
  return static_cast<std::size_t>(std::count_if(table.rows.begin(), table.rows.end(), [](const auto& r) { return !r.back().empty(); }));
}

std::filesystem::path output_dir(const SweepArgs& args, const SweepSpec& spec) {
  const std::filesystem::path dir = args.out.empty() ? std::filesystem::path("out") / spec.name : std::filesystem::path(args.out);
  OutputFolder folder(dir);  // kept: the journal and the lock live there while the sweep runs
  folder.keep();
  return dir;
}

void report(const SweepArgs& args, const SweepSpec& spec, const SweepTableFile& table, const std::filesystem::path& dir,
            const std::string& stem, double seconds, std::size_t from_journal) {
  if (args.quiet) return;
  const std::size_t failed = count_failed(table.table);
  std::printf("sweep %s: %zu runs", spec.name.c_str(), table.table.rows.size());
  if (!table.shard.whole()) std::printf(" (shard %zu/%zu of %zu)", table.shard.index, table.shard.count, spec.runs());
  if (from_journal) std::printf(" (%zu from the journal of an earlier, interrupted sweep)", from_journal);
  std::printf(" in %.3g s", seconds);
  if (failed) std::printf(", %zu stopped on a numerical failure (see the error column)", failed);
  std::printf("\nwrote %s, %s\n", (dir / (stem + ".csv")).string().c_str(), (dir / (stem + ".json")).string().c_str());
}

int sweep_local(const SweepArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  const SweepSpec spec = load_sweep(args.sweep);
  const SweepShard shard = args.shard.empty() ? SweepShard{} : parse_shard(args.shard);
  check_sweep_memory(spec, shard_runs(spec, shard));
  const std::filesystem::path dir = output_dir(args, spec);
  const std::string stem = sweep_file_stem(shard);
  // Held until the files are written and the journal removed: one sweep at a time per output.
  const FolderLock lock(dir, stem + ".lock", command_text(args, shard));
  auto [rows, from_journal] = run_shard(spec, shard, dir, args.jobs, !args.quiet, !args.quiet);
  SweepTable table{sweep_columns(spec), std::move(rows)};
  const SweepTableFile file = sweep_table_file(spec, std::move(table), shard);
  write_sweep_table(file, dir / (stem + ".csv"), dir / (stem + ".json"));
  std::filesystem::remove(dir / (stem + ".partial.csv"));
  report(args, spec, file, dir, stem,
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), from_journal);
  return 0;
}

#ifdef ADJOIN_WITH_MPI
int sweep_mpi(const SweepArgs& args, const MpiSession& mpi) {
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  std::string message;
  std::vector<std::vector<std::string>> mine_rows;
  SweepSpec spec;
  std::filesystem::path dir;
  const SweepShard shard{static_cast<std::size_t>(mpi.rank), static_cast<std::size_t>(mpi.size)};
  std::size_t from_journal = 0;
  std::unique_ptr<FolderLock> shard_lock, table_lock;  // held to the end, as in sweep_local
  try {
    if (!args.shard.empty()) throw InputError("--shard " + text_excerpt(args.shard) + ": not with mpirun (each rank runs shard RANK/SIZE)");
    spec = load_sweep(args.sweep);
    check_sweep_memory(spec, mpi.rank == 0 ? spec.runs() : shard_runs(spec, shard));  // rank 0 gathers every row
    dir = output_dir(args, spec);
    shard_lock = std::make_unique<FolderLock>(dir, sweep_file_stem(shard) + ".lock", command_text(args, shard));
    if (mpi.rank == 0) table_lock = std::make_unique<FolderLock>(dir, "sweep.lock", command_text(args, SweepShard{}));
    const unsigned jobs = threads_per_rank(args.jobs, mpi);
    auto result = run_shard(spec, shard, dir, jobs, !args.quiet && mpi.rank == 0, !args.quiet);
    from_journal = result.from_journal;
    mine_rows = std::move(result.rows);
  } catch (const std::exception&) {
    status = caught_status(&message);
  }
  if (const int worst = worst_status(status, message, mpi)) return worst;
  std::vector<std::vector<std::string>> gathered = gather_rows(mine_rows, mpi);
  // Every rank's journal rows, for rank 0's summary line.
  unsigned long long mine = from_journal, journal_rows = 0;
  MPI_Reduce(&mine, &journal_rows, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  int written = 0;
  if (mpi.rank == 0) {
    try {
      const SweepTableFile file = sweep_table_file(spec, SweepTable{sweep_columns(spec), std::move(gathered)}, SweepShard{});
      write_sweep_table(file, dir / "sweep.csv", dir / "sweep.json");
      written = 1;
      report(args, spec, file, dir, "sweep", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
             static_cast<std::size_t>(journal_rows));
      if (!args.quiet) std::printf("(%d MPI ranks)\n", mpi.size);
    } catch (const std::exception& e) {
      message = e.what();
    }
  }
  if (!share_status(written, mpi)) {
    if (mpi.rank == 0) throw InputError(message);
    return kExitInputError;
  }
  std::filesystem::remove(dir / (sweep_file_stem(shard) + ".partial.csv"));
  return 0;
}
#endif

int sweep_command(const SweepArgs& args) {
  if (args.sweep.empty()) throw InputError("adjoin sweep: expected a sweep file (adjoin sweep SWEEP.toml) or `adjoin sweep merge`");
#ifdef ADJOIN_WITH_MPI
  MpiSession mpi;
  if (mpi.size > 1) return sweep_mpi(args, mpi);
#else
  refuse_mpi_launcher_without_mpi("adjoin sweep", "sweep", "it uses every local core; --shard I/N splits a sweep over machines");
#endif
  return sweep_local(args);
}

// Where `sweep merge --out` writes: FILE.csv and FILE.json, or DIR/sweep.csv and DIR/sweep.json.
std::pair<std::filesystem::path, std::filesystem::path> merged_files(const std::string& out) {
  std::filesystem::path csv(out), json(out);
  if (csv.extension() == ".csv" || csv.extension() == ".json") {
    csv.replace_extension(".csv");
    json.replace_extension(".json");
  } else {
    csv = csv / "sweep.csv";
    json = json / "sweep.json";
  }
  return {csv, json};
}

int merge_command(const MergeArgs& args) {
  const auto [csv, json] = merged_files(args.out);
  const std::filesystem::path folder = csv.has_parent_path() ? csv.parent_path() : std::filesystem::path(".");
  check_output_folder(folder, folder == std::filesystem::path(args.out) ? "--out" : "--out " + args.out + ", its folder");
  // (before the tables are read)
  std::vector<std::filesystem::path> files;
  for (const auto& input : args.inputs) {
    const std::filesystem::path p(input);
    if (std::filesystem::is_directory(p)) {
      std::vector<std::filesystem::path> found;
      for (const auto& entry : std::filesystem::directory_iterator(p)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("sweep.shard-", 0) == 0 && entry.path().extension() == ".json") found.push_back(entry.path());
      }
      if (found.empty()) throw InputError(p.string() + ": no shard tables (sweep.shard-I-of-N.json) in this folder");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (p.extension() == ".csv") {
      // The CSV's sibling JSON carries the sweep's fingerprint and run count.
      files.push_back(std::filesystem::path(p).replace_extension(".json"));
    } else {
      files.push_back(p);
    }
  }
  std::vector<SweepTableFile> parts;
  for (const auto& f : files) parts.push_back(read_sweep_json(f));
  const SweepTableFile merged = merge_sweep_tables(parts);
  OutputFolder made(folder);  // made for the pair, removed again if it fails
  write_sweep_table(merged, csv, json);
  made.keep();
  std::printf("merged %zu tables: %zu runs of sweep %s\nwrote %s, %s\n", parts.size(), merged.table.rows.size(),
              merged.sweep.c_str(), csv.string().c_str(), json.string().c_str());
  return 0;
}

void add_merge_options(CLI::App* sub, const std::shared_ptr<MergeArgs>& args) {
  sub->add_option("tables", args->inputs, "Shard tables: folders holding sweep.shard-I-of-N.json, or .json/.csv files")->required();
  sub->add_option("--out", args->out, "Merged table: FILE.csv (and FILE.json beside it), or a folder")->required();
}

const Registration registration(50, "sweep", "Run a sweep (base scene x axes x ground motions): sweep.csv and sweep.json",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<SweepArgs>();
  auto merge = std::make_shared<MergeArgs>();
  sub->add_option("sweep", args->sweep, "Sweep file (TOML; docs/reference/sweep-file.md)");
  sub->add_option("--out", args->out, "Output folder (default out/<sweep name>/)");
  sub->add_option("--jobs,-j", args->jobs, "Threads (default: all local cores; under MPI, cores per local rank)");
  sub->add_option("--shard", args->shard, "Run only the runs i with i mod N == I (0-based I/N); merge the shards with `adjoin sweep merge`");
  sub->add_flag("--quiet,-q", args->quiet, "No progress bar and no summary");
  auto* merge_sub = sub->add_subcommand("merge", "Combine shard tables into the table of the whole sweep");
  add_merge_options(merge_sub, merge);
  return [args, merge, merge_sub]() { return merge_sub->parsed() ? merge_command(*merge) : sweep_command(*args); };
});

const Registration merge_registration(51, "sweep-merge", "The same as `adjoin sweep merge`",
                                      [](CLI::App* sub) -> Runner {
  auto merge = std::make_shared<MergeArgs>();
  add_merge_options(sub, merge);
  return [merge]() { return merge_command(*merge); };
});

}  // namespace
}  // namespace adjoin::cli
