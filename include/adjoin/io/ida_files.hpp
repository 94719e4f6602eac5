#pragma once
// The files of `adjoin ida` (SPEC §9; the numbers are study/ida.hpp's, the runs a sweep's):
//
//  - the suite: record files, and folders of them (every file in a folder whose header a
//    record reader recognises, as `adjoin spectrum --suite` takes them);
//  - the sweep of the runs: the base scene with, per run, its ground replaced by one record
//    scaled by a factor — exactly `adjoin run SCENE --unset ground --set ground.source=record
//    --set ground.file=F --set ground.scale=S` (and ground.units when given; a dimensionless
//    scene's ground.time_scale is kept);
//  - ida.csv: `record,im,scale,<edp>...`, one row per run, the demands named as the sweep
//    table's columns (study/sweep_columns.hpp), numbers in their shortest round-trip form;
//  - the figure: the IDA curves (EDP on x, IM on y), one per record, with the 16/50/84 %
//    fractile curves.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"
#include "adjoin/io/plot_style.hpp"
#include "adjoin/post/fragility_event.hpp"
#include "adjoin/study/ida.hpp"
#include "adjoin/study/sweep.hpp"

namespace adjoin {

// The records of a suite, in the order given (a folder's sorted by name); `skipped` gets the
// folder files no reader recognises. InputError for a missing file, an empty folder, a record
// given twice, two records of one file name (ida.csv names a record by its file name).
std::vector<std::filesystem::path> ida_suite(const std::vector<std::string>& inputs, std::vector<std::string>* skipped);

// One run of the sweep: a record (its file and the name ida.csv gives it) at a scale.
struct IdaMotion {
  std::string record;  // the file's name
  std::filesystem::path file;
  double scale = 1.0;
};

// The sweep of `motions` on the base scene `scene` (one motion a run, in order); `units`
// ("" or a ground.units value) is set on every run. `name` names the sweep in messages.
SweepSpec ida_sweep(const std::filesystem::path& scene, const std::vector<IdaMotion>& motions, const std::string& units,
                    const std::string& name);
// The same sweep with motion k's scale changed (the trace's next run).
void set_ida_scale(SweepSpec& spec, std::size_t motion, double scale);

// The default demands of a sweep (say which: docs/reference/cli.md#adjoin-ida): a building
// scene's X.drift_ratio_max (X.drift_max without storey heights), X.roof_max, X.accel_max,
// linkN.force_max, linkN.stroke_max, contactN.min_gap, contactN.impacts, and collapse_t; a
// two-block scene's x1, x2, drift, f1, f2, min_gap.
std::vector<std::string> ida_default_edps(const SweepSpec& spec);
// InputError naming --edp unless every name is a column of the sweep's table.
void check_ida_edps(const SweepSpec& spec, const std::vector<std::string>& edps, const std::string& option);

struct IdaRow {
  std::string record;
  double im = 0.0, scale = 1.0;
  std::vector<std::string> edps;  // cells, as the sweep table has them
  std::string units;              // the run's: "SI" or "dimensionless"
  std::string error;              // a numerical failure's message
  bool event = false;             // --trace: the capacity event happened
};
// ---- the runs, without files (`adjoin ida` and adjoin.ida) ----

// A record of the suite: its file, the name ida.csv gives it, its IM as read (g).
struct IdaRecord {
  std::filesystem::path file;
  std::string name;
  double im = 0.0;
};
// The suite (ida_suite) read with `units` ("" or g, m/s2, cm/s2, gal, mm/s2: for records that
// do not state theirs; InputError naming `units_option` otherwise) and each record's IM.
std::vector<IdaRecord> read_ida_suite(const std::vector<std::string>& inputs, const std::string& units,
                                      const IntensityMeasure& im, std::vector<std::string>* skipped,
                                      const std::string& units_option);

// Whether a row of the sweep's table shows the capacity event: a numerical failure, the run's
// collapse (collapse_t has a value), or the event expression (post/fragility_event.hpp, the
// parser of `adjoin fragility --event`: comparisons of the demands joined by and/or) is true.
// An expression that reads an empty cell and stays unknown is not the event.
struct IdaCapacity {
  std::optional<FragilityEvent> event;
  std::vector<std::size_t> event_columns;  // the sweep-table column of each of the event's columns
  std::size_t collapse_column = 0, error_column = 0;
  bool collapse = false;
  bool operator()(const std::vector<std::string>& cells) const;
};
// `event` "" (collapse or failure only) or an event expression over the scene's demands
// (channel_columns), e.g. "A.drift_ratio_max > 0.05 or contact1.impacts > 0" (InputError
// naming `option`).
IdaCapacity ida_capacity(const SweepSpec& spec, const std::string& event, const std::string& option);

// The row of one run (`cells` its sweep-table cells).
IdaRow ida_row(const SweepSpec& spec, const std::vector<std::string>& cells, const std::vector<std::string>& edps,
               const IdaRecord& record, double level, double scale, const IdaCapacity& capacity);

// Stripes: one motion per (record, level), record-major (record k at level j is run
// k x levels + j), each scaled by level / record IM.
std::vector<IdaMotion> ida_stripe_motions(const std::vector<IdaRecord>& records, const std::vector<double>& levels);
// The rows of the stripes' sweep table (`cells`: its rows, cell 0 the run's index), in order.
std::vector<IdaRow> ida_stripe_rows(const SweepSpec& spec, const std::vector<std::vector<std::string>>& cells,
                                    const std::vector<IdaRecord>& records, const std::vector<double>& levels,
                                    const std::vector<std::string>& edps, const IdaCapacity& capacity);

// Tracing: hunt and fill per record (study/ida.hpp hunt_and_fill) up to its capacity event,
// the records in threads. The option names appear in messages (the command's or the keywords).
struct IdaTraceRequest {
  std::filesystem::path scene;
  std::string units, capacity;  // capacity: "" (collapse or failure only) or an event expression
  TraceOptions options;
  unsigned jobs = 0;  // 0: one thread per local core
  std::string name;   // the sweep's, in messages
  std::string edp_option = "--edp", capacity_option = "--capacity", trace_option = "--trace";
  std::function<void()> on_record;  // after each record is traced (one call at a time)
};
// The rows, record by record in the suite's order, each record's by IM; `edps` empty: the
// default demands (filled in); `found` each record's trace. InputError if the scene has no
// collapse check and no capacity is given.
std::vector<IdaRow> ida_traces(const IdaTraceRequest& request, const std::vector<IdaRecord>& records,
                               std::vector<std::string>* edps, std::vector<Trace>* found);

// ida.csv's text.
std::string ida_csv(const std::vector<std::string>& edps, const std::vector<IdaRow>& rows);

// The figure of the first demand `edp`: each record's curve (its runs by IM; a run with the
// capacity event, or one that failed, ends it: a flat line to the right at the last IM without), and the
// 16/50/84 % fractiles (study/ida.hpp ida_fractile) at the runs' IMs. `si`: the units; the
// title is followed by the count of records.
void plot_ida(const std::vector<IdaRow>& rows, std::size_t edp, const std::string& edp_name, const std::string& im,
              bool si, const std::string& title, const std::filesystem::path& image, const PlotStyle& style);

}  // namespace adjoin
