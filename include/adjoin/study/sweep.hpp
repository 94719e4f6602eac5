#pragma once
// Sweeps for damper design (SPEC §2 "Studies"): a base scene, axes over any scene key, and a
// set of ground motions; one run per point of their cartesian product, one table row per run.
//
//     SweepSpec spec = load_sweep("examples/sweeps/slip-force.toml");   // io/sweep_file.hpp
//     std::vector<SweepRow> rows = run_sweep(spec);          // all local cores
//     SweepTable table = sweep_table(spec, rows);            // the CSV/JSON cells
//
// Order. Run i has coordinates (axis 0 value, axis 1 value, ..., motion): the first axis varies
// slowest and the motion fastest, i = ((v0 n1 + v1) n2 + ...) n_motions + m. Rows are placed by
// index, so the table is the same whatever the parallelism (threads, shards, MPI ranks).
//
// A run's description is the base scene with the run's edits (the axis values, then the
// motion), exactly like `adjoin run BASE --set KEY=VALUE...`; the sweep asks spec.scenes for it
// (SweepScenes: io reads the base once and applies the edits, io/sweep_scenes.hpp). It is
// integrated with the observers run() uses (peaks, phases, pounding, energy) plus the
// ground-motion intensity measures of the forcing the solver actually saw (PGA; Sa(T, damping)
// at the sweep's im_periods). A NumericalError is recorded in the row's `error`; an InputError
// stops the sweep with the sweep file, the run and the key. Its columns are read from the
// run's Report by the base scene's registry (study/sweep_columns.hpp): SPEC §3's names for a
// scene written with the two-block keys, a structure's channels otherwise. Finished rows go to a SweepRowSink (io's
// journal, io/sweep_files.hpp, is the one a resumed sweep reads back).
//
// Values are in the base scene's units (SI scenes: m, N, m/s^2, J); energy shares are ratios to
// the input energy; pga_g and sa_T are in g with T in seconds (a dimensionless scene: T in its
// time unit, i.e. ground.time_scale seconds for a record, 1 otherwise).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin {

namespace structure {
struct Structure;
}

enum class ColumnType { integer, number, boolean, string };

struct SweepColumn {
  std::string name;
  ColumnType type;
  // A link's or contact's cell that a run without that element leaves empty (building sweeps:
  // a run that unsets every link); other integer and boolean cells are empty only in failed runs.
  bool may_be_empty = false;
};

// One item of a list value, or a plain value: a number, a string or true/false.
using SweepScalar = std::variant<std::int64_t, double, bool, std::string>;

// The value an edit gives a scene key: typed, as the sweep file wrote it, with its spelling as
// a TOML value (what a --set of it would say, for messages). A list value (link.1.floors =
// [3, 3]) holds its items; lists of lists are not scene values.
struct SweepValue {
  std::variant<std::int64_t, double, bool, std::string, std::vector<SweepScalar>> value;
  std::string text;
};

// Values made in code (adjoin optimize, ida), spelled as a --set of them would be: a double as
// a TOML float (2.0 as "2.0", 2e5 as "2e+05"), a string quoted, a list as "[3, 3]".
//     spec.axes[0].values[0].set.emplace_back("link.1.floors", sweep_value({std::int64_t{2}, std::int64_t{3}}));
SweepValue sweep_value(double v);
SweepValue sweep_value(std::int64_t v);
SweepValue sweep_value(bool v);
SweepValue sweep_value(const std::string& v);
SweepValue sweep_value(std::vector<SweepScalar> items);
// The TOML spelling of one scalar (what sweep_value(...).text is for it).
std::string sweep_value_text(const SweepScalar& v);

// One value of an axis, or one ground motion: a label for the table and the scene edits it makes.
struct SweepSetting {
  std::string label;                    // the table cell (an axis value) or the motion's name
  std::optional<double> number;         // the value, when it is a number (label = shortest repr)
  std::vector<std::string> unset;       // dotted keys removed from the base scene first
  std::vector<std::pair<std::string, SweepValue>> set;  // dotted key -> value
  std::size_t line = 0;                 // where it was written in the sweep file
  // "--set" style strings "key=value", in order.
  std::vector<std::string> overrides() const;
};

struct SweepAxis {
  std::string name;  // column header: `name`, or the key
  std::string key;   // the scene key a plain value sets (empty if every value is a set of edits)
  std::vector<SweepSetting> values;
  std::size_t line = 0;  // in the sweep file
};

struct SweepSpec;
struct SweepChannel;  // study/sweep_columns.hpp
struct SweepRow;

// How a run's description is made from the base scene and the run's edits. io implements it
// with its scene reader (io/sweep_scenes.hpp); the sweep file's reader gives every spec one.
class SweepScenes {
 public:
  virtual ~SweepScenes() = default;
  // The description of run `index` (InputError prefixed with the sweep file, the line of the
  // edit that caused it and the run).
  virtual RunSpec scene(const SweepSpec& spec, std::size_t index) const = 0;
  // The columns between `units` and `pga_g` when io presents the base under names of its own
  // (a scene written with the two-block keys: SPEC §3's x1 ... switches, io/two_block_names.hpp);
  // null: the base structure's channel columns (study/sweep_columns.hpp).
  virtual const std::vector<SweepChannel>* presented_channels() const { return nullptr; }
};

// Where finished rows go (io's journal, io/sweep_files.hpp, writes them as they come, so that
// an interrupted sweep resumes).
class SweepRowSink {
 public:
  virtual ~SweepRowSink() = default;
  // Called once per finished row, one call at a time (under a lock), from the worker threads.
  virtual void take(const SweepRow& row) = 0;
};

struct SweepSpec {
  std::filesystem::path file;  // the sweep file ("" if parsed from text without a file)
  std::string name;            // `name`, or the sweep file's stem
  std::filesystem::path base;  // the base scene (resolved relative to the sweep file)
  SweepSetting common;         // top-level set = {...} / unset = [...]: edits every run makes first
  std::vector<SweepAxis> axes;
  std::vector<SweepSetting> motions;  // at least one ("base": the base scene's own ground)
  std::vector<double> im_periods;     // [output] im_periods: Sa(T) columns [s]
  double im_damping = 0.05;           // [output] im_damping
  std::string fingerprint;            // hash of the sweep text, the base scene text and the version
  std::shared_ptr<const SweepScenes> scenes;  // makes each run's description (set by the reader)
  // A structure as the base (SPEC §5; study/sweep_columns.hpp): its structure as read
  // (without edits), which decides the channel columns; null for a two-block base.
  std::shared_ptr<const structure::Structure> base_structure;
  std::vector<SweepColumn> channel_columns;  // building sweeps: A.roof_max, link1.stroke_max, ...
  // Building sweeps: how many linkN and contactN column sets the table has: the base's, or
  // more where an edit adds a table (link.2.* on a base with one link; study/sweep_columns.hpp).
  std::size_t link_columns = 0, contact_columns = 0;
  bool building() const { return base_structure != nullptr; }

  std::size_t runs() const;
  // Index of the value on each axis, then the motion's index (size axes + 1).
  std::vector<std::size_t> coordinates(std::size_t index) const;
  // The edits of run `index`: the common ones, the axis values, then the motion.
  std::vector<SweepSetting> settings(std::size_t index) const;
  // "model.mu=0.3, motion=elcentro": for messages.
  std::string describe(std::size_t index) const;
};

// The scene of run `index` (InputError prefixed with the sweep file, the line of the edit that
// caused it and the run); a structure's groups checked against the base's (study/sweep_columns.hpp).
RunSpec sweep_scene(const SweepSpec& spec, std::size_t index);

// "" if the table of a sweep with one axis of `n` points and `columns` other columns fits in
// this machine's memory; else why not ("would need about 4.1 GB of memory for the sweep's
// table alone, more than ...").
std::string sweep_axis_memory_problem(std::size_t n, std::size_t columns);

struct SweepRow {
  std::size_t index = 0;
  std::string units;  // "dimensionless" or "SI"
  // The cells of the run's report, in the columns between units and pga_g
  // (study/sweep_columns.hpp: x1 ... switches for a two-block base, a structure's channel
  // columns otherwise); all empty if the run failed.
  std::vector<std::string> channels;
  double pga_g = 0;             // of the forcing the solver saw [g]
  std::vector<double> sa_g;     // Sa(T, im_damping) at spec.im_periods [g]
  double wall_seconds = 0;      // building the scene + integrating + intensity measures
  std::string error;            // a NumericalError's message; the numbers are then NaN
};

// One run (InputError propagates; NumericalError is caught into row.error).
SweepRow run_sweep_point(const SweepSpec& spec, std::size_t index);

struct SweepOptions {
  unsigned jobs = 0;                  // threads; 0: std::thread::hardware_concurrency()
  std::vector<std::size_t> indices;   // runs to do; empty: all
  // Where each finished row goes (a journal), then on_row (a progress bar): one call at a time
  // (under a lock), from the worker threads. Either may be empty.
  SweepRowSink* sink = nullptr;
  std::function<void(const SweepRow&)> on_row;
};

// The rows of options.indices (or all runs), in increasing index order. An InputError (or any
// other exception) in one run stops the others from starting and is rethrown (the lowest
// failing index wins, so the message does not depend on timing).
std::vector<SweepRow> run_sweep(const SweepSpec& spec, const SweepOptions& options = {});

// ---- the table: what sweep.csv and sweep.json hold ----

// index, the axes, motion, units, x1, x2, drift, f1, f2, a1_abs, a2_abs, min_gap, contact,
// outside_model, contact.impacts, contact.force_max, contact.penetration_max, energy_input,
// share_rod1, share_rod2, share_friction, share_residual, stick_intervals, slip_intervals,
// switches, pga_g, sa_<T>..., wall_seconds, error. A building sweep has its channel columns
// (spec.channel_columns) in place of x1 ... switches.
std::vector<SweepColumn> sweep_columns(const SweepSpec& spec);

// Cells as text: numbers in their shortest round-trip form, NaN and absent values as "",
// booleans as true/false. The same cells go to the CSV, the journal and the JSON, so a table
// assembled from shards or ranks is identical to one computed in one go.
struct SweepTable {
  std::vector<SweepColumn> columns;
  std::vector<std::vector<std::string>> rows;  // ordered by index (column 0)
};

std::vector<std::string> sweep_cells(const SweepSpec& spec, const SweepRow& row);
// One number as a cell: its shortest round-trip form, NaN as "" (every table column uses it).
std::string sweep_number_cell(double v);
SweepTable sweep_table(const SweepSpec& spec, const std::vector<SweepRow>& rows);

// CSV: a header line, then one line per row (core/csv_line.hpp: csv_line, split_csv_line).
std::string sweep_csv(const SweepTable& table);

// A shard of the runs: indices i with i mod count == index (0-based).
struct SweepShard {
  std::size_t index = 0, count = 1;
  bool whole() const { return count == 1; }
  bool contains(std::size_t run) const { return run % count == index; }
};

// Refuses (InputError naming the sweep file) a sweep whose table for `runs` runs (those of one
// process: a shard's) would not fit in 80 % of the machine's memory, saying how much it needs.
void check_sweep_memory(const SweepSpec& spec, std::size_t runs);

}  // namespace adjoin
