// A study's designs evaluated by running the suite (io/optimize_study.hpp), through the cache
// DIR/evaluations.cache.csv that makes a study resumable.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/optimize_study.hpp"
#include "adjoin/post/fragility.hpp"
#include "adjoin/post/fragility_event.hpp"
#include "adjoin/study/sweep_columns.hpp"

namespace adjoin {
namespace fs = std::filesystem;
namespace {

using DesignKey = std::pair<std::size_t, std::vector<double>>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A table cell as a number: "" is NaN (a run without that value).
bool cell_value(const std::string& cell, double* v) {
  if (cell.empty()) {
    *v = kNaN;
    return true;
  }
  return parse_finite(cell, v);
}

// The cache file: "# adjoin optimize cache fingerprint=F", the header, then one row per design:
// choice, the variables, then each record's demands (record-major), numbers in their shortest
// round-trip form (so a design's key reads back exactly).
class DesignCache {
 public:
  DesignCache(const OptimizeStudy& study, const fs::path& dir) : study_(study) {
    if (dir.empty()) return;
    path_ = dir / "evaluations.cache.csv";
    read();
    out_.open(path_, std::ios::trunc);
    if (!out_) throw InputError(path_.string() + ": cannot write the cache");
    out_ << preamble() << "\n" << csv_line(header()) << "\n";
    for (const auto& [key, values] : rows_) out_ << csv_line(cells(key, values)) << "\n";
    out_.flush();
  }
  const std::vector<std::vector<double>>* find(const DesignKey& key) const {
    const auto it = rows_.find(key);
    return it == rows_.end() ? nullptr : &it->second;
  }
  void add(const DesignKey& key, const std::vector<std::vector<double>>& values) {
    rows_[key] = values;
    if (!out_.is_open()) return;
    out_ << csv_line(cells(key, values)) << "\n";
    out_.flush();
    if (!out_) throw InputError(path_.string() + ": cannot write the cache (is the disk full?)");
  }

 private:
  std::string preamble() const { return "# adjoin optimize cache fingerprint=" + study_.fingerprint; }
  std::vector<std::string> header() const {
    std::vector<std::string> h{"choice"};
    for (const auto& v : study_.variables) h.push_back(v.key);
    for (std::size_t r = 0; r < study_.runs(); ++r)
      for (const auto& e : study_.edps) h.push_back(e + "@" + study_.run_name(r));
    return h;
  }
  std::vector<std::string> cells(const DesignKey& key, const std::vector<std::vector<double>>& values) const {
    std::vector<std::string> c{std::to_string(key.first)};
    for (double x : key.second) c.push_back(sweep_number_cell(x));
    for (const auto& per_record : values)
      for (double v : per_record) c.push_back(sweep_number_cell(v));
    return c;
  }
  // The rows of an earlier run of the same study; a cache of another study (or one that does
  // not read back) is started again.
  void read() {
    std::ifstream in(path_);
    std::string line;
    if (!in || !std::getline(in, line) || line != preamble()) return;
    std::vector<std::string> h;
    if (!std::getline(in, line) || !split_csv_line(line, &h) || h != header()) return;
    const std::size_t nx = study_.variables.size(), ne = study_.edps.size(), nr = study_.runs();
    while (std::getline(in, line)) {
      std::vector<std::string> c;
      if (!split_csv_line(line, &c) || c.size() != h.size()) continue;  // a torn last line
      DesignKey key;
      bool ok = parse_count(c[0], &key.first) && key.first < study_.choices();
      key.second.resize(nx);
      for (std::size_t i = 0; ok && i < nx; ++i) ok = parse_finite(c[1 + i], &key.second[i]);
      std::vector<std::vector<double>> values(nr, std::vector<double>(ne));
      for (std::size_t k = 0; ok && k < nr * ne; ++k) ok = cell_value(c[1 + nx + k], &values[k / ne][k % ne]);
      if (ok) rows_[key] = std::move(values);
    }
  }

  const OptimizeStudy& study_;
  fs::path path_;
  std::map<DesignKey, std::vector<std::vector<double>>> rows_;
  std::ofstream out_;
};

// "link.1.floors=[2, 2], link.1.slip_force=1.2e5": a design in messages.
std::string describe(const OptimizeStudy& study, const DesignKey& key) {
  std::string d = study.choice_label(key.first);
  for (std::size_t i = 0; i < study.variables.size(); ++i)
    d += (d.empty() ? "" : ", ") + study.variables[i].key + "=" + sweep_number_cell(key.second[i]);
  return d;
}

// The suite's runs of a design: values[run][column].
std::vector<std::vector<double>> run_design(const OptimizeStudy& study, const DesignKey& key, unsigned jobs) {
  const SweepSpec spec = design_sweep(study, key.first, key.second);
  SweepOptions options;
  options.jobs = jobs;
  const std::vector<SweepRow> rows = run_sweep(spec, options);
  const auto columns = sweep_columns(spec);
  std::vector<std::size_t> at;
  for (const auto& e : study.edps)
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c].name == e) at.push_back(c);
  std::vector<std::vector<double>> values;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (!rows[r].error.empty())
      throw NumericalError("optimize: the design " + describe(study, key) + " failed on " + study.run_name(r) + ": " +
                               rows[r].error, 0.0);
    const auto cells = sweep_cells(spec, rows[r]);
    values.emplace_back();
    for (std::size_t k = 0; k < at.size(); ++k) {
      double v = kNaN;
      cell_value(cells[at[k]], &v);
      values.back().push_back(v);
    }
  }
  return values;
}

std::size_t column_index(const OptimizeStudy& study, const std::string& name) {
  return static_cast<std::size_t>(std::find(study.edps.begin(), study.edps.end(), name) - study.edps.begin());
}

// A demand's statistic over the runs; an empty cell is the study's mistake (a demand the scene
// leaves empty), named.
double demand_value(const OptimizeStudy& study, const DesignKey& key, const StudyGoal& g,
                    const std::vector<std::vector<double>>& per_run) {
  const std::size_t e = column_index(study, g.edp);
  std::vector<double> v;
  for (std::size_t r = 0; r < per_run.size(); ++r) {
    if (std::isnan(per_run[r][e]))
      throw InputError(study.file.string() + ":" + std::to_string(g.line) + ": " + g.key + ".edp: " + g.edp +
                       " has no value in the run of " + study.run_name(r) + " (design " + describe(study, key) +
                       "); choose a demand every run has");
    v.push_back(per_run[r][e]);
  }
  return suite_statistic(v, g.statistic);
}

// P(event | IM = probability_at): the lognormal fragility fitted to the runs by maximum
// likelihood; runs whose event reads an empty cell are left out. Counts without a fit (no
// event, events everywhere, levels that separate the runs) give the observed fraction of
// events at the level nearest probability_at (in ln IM).
double fragility_value(const OptimizeStudy& study, const DesignKey& key, const StudyGoal& g,
                       const std::vector<std::vector<double>>& per_run) {
  const auto columns = sweep_columns(study.sweep);
  std::vector<std::vector<double>> values(columns.size(), std::vector<double>(per_run.size(), kNaN));
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::size_t e = column_index(study, columns[c].name);
    if (e == study.edps.size()) continue;
    for (std::size_t r = 0; r < per_run.size(); ++r) values[c][r] = per_run[r][e];
  }
  std::vector<std::string> records;
  std::vector<double> im;
  for (std::size_t r = 0; r < per_run.size(); ++r) {
    records.push_back(study.run_record(r).name);
    im.push_back(study.run_level(r));
  }
  const FragilityOutcomes outcomes = fragility_outcomes(*g.parsed, records, im, values, {});
  if (outcomes.runs.empty())
    throw InputError(study.file.string() + ":" + std::to_string(g.line) + ": " + g.key + ".event: no run of the design " +
                     describe(study, key) + " has a value for it");
  const std::vector<FragilityLevel> levels = fragility_levels(outcomes.runs);
  const FragilityFit fit = fit_fragility_mle(levels);
  if (fit.fitted) return fragility_probability(fit.theta, fit.beta, g.probability_at);
  const FragilityLevel* nearest = &levels.front();
  for (const auto& l : levels)
    if (std::abs(std::log(l.im / g.probability_at)) < std::abs(std::log(nearest->im / g.probability_at))) nearest = &l;
  return static_cast<double>(nearest->events) / static_cast<double>(nearest->n);
}

DesignValues design_values(const OptimizeStudy& study, const DesignKey& key, const std::vector<std::vector<double>>& per_run) {
  const auto value = [&](const StudyGoal& g) {
    return g.fragility() ? fragility_value(study, key, g, per_run) : demand_value(study, key, g, per_run);
  };
  DesignValues d;
  for (const auto& g : study.objectives) d.objectives.push_back(value(g));
  for (const auto& g : study.constraints) d.constraints.push_back(value(g));
  return d;
}

}  // namespace

OptimizeOutcome run_optimize_study(const OptimizeStudy& study, const OptimizeRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  DesignCache cache(study, request.dir);
  OptimizeOutcome outcome;
  const DesignEvaluator evaluate = [&](std::size_t choice, const std::vector<double>& x) {
    const DesignKey key{choice, x};
    DesignDemands d;
    if (const auto* cached = cache.find(key)) {
      d.values = *cached;
      d.from_cache = true;
      ++outcome.from_cache;
    } else {
      d.values = run_design(study, key, request.jobs);
      outcome.runs += study.runs();
      cache.add(key, d.values);
    }
    outcome.demands.push_back(d);
    if (request.on_evaluation) request.on_evaluation(outcome.demands.size(), d.from_cache);
    return design_values(study, key, d.values);
  };
  outcome.result = optimize_designs(study.variables, study.choices(), study.objectives.size(), study.limits(), study.options, evaluate);
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

}  // namespace adjoin
