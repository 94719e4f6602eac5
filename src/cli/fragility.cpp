// adjoin fragility DIR/ida.csv [DIR2/ida.csv ...] --event "EXPR" [--label L1,L2,...]
//                  [--bootstrap N] [--seed S] [--at IM] --out FILE.json [--plot FILE.png|.svg]
//
// The lognormal fragility P(event | IM = x) = Phi(ln(x / theta) / beta) of each table of
// `adjoin ida` (record,im,scale,<edp>...), by maximum likelihood on the counts per IM level,
// with bootstrap bounds over records, and for IDA traces also by the IM-at-first-event moments
// (post/fragility.hpp). Several tables are several designs: one JSON with each, one figure
// with every curve, and their probabilities at --at. Data without a fit (no events, events in
// every run, levels that separate the runs perfectly) is reported: a warning, and in the JSON
// fitted = false with the reason and theta = beta = null; the exit status stays 0.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/csv_table.hpp"
#include "adjoin/io/fragility_plot.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/post/fragility.hpp"
#include "adjoin/post/fragility_event.hpp"
#include "command.hpp"

namespace adjoin::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// More resamples than this would only spend time: the percentiles' own sampling error is
// already far below the bounds' width.
constexpr std::size_t kMostResamples = 100000;

struct FragilityArgs {
  std::vector<std::string> tables, labels;
  std::string event, out, plot;
  std::size_t bootstrap = 1000;
  std::uint64_t seed = 1;
  std::optional<double> at;
};

// One design: its table's runs and what was fitted to them.
struct Design {
  std::string file, label;
  std::vector<FragilityRun> runs;
  std::size_t failed = 0, unknown = 0, first_unknown_line = 0;
  bool trace = false;  // records with their own IM levels (failed runs counted: they were run there)
  std::vector<FragilityLevel> levels;
  FragilityFit fit;
  std::optional<FragilityBounds> bounds;
  std::optional<FirstEventFit> first_event;  // IDA traces
};

// The runs of one ida.csv with the event evaluated. A run that failed (a non-empty `error`
// cell, where the table has that column) or whose event depends on an empty cell is left out
// and counted.
Design read_design(const std::string& file, const std::string& event_text) {
  Design d;
  d.file = file;
  const CsvTable table = read_csv_table(file, "the ida.csv of `adjoin ida` (record,im,scale,<edp>...)");
  const std::string context = "ida.csv: record,im,scale,<edp>...";
  const std::vector<std::string> records = table.texts("record", context);
  const std::vector<double> im = table.numbers("im", context);
  FragilityEvent event;
  try {
    event = FragilityEvent::parse(event_text, table.columns);
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());
  }
  std::vector<std::vector<double>> values(table.columns.size());
  for (std::size_t c : event.columns_used()) values[c] = table.numbers(table.columns[c], "--event " + text_excerpt(event_text));
  const std::vector<std::string> errors = table.has("error") ? table.texts("error") : std::vector<std::string>();
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const std::string where = file + ":" + std::to_string(table.lines[r]);
    if (!(im[r] > 0.0) || !std::isfinite(im[r]))
      throw InputError(where + ": im " + text_excerpt(table.rows[r][table.column("im")]) + ": expected an intensity > 0");
    if (records[r].empty()) throw InputError(where + ": an empty record name");
  }
  FragilityOutcomes outcomes = fragility_outcomes(event, records, im, values, errors);
  d.runs = std::move(outcomes.runs);
  d.failed = outcomes.failed;
  d.unknown = outcomes.unknown;
  if (d.unknown) d.first_unknown_line = table.lines[outcomes.first_unknown];
  d.trace = outcomes.trace;
  if (d.runs.empty()) throw InputError(file + ": no run with a known outcome of the event (" + std::to_string(d.failed) +
                                       " failed, " + std::to_string(d.unknown) + " with an empty value the event reads)");
  return d;
}

void fit_design(Design& d, const FragilityArgs& args) {
  d.levels = fragility_levels(d.runs);
  d.fit = fit_fragility_mle(d.levels);
  if (d.fit.fitted && args.bootstrap > 0) d.bounds = bootstrap_fragility(d.runs, args.bootstrap, args.seed);
  if (d.trace) d.first_event = fit_first_event(d.runs);
}

ordered_json number_or_null(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

ordered_json design_json(const Design& d, const FragilityArgs& args) {
  ordered_json levels = ordered_json::array(), n = ordered_json::array(), events = ordered_json::array();
  for (const FragilityLevel& l : d.levels) {
    levels.push_back(l.im);
    n.push_back(l.n);
    events.push_back(l.events);
  }
  std::set<std::string> records;
  for (const FragilityRun& r : d.runs) records.insert(r.record);
  ordered_json out{{"file", d.file},
                   {"label", d.label},
                   {"event", args.event},
                   {"method", "maximum likelihood, binomial counts per IM level (Baker 2015)"},
                   {"fitted", d.fit.fitted},
                   {"problem", d.fit.fitted ? ordered_json(nullptr) : ordered_json(d.fit.problem)},
                   {"theta", number_or_null(d.fit.theta)},
                   {"beta", number_or_null(d.fit.beta)},
                   {"log_likelihood", number_or_null(d.fit.log_likelihood)},
                   {"levels", levels},
                   {"n", n},
                   {"events", events},
                   {"records", records.size()},
                   {"runs", d.runs.size()},
                   {"skipped", {{"failed", d.failed}, {"unknown", d.unknown}}}};
  if (d.bounds) {
    const FragilityBounds& b = *d.bounds;
    out["bootstrap"] = {{"samples", b.samples},
                        {"seed", b.seed},
                        {"degenerate", b.degenerate},
                        {"percentiles", {0.05, 0.95}},
                        {"theta", {number_or_null(b.theta_low), number_or_null(b.theta_high)}},
                        {"beta", {number_or_null(b.beta_low), number_or_null(b.beta_high)}}};
  } else {
    out["bootstrap"] = nullptr;
  }
  if (d.first_event) {
    const FirstEventFit& f = *d.first_event;
    out["first_event"] = {{"method", "IM at first event: theta = exp(mean ln IM_i), beta = sd ln IM_i (n - 1)"},
                          {"fitted", f.fitted},
                          {"problem", f.fitted ? ordered_json(nullptr) : ordered_json(f.problem)},
                          {"theta", number_or_null(f.theta)},
                          {"beta", number_or_null(f.beta)},
                          {"records", f.records},
                          {"censored", f.censored},
                          {"censored_records", f.censored_records}};
  }
  if (args.at)
    out["at"] = {{"im", *args.at},
                 {"probability", d.fit.fitted ? number_or_null(fragility_probability(d.fit.theta, d.fit.beta, *args.at))
                                              : ordered_json(nullptr)}};
  return out;
}

// The table's file, and its label where that says more.
std::string who(const Design& d) { return d.file + (d.label == d.file || d.label == fs::path(d.file).filename().string() ? "" : " (" + d.label + ")"); }

void print_design(const Design& d, const FragilityArgs& args) {
  std::printf("%s: %zu runs at %zu levels", who(d).c_str(), d.runs.size(), d.levels.size());
  if (d.failed || d.unknown) std::printf(", %zu failed and %zu unknown runs left out", d.failed, d.unknown);
  std::printf("\n");
  if (d.fit.fitted) {
    std::printf("  maximum likelihood: theta = %.5g g, beta = %.4g, ln L = %.6g\n", d.fit.theta, d.fit.beta, d.fit.log_likelihood);
    if (d.bounds && std::isfinite(d.bounds->theta_low))
      std::printf("  bootstrap (%zu resamples, seed %llu): theta in [%.5g, %.5g], beta in [%.4g, %.4g] (5 %%, 95 %%)\n",
                  d.bounds->samples, static_cast<unsigned long long>(d.bounds->seed), d.bounds->theta_low,
                  d.bounds->theta_high, d.bounds->beta_low, d.bounds->beta_high);
    if (args.at)
      std::printf("  P(event | IM = %g g) = %.4f\n", *args.at, fragility_probability(d.fit.theta, d.fit.beta, *args.at));
  } else {
    std::printf("  not fitted\n");
  }
  if (d.first_event && d.first_event->fitted)
    std::printf("  IM at first event: theta = %.5g g, beta = %.4g (%zu records, %zu censored)\n", d.first_event->theta,
                d.first_event->beta, d.first_event->records, d.first_event->censored);
}

void warn(const Design& d) {
  const std::string who = cli::who(d);
  if (!d.fit.fitted)
    std::cerr << "warning: " << printable_message(who + ": not fitted: " + d.fit.problem) << " (fitted = false in --out)\n";
  if (d.unknown)
    std::cerr << "warning: " << printable_message(who + ": " + std::to_string(d.unknown) +
                                                  " runs left out, their event reads an empty cell (the first at line " +
                                                  std::to_string(d.first_unknown_line) + ")") << "\n";
  if (d.bounds && d.bounds->degenerate)
    std::cerr << "warning: " << printable_message(who + ": " + std::to_string(d.bounds->degenerate) + " of " +
                                                  std::to_string(d.bounds->samples) +
                                                  " bootstrap resamples had no fit and are left out of the bounds") << "\n";
  if (d.bounds && d.fit.fitted &&
      !(d.bounds->theta_low <= d.fit.theta && d.fit.theta <= d.bounds->theta_high && d.bounds->beta_low <= d.fit.beta &&
        d.fit.beta <= d.bounds->beta_high))
    std::cerr << "warning: " << printable_message(who + ": the estimate lies outside its bootstrap bounds (a biased "
                                                  "estimate: too few records or levels)") << "\n";
  if (d.first_event && d.first_event->censored)
    std::cerr << "warning: " << printable_message(who + ": " + std::to_string(d.first_event->censored) +
                                                  " records never had the event and are left out of the first-event "
                                                  "moments (their theta is biased low)") << "\n";
}

int fragility_command(const FragilityArgs& args) {
  if (!args.labels.empty() && args.labels.size() != args.tables.size())
    throw InputError("--label: " + std::to_string(args.labels.size()) + " labels for " + std::to_string(args.tables.size()) +
                     " tables (give one per table, in order)");
  if (args.bootstrap > kMostResamples)
    throw InputError("--bootstrap " + std::to_string(args.bootstrap) + ": at most " + std::to_string(kMostResamples) +
                     " resamples (1000 give the 5 % and 95 % percentiles to about 1 %)");
  if (args.at && !(*args.at > 0.0 && std::isfinite(*args.at))) throw InputError("--at: expected an intensity > 0 (in g)");
  // The places of the outputs, before any work; a missing folder of --out is made to write it.
  const fs::path out_folder = fs::path(args.out).parent_path();
  if (!out_folder.empty()) check_output_folder(out_folder, "--out");
  PlotStyle style;
  if (!args.plot.empty()) plot_target(args.plot, {}, "", &style, "--plot");

  std::vector<Design> designs;
  for (std::size_t i = 0; i < args.tables.size(); ++i) {
    Design d = read_design(args.tables[i], args.event);
    const fs::path path(args.tables[i]);
    d.label = !args.labels.empty() ? args.labels[i]
              : path.has_parent_path() && !path.parent_path().filename().empty() ? path.parent_path().filename().string()
                                                                                : path.filename().string();
    fit_design(d, args);
    designs.push_back(std::move(d));
  }

  ordered_json json;
  if (designs.size() == 1) {
    json = design_json(designs[0], args);
  } else {
    json = {{"event", args.event}, {"designs", ordered_json::array()}};
    for (const Design& d : designs) json["designs"].push_back(design_json(d, args));
  }
  std::optional<OutputFolder> folder;
  if (!out_folder.empty()) folder.emplace(out_folder, "--out");
  AtomicFile file(args.out);
  file.stream() << json.dump(2) << "\n";
  file.commit();
  if (folder) folder->keep();

  std::printf("event: %s\n", args.event.c_str());
  for (const Design& d : designs) {
    print_design(d, args);
    warn(d);
  }
  std::printf("wrote %s\n", args.out.c_str());

  if (args.plot.empty()) return 0;
  std::vector<FragilityCurve> curves;
  for (const Design& d : designs) curves.push_back({d.label, d.levels, d.fit, d.first_event});
  return draw_figure([&] { plot_fragility(curves, "Fragility: " + args.event, args.at, args.plot, style); },
                     "the fits were written to " + args.out);
}

const Registration registration(54, "fragility", "Fit lognormal fragility curves P(event | IM) to the runs of `adjoin ida`",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<FragilityArgs>();
  sub->add_option("tables", args->tables, "ida.csv of `adjoin ida` (record,im,scale,<edp>...); several: one design each")
      ->required();
  sub->add_option("--event", args->event,
                  "The event: COLUMN > NUMBER (>, >=, <, <=) joined by and/or, e.g. \"contact1.impacts > 0\"")
      ->required();
  sub->add_option("--label", args->labels, "Names of the designs, one per table (default: each table's folder)")
      ->delimiter(',');
  sub->add_option("--bootstrap", args->bootstrap, "Bootstrap resamples of the records for 5 %/95 % bounds (default 1000; 0: none)");
  sub->add_option("--seed", args->seed, "Seed of the bootstrap's random draws (default 1)");
  sub->add_option("--at", args->at, "An intensity (g) at which to report each design's probability of the event");
  sub->add_option("--out", args->out, "The fits as JSON (fragility.json)")->required();
  sub->add_option("--plot", args->plot, "Also draw the curves and the observed fractions with gnuplot (.png or .svg)");
  return [args]() { return fragility_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
