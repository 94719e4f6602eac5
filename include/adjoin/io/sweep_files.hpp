#pragma once
// A sweep's files (study/sweep.hpp runs the sweep): the table, DIR/sweep.csv and
// DIR/sweep.json (or sweep.shard-I-of-N.*), and the journal, DIR/sweep.partial.csv (or
// sweep.shard-I-of-N.partial.csv), where each finished row is appended as it comes so that an
// interrupted sweep resumes from it.
//
//     SweepJournal journal(spec, shard, dir, &dropped);    // the rows an earlier sweep left
//     SweepOptions options;
//     options.indices = journal.pending();
//     options.sink = &journal;
//     run_sweep(spec, options);
//     write_sweep_table(sweep_table_file(spec, {sweep_columns(spec), journal.rows()}, shard), csv, json);
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "adjoin/study/sweep.hpp"

namespace adjoin {

// ---- the table ----

// sweep.json: {"sweep", "base", "fingerprint", "runs", "shard" ({"index","count"} or null),
// "columns": [{"name","type"}], "rows": [{column: value}]} with numbers as numbers and empty
// cells as null.
// A table (a shard's or a whole sweep's) with its bookkeeping, as sweep.json holds it.
struct SweepTableFile {
  std::filesystem::path file;  // where it was read from (empty if made here)
  std::string sweep, base, fingerprint;
  std::size_t runs = 0;
  SweepShard shard;
  SweepTable table;
};
SweepTableFile sweep_table_file(const SweepSpec& spec, SweepTable table, const SweepShard& shard);
std::string sweep_json(const SweepTableFile& table);
SweepTableFile read_sweep_json(const std::filesystem::path& file);
// Writes the table as CSV and JSON, a pair: neither file is replaced until both are written whole.
void write_sweep_table(const SweepTableFile& table, const std::filesystem::path& csv, const std::filesystem::path& json);

// Combines shard tables into the table of the whole sweep: same fingerprint and columns, every
// run exactly once (InputError naming the file otherwise).
SweepTableFile merge_sweep_tables(const std::vector<SweepTableFile>& parts);

// File names inside the output folder: "sweep" or "sweep.shard-I-of-N".
std::string sweep_file_stem(const SweepShard& shard);

// ---- the journal ----
// Line 1 "# adjoin sweep journal fingerprint=F runs=N shard=I/N", line 2 the CSV header,
// then one row per finished run, appended and flushed as each run ends (any order).

std::string sweep_journal_preamble(const SweepSpec& spec, const SweepShard& shard);
// Rows of a journal that match the spec and shard: returns what can be trusted ({} if the file
// does not exist). A torn last line is dropped quietly (an interrupted run); every other row
// that is not one of this sweep's (sweep_row_problem), and a journal of another sweep, is
// dropped with a "FILE:LINE: why" in `dropped`, so the caller can warn and run it again.
std::vector<std::vector<std::string>> read_sweep_journal(const std::filesystem::path& file,
                                                         const SweepSpec& spec, const SweepShard& shard,
                                                         std::vector<std::string>* dropped = nullptr);
// Why `cells` cannot be a row of this sweep and shard ("" if it can; *index is then its run):
// the cell count, the index, the axis values and motion of that run, the units, and every
// number finite (empty only where a run leaves it empty), counts and booleans well formed.
std::string sweep_row_problem(const SweepSpec& spec, const SweepShard& shard, const std::vector<std::string>& cells,
                              std::size_t* index);

// The journal of one shard of a sweep in `dir`, as the row sink of its run_sweep: opening it
// keeps the rows an earlier, interrupted sweep left that can be trusted (read_sweep_journal;
// `dropped` gets why the others were dropped) and rewrites the file with only them; take()
// appends each finished row and flushes it (InputError if the disk refuses).
class SweepJournal final : public SweepRowSink {
 public:
  SweepJournal(const SweepSpec& spec, const SweepShard& shard, const std::filesystem::path& dir,
               std::vector<std::string>* dropped = nullptr);
  const std::filesystem::path& path() const { return path_; }
  std::size_t from_journal() const { return from_journal_; }
  // The shard's runs the journal does not hold, in increasing order.
  const std::vector<std::size_t>& pending() const { return pending_; }
  void take(const SweepRow& row) override;
  // Every row of the shard held so far (from the journal and taken since), ordered by index.
  std::vector<std::vector<std::string>> rows() const;
  // Removes the file (once the table is written).
  void remove();

 private:
  const SweepSpec& spec_;
  std::filesystem::path path_;
  std::vector<std::vector<std::string>> rows_;
  std::size_t from_journal_ = 0;
  std::vector<std::size_t> pending_;
  std::ofstream out_;
};

}  // namespace adjoin
