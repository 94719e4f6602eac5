// A study's designs evaluated by running the suite (io/optimize_study.hpp), through the cache
// DIR/evaluations.cache.csv that makes a study resumable.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/optimize_study.hpp"
#include "adjoin/study/sweep_columns.hpp"

namespace adjoin {
namespace fs = std::filesystem;
namespace {

using DesignKey = std::pair<std::size_t, std::vector<double>>;

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
    for (const auto& r : study_.records)
      for (const auto& e : study_.edps) h.push_back(e + "@" + r.name);
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
    const std::size_t nx = study_.variables.size(), ne = study_.edps.size(), nr = study_.records.size();
    while (std::getline(in, line)) {
      std::vector<std::string> c;
      if (!split_csv_line(line, &c) || c.size() != h.size()) continue;  // a torn last line
      DesignKey key;
      bool ok = parse_count(c[0], &key.first) && key.first < study_.choices();
      key.second.resize(nx);
      for (std::size_t i = 0; ok && i < nx; ++i) ok = parse_finite(c[1 + i], &key.second[i]);
      std::vector<std::vector<double>> values(nr, std::vector<double>(ne));
      for (std::size_t k = 0; ok && k < nr * ne; ++k) ok = parse_finite(c[1 + nx + k], &values[k / ne][k % ne]);
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

// The suite's runs of a design: values[record][edp].
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
    const std::string& record = study.records[r].name;
    if (!rows[r].error.empty())
      throw NumericalError("optimize: the design " + describe(study, key) + " failed on record " + record + ": " + rows[r].error, 0.0);
    const auto cells = sweep_cells(spec, rows[r]);
    values.emplace_back();
    for (std::size_t k = 0; k < at.size(); ++k) {
      double v = 0.0;
      if (!parse_finite(cells[at[k]], &v))
        throw InputError(study.file.string() + ": " + study.edps[k] + " has no value in the run of record " + record +
                         " (design " + describe(study, key) + "); choose a demand every run has");
      values.back().push_back(v);
    }
  }
  return values;
}

DesignValues design_values(const OptimizeStudy& study, const std::vector<std::vector<double>>& per_record) {
  const auto goal = [&](const StudyGoal& g) {
    const std::size_t e = static_cast<std::size_t>(std::find(study.edps.begin(), study.edps.end(), g.edp) - study.edps.begin());
    std::vector<double> v;
    for (const auto& r : per_record) v.push_back(r[e]);
    return suite_statistic(v, g.statistic);
  };
  DesignValues d;
  for (const auto& g : study.objectives) d.objectives.push_back(goal(g));
  for (const auto& g : study.constraints) d.constraints.push_back(goal(g));
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
      outcome.runs += study.records.size();
      cache.add(key, d.values);
    }
    outcome.demands.push_back(d);
    if (request.on_evaluation) request.on_evaluation(outcome.demands.size(), d.from_cache);
    return design_values(study, d.values);
  };
  outcome.result = optimize_designs(study.variables, study.choices(), study.objectives.size(), study.limits(), study.options, evaluate);
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

}  // namespace adjoin
