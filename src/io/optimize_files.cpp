// The files of `adjoin optimize` (io/optimize_study.hpp): evaluations.csv, optimum.json and
// the convergence (or Pareto) figure.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/optimize_study.hpp"

namespace adjoin {
namespace fs = std::filesystem;
namespace {

using json = nlohmann::ordered_json;

bool on_front(const OptimizeResult& r, std::size_t i) { return std::find(r.pareto.begin(), r.pareto.end(), i) != r.pareto.end(); }

json design_json(const OptimizeStudy& study, const Evaluation& e) {
  json d;
  json vars = json::object();
  for (std::size_t i = 0; i < study.variables.size(); ++i) vars[study.variables[i].key] = e.x[i];
  d["variables"] = vars;
  if (study.placements.empty()) d["placement"] = nullptr;
  else {
    json p = json::object();
    const auto at = study.choice_values(e.choice);
    for (std::size_t k = 0; k < study.placements.size(); ++k) p[study.placements[k].key] = study.placements[k].values[at[k]].text;
    d["placement"] = p;
  }
  return d;
}

}  // namespace

std::string optimize_evaluations_csv(const OptimizeStudy& study, const OptimizeOutcome& outcome) {
  const OptimizeResult& r = outcome.result;
  std::vector<std::string> header{"evaluation", "stage"};
  for (const auto& p : study.placements) header.push_back(p.key);
  for (const auto& v : study.variables) header.push_back(v.key);
  for (const auto& g : study.objectives) header.push_back(g.name());
  for (const auto& g : study.constraints) header.push_back(g.name());
  header.push_back("feasible");
  if (study.objectives.size() == 2) header.push_back("pareto");
  for (const auto& e : study.edps)
    for (std::size_t run = 0; run < study.runs(); ++run) header.push_back(e + "@" + study.run_name(run));
  std::string out = csv_line(header) + "\n";
  for (std::size_t i = 0; i < r.evaluations.size(); ++i) {
    const Evaluation& e = r.evaluations[i];
    std::vector<std::string> cells{std::to_string(i + 1), e.stage};
    const auto at = study.choice_values(e.choice);
    for (std::size_t k = 0; k < study.placements.size(); ++k) cells.push_back(study.placements[k].values[at[k]].text);
    for (double x : e.x) cells.push_back(sweep_number_cell(x));
    for (double v : e.values.objectives) cells.push_back(sweep_number_cell(v));
    for (double v : e.values.constraints) cells.push_back(sweep_number_cell(v));
    cells.push_back(e.feasible ? "true" : "false");
    if (study.objectives.size() == 2) cells.push_back(on_front(r, i) ? "true" : "false");
    for (std::size_t k = 0; k < study.edps.size(); ++k)
      for (const auto& per_record : outcome.demands[i].values) cells.push_back(sweep_number_cell(per_record[k]));
    out += csv_line(cells) + "\n";
  }
  return out;
}

std::string optimize_json(const OptimizeStudy& study, const OptimizeOutcome& outcome) {
  const OptimizeResult& r = outcome.result;
  json j;
  j["study"] = study.file.string();
  j["scene"] = study.scene.string();
  j["method"] = study.options.method;
  j["tolerance"] = study.options.tolerance;
  j["max_evaluations"] = study.options.max_evaluations;
  j["seed"] = study.options.seed;
  json records = json::array();
  for (const auto& rec : study.records) {
    json one{{"record", rec.name}};
    if (study.im) one["im"] = rec.im;  // as read, g
    records.push_back(one);
  }
  j["records"] = records;
  if (study.im) j["intensity"] = {{"im", study.im->text()}, {"levels", study.levels}};
  json names = json::array();
  for (const auto& g : study.objectives) names.push_back(g.name());
  j["objectives"] = names;
  if (r.best) {
    const Evaluation& b = r.evaluations[*r.best];
    const json d = design_json(study, b);
    j["variables"] = d["variables"];
    j["placement"] = d["placement"];
    j["objective"] = b.values.objectives[0];
    if (study.objectives.size() == 2) j["objective_values"] = b.values.objectives;
    json cons = json::array();
    for (std::size_t k = 0; k < study.constraints.size(); ++k)
      cons.push_back({{"name", study.constraints[k].name()}, {"value", b.values.constraints[k]}, {"max", study.constraints[k].max}});
    j["constraints"] = cons;
    j["feasible"] = b.feasible;
  }
  j["evaluations"] = r.evaluations.size();
  j["runs"] = r.evaluations.size() * study.runs();
  j["from_cache"] = outcome.from_cache;
  j["runs_now"] = outcome.runs;
  json searches = json::array();
  for (const auto& s : r.runs) {
    json o{{"stage", s.stage}, {"placement", study.choice_label(s.choice)}, {"evaluations", s.evaluations}, {"stop", s.stop},
           {"best_evaluation", s.best + 1}, {"objective", r.evaluations[s.best].values.objectives[0]}};
    o.update(design_json(study, r.evaluations[s.best]));
    searches.push_back(o);
  }
  j["searches"] = searches;
  json history = json::array();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < r.evaluations.size(); ++i) {
    const Evaluation& e = r.evaluations[i];
    if (e.feasible) best = std::min(best, e.values.objectives[0]);
    history.push_back({{"evaluation", i + 1}, {"objective", e.values.objectives[0]}, {"feasible", e.feasible},
                       {"best", std::isfinite(best) ? json(best) : json(nullptr)}});
  }
  j["history"] = history;
  if (study.objectives.size() == 2) {
    json front = json::array();
    for (std::size_t i : r.pareto) {
      json p = design_json(study, r.evaluations[i]);
      p["objectives"] = r.evaluations[i].values.objectives;
      p["evaluation"] = i + 1;
      front.push_back(p);
    }
    j["pareto"] = front;
  }
  return j.dump(2) + "\n";
}

void write_optimize_files(const OptimizeStudy& study, const OptimizeOutcome& outcome, const fs::path& dir) {
  AtomicFile csv(dir / "evaluations.csv");
  csv.stream() << optimize_evaluations_csv(study, outcome);
  AtomicFile js(dir / "optimum.json");
  js.stream() << optimize_json(study, outcome);
  csv.commit();
  js.commit();
}

void plot_optimize(const OptimizeStudy& study, const OptimizeOutcome& outcome, const fs::path& image, const PlotStyle& style) {
  const OptimizeResult& r = outcome.result;
  std::ostringstream s;
  s << kGnuplotPreamble;
  if (study.objectives.size() == 1) {
    std::vector<std::vector<double>> ok(2), bad(2), best(2);
    double so_far = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < r.evaluations.size(); ++i) {
      const Evaluation& e = r.evaluations[i];
      auto& to = e.feasible ? ok : bad;
      to[0].push_back(static_cast<double>(i + 1));
      to[1].push_back(e.values.objectives[0]);
      if (e.feasible) so_far = std::min(so_far, e.values.objectives[0]);
      if (std::isfinite(so_far)) best[0].push_back(static_cast<double>(i + 1)), best[1].push_back(so_far);
    }
    gnuplot_datablock(s, "ok", ok);
    gnuplot_datablock(s, "bad", bad);
    gnuplot_datablock(s, "best", best);
    s << "set title " << gnuplot_quote(study.name + ": " + study.options.method + ", " + std::to_string(r.evaluations.size()) +
                                       " designs x " + std::to_string(study.runs()) + " runs")
      << " noenhanced\n"
      << "set xlabel 'evaluation'\nset ylabel " << gnuplot_quote(study.objectives[0].name()) << " noenhanced\n"
      << "set key top right noenhanced\n"
      << "plot $ok using 1:2 with points pt 7 ps 0.8 lc rgb '#1f77b4' title 'design'"
      << (bad[0].empty() ? "" : ", $bad using 1:2 with points pt 6 ps 0.8 lc rgb '#7f7f7f' title 'infeasible'")
      << (best[0].empty() ? "" : ", $best using 1:2 with steps lw 2.5 lc rgb '#d62728' title 'best so far'") << "\n";
  } else {
    std::vector<std::vector<double>> all(2), front(2);
    for (const auto& e : r.evaluations)
      if (e.feasible) all[0].push_back(e.values.objectives[0]), all[1].push_back(e.values.objectives[1]);
    for (std::size_t i : r.pareto)
      front[0].push_back(r.evaluations[i].values.objectives[0]), front[1].push_back(r.evaluations[i].values.objectives[1]);
    gnuplot_datablock(s, "all", all);
    gnuplot_datablock(s, "front", front);
    s << "set title " << gnuplot_quote(study.name + ": Pareto front, " + std::to_string(r.pareto.size()) + " of " +
                                       std::to_string(r.evaluations.size()) + " designs")
      << " noenhanced\n"
      << "set xlabel " << gnuplot_quote(study.objectives[0].name()) << " noenhanced\n"
      << "set ylabel " << gnuplot_quote(study.objectives[1].name()) << " noenhanced\n"
      << "set key top right noenhanced\n"
      << "plot $all using 1:2 with points pt 6 ps 0.8 lc rgb '#7f7f7f' title 'feasible designs', "
      << "$front using 1:2 with linespoints pt 7 ps 1 lw 2 lc rgb '#d62728' title 'Pareto front'\n";
  }
  render_gnuplot(s.str(), image, style);
}

}  // namespace adjoin
