#pragma once
// `adjoin optimize`'s study (SPEC §9; docs/reference/study-file.md): the study file, a design's
// runs, the cache that makes a study resumable, and its files. The search itself is
// study/optimize.hpp's.
//
//     OptimizeStudy study = load_optimize_study("examples/studies/slip-force.toml");
//     OptimizeOutcome out = run_optimize_study(study, {.jobs = 2, .dir = "out/opt"});
//     write_optimize_files(study, out, "out/opt");          // evaluations.csv, optimum.json
//
// A design is evaluated by running the suite's records on the base scene with the design's
// edits (its variables' values and its placement's), exactly as a sweep would run them
// (io/ida_files.hpp ida_sweep: each record scaled by ground.scale, to the study's IM level when
// one is given; the design's edits are the sweep's common edits). Each demand of an objective
// or constraint is a sweep-table column, taken per record, then its statistic over the records.
//
// The cache: DIR/evaluations.cache.csv holds every evaluated design's per-record demands,
// keyed by the design (its placement and its variables' values, exactly), under the study's
// fingerprint (the study file's text, the base scene's text, the records and their scales, the
// version). A rerun of the same study with the same DIR takes a design from the cache instead
// of running it; a different study starts a new cache.
#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/io/ida_files.hpp"
#include "adjoin/io/plot_style.hpp"
#include "adjoin/post/fragility_event.hpp"
#include "adjoin/study/ida.hpp"
#include "adjoin/study/optimize.hpp"
#include "adjoin/study/sweep.hpp"

namespace adjoin {

// What an objective or a constraint measures over the suite's runs: a demand's statistic,
// "mean(A.drift_max)", or a fragility probability, "P(contact1.impacts > 0 | pga = 0.35)":
// the event's lognormal fragility fitted to the stripes' runs by maximum likelihood
// (post/fragility.hpp, as `adjoin fragility` fits it) at the IM `probability_at`.
struct StudyGoal {
  std::string edp;  // a sweep-table column (a demand goal)
  Statistic statistic = Statistic::mean;
  std::string event;          // a fragility goal: the event (post/fragility_event.hpp)
  double probability_at = 0;  // and the IM (g)
  std::optional<FragilityEvent> parsed;  // the event, parsed against the sweep's columns
  double max = 0.0;  // constraints: the limit
  std::size_t line = 0;
  std::string key;  // where the study file gives it: "objective", "constraints[2]"
  bool fragility() const { return !event.empty(); }
  std::string name() const;
};

// A discrete choice: one scene key and its candidate values (a TOML value each: a number, a
// string, or a list such as [3, 3] for a building scene's link.1.floors).
struct StudyPlacement {
  std::string key;
  std::vector<SweepValue> values;
  std::size_t line = 0;
};

struct OptimizeStudy {
  std::filesystem::path file;
  std::string name;                 // the study file's stem
  std::filesystem::path scene;      // resolved against the study file's folder
  std::vector<std::string> suite;   // as given, resolved
  std::string units;                // records that do not state theirs
  std::optional<IntensityMeasure> im;  // with `level` or `levels`: each record scaled to them
  std::vector<double> levels;       // g: `level` (one), or `levels` (stripes); empty: records as read
  std::vector<OptimizeVariable> variables;
  std::vector<std::size_t> variable_lines;
  std::vector<StudyPlacement> placements;
  std::vector<StudyGoal> objectives;   // 1 or 2
  std::vector<StudyGoal> constraints;
  OptimizeOptions options;

  // Made by load_optimize_study: the records (their IM as read), the sweep whose motions are
  // the suite (one run per record and level, record-major), the columns read per run (the
  // demands and the events' columns), the fingerprint.
  std::vector<IdaRecord> records;
  SweepSpec sweep;
  std::vector<std::string> edps;  // the distinct demands of the objectives and constraints
  std::string fingerprint;

  // Placement choices: the product of the placements' value counts (1 without placements);
  // choice c's value index for each placement (the first placement varies slowest).
  std::size_t choices() const;
  std::vector<std::size_t> choice_values(std::size_t choice) const;
  // "link.1.floors=[2, 2]" (or "" without placements), for tables and messages.
  std::string choice_label(std::size_t choice) const;
  std::vector<double> limits() const;
  // The runs of a design: records x levels (1 level without stripes), record-major; run r's
  // record and IM level (g; 0 without im) and its name in tables ("RSN1044.AT2", with stripes
  // "RSN1044.AT2@0.35").
  std::size_t runs() const { return records.size() * std::max<std::size_t>(levels.size(), 1); }
  const IdaRecord& run_record(std::size_t r) const { return records[r / std::max<std::size_t>(levels.size(), 1)]; }
  double run_level(std::size_t r) const { return levels.empty() ? 0.0 : levels[r % levels.size()]; }
  std::string run_name(std::size_t r) const;
};

// Reads and checks the study (InputError "FILE:LINE: ..." naming the key): the base scene as
// `adjoin run` reads it, the suite as `adjoin ida --suite` takes it, each variable's bounds
// and each placement's values tried on the scene (a key the scene does not take is named with
// the study file's line), the demands as columns of the scene's sweep table, the method.
// `skipped`: suite folder files no reader recognises.
OptimizeStudy load_optimize_study(const std::filesystem::path& file, std::vector<std::string>* skipped = nullptr);

// The sweep that evaluates a design: the suite on the base scene with the design's edits.
SweepSpec design_sweep(const OptimizeStudy& study, std::size_t choice, const std::vector<double>& x);

// One evaluated design's values: values[run][column] (runs as study.runs(), columns as
// study.edps; NaN for an empty cell).
struct DesignDemands {
  std::vector<std::vector<double>> values;
  bool from_cache = false;
};

struct OptimizeRequest {
  unsigned jobs = 0;                // threads per design (the records run in parallel); 0: all cores
  std::filesystem::path dir;        // the cache's folder ("" for none)
  std::function<void(std::size_t evaluation, bool from_cache)> on_evaluation;  // after each new design
};

struct OptimizeOutcome {
  OptimizeResult result;
  std::vector<DesignDemands> demands;  // per evaluation
  std::size_t from_cache = 0, runs = 0;  // designs taken from the cache; runs done now
  double seconds = 0.0;
};

// Runs the study (study/optimize.hpp optimize_designs with its evaluator). A run's numerical
// failure stops it with a NumericalError naming the design and the record.
OptimizeOutcome run_optimize_study(const OptimizeStudy& study, const OptimizeRequest& request);

// ---- the files ----

// evaluations.csv: one row per evaluated design, in order: evaluation, stage, the placement's
// keys (their values as written), the variables (by key), the objectives and constraints (by
// name: "mean(A.drift_ratio_max)"), feasible, pareto (two objectives), then each demand per
// record ("A.drift_ratio_max@RSN1044.AT2").
std::string optimize_evaluations_csv(const OptimizeStudy& study, const OptimizeOutcome& outcome);
// optimum.json: study, scene, method, tolerance, max_evaluations, seed, records, variables
// (the best design's values by key), placement (by key, or null), objective (its value; two
// objectives: f1's at the front's point of least f1) and objectives (names), constraints
// (name, value, max), feasible, evaluations (distinct designs), runs (evaluations x records),
// from_cache, runs_now, searches (each optimisation: placement, stage, evaluations, stop, best
// design and objective), history (per evaluation: the objective and the best feasible so far),
// and pareto (two objectives: the front's designs and objectives).
std::string optimize_json(const OptimizeStudy& study, const OptimizeOutcome& outcome);
// Writes DIR/evaluations.csv and DIR/optimum.json.
void write_optimize_files(const OptimizeStudy& study, const OptimizeOutcome& outcome, const std::filesystem::path& dir);
// The convergence figure: each evaluation's objective (points; infeasible ones hollow) and the
// best feasible so far (a line). Two objectives: the front (f2 against f1) over every design.
void plot_optimize(const OptimizeStudy& study, const OptimizeOutcome& outcome, const std::filesystem::path& image,
                   const PlotStyle& style);

}  // namespace adjoin
