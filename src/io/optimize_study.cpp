// The study file of `adjoin optimize` (io/optimize_study.hpp; docs/reference/study-file.md):
// every problem an InputError "FILE:LINE: KEY: what was expected".
#include "adjoin/io/optimize_study.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <toml++/toml.h>

#include "../detail/nearest.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/study/sweep_columns.hpp"

namespace adjoin {
namespace fs = std::filesystem;
namespace {

const std::vector<std::string> kKeys{"scene",     "suite",      "units",       "im",     "level",  "levels",
                                     "variables", "placements", "objective",   "objectives", "constraints",
                                     "method",    "tolerance",  "max_evaluations", "seed", "pareto_points"};

// A double as a TOML float ("1.0", not "1"): what a --set of it says.
std::string toml_float(double v) {
  std::string s = sweep_number_cell(v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

class StudyReader {
 public:
  explicit StudyReader(std::string name) : name_(std::move(name)) {}
  [[noreturn]] void fail(const toml::node* node, const std::string& key, const std::string& message) const {
    throw InputError(where(node) + key + ": " + message);
  }
  std::string where(const toml::node* node) const {
    return name_ + (node && node->source().begin.line > 0 ? ":" + std::to_string(node->source().begin.line) : "") + ": ";
  }
  std::size_t line(const toml::node* node) const { return node ? node->source().begin.line : 0; }
  const std::string& name() const { return name_; }

  void check_keys(const toml::table& t, const std::vector<std::string>& known, const std::string& within) const {
    for (const auto& [key, node] : t) {
      const std::string k(key.str());
      if (std::find(known.begin(), known.end(), k) != known.end()) continue;
      std::string list;
      for (const auto& c : known) list += (list.empty() ? "" : ", ") + c;
      fail(&node, within + k, "unknown key; did you mean " + detail::nearest(k.substr(0, 200), known) + "? (expected one of: " + list + ")");
    }
  }
  std::string string(const toml::table& t, const std::string& key, const std::string& path) const {
    const toml::node* n = t.get(key);
    if (!n || !n->is_string() || n->as_string()->get().empty()) fail(n ? n : &t, path, "expected a string");
    return n->as_string()->get();
  }
  double number(const toml::node* n, const std::string& path) const {
    const auto v = n ? n->value<double>() : std::nullopt;
    if (!v || !std::isfinite(*v)) fail(n, path, "expected a finite number");
    return *v;
  }
  std::int64_t integer(const toml::node* n, const std::string& path, std::int64_t lo, std::int64_t hi) const {
    const auto* v = n->as_integer();
    if (!v || v->get() < lo || v->get() > hi)
      fail(n, path, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
    return v->get();
  }
  const toml::table& table(const toml::node* n, const std::string& path, const std::string& example) const {
    if (!n || !n->is_table()) fail(n, path, "expected a table, e.g. " + example);
    return *n->as_table();
  }
  const toml::array& array(const toml::node* n, const std::string& path, const std::string& example) const {
    if (!n || !n->is_array() || n->as_array()->empty()) fail(n, path, "expected a list, e.g. " + example);
    return *n->as_array();
  }

 private:
  std::string name_;
};

fs::path relative_to(const fs::path& folder, const std::string& path) {
  const fs::path p(path);
  return p.is_relative() && !folder.empty() ? (folder / p).lexically_normal() : p;
}

// A placement's value: a number, a string, true/false, or a list of them (its TOML text).
SweepValue placement_value(const StudyReader& r, const toml::node& n, const std::string& path) {
  if (auto v = n.as_integer()) return {v->get(), std::to_string(v->get())};
  if (auto v = n.as_floating_point()) {
    if (!std::isfinite(v->get())) r.fail(&n, path, "expected a finite number");
    return {v->get(), toml_float(v->get())};
  }
  if (auto v = n.as_boolean()) return {v->get(), v->get() ? "true" : "false"};
  if (auto v = n.as_string()) return {v->get(), "\"" + v->get() + "\""};
  if (auto a = n.as_array()) {
    std::string text = "[";
    for (const auto& e : *a) {
      if (e.is_array() || e.is_table()) r.fail(&e, path, "expected a list of numbers or strings, e.g. [3, 3]");
      text += (text.size() > 1 ? ", " : "") + placement_value(r, e, path).text;
    }
    return {text + "]", text + "]"};
  }
  r.fail(&n, path, "expected a number, a string or a list such as [3, 3]");
}

StudyGoal read_goal(const StudyReader& r, const toml::node* n, const std::string& path, bool limit) {
  const std::string example = limit ? "{edp = \"link1.stroke_max\", statistic = \"max\", max = 0.05}"
                                    : "{edp = \"A.drift_ratio_max\", statistic = \"mean\"}";
  const toml::table& t = r.table(n, path, example);
  std::vector<std::string> keys{"edp", "statistic", "event", "probability_at"};
  if (limit) keys.push_back("max");
  r.check_keys(t, keys, path + ".");
  StudyGoal g;
  g.line = r.line(n);
  g.key = path;
  if (t.contains("event") || t.contains("probability_at")) {
    if (t.contains("edp") || t.contains("statistic"))
      r.fail(n, path, "give edp (and statistic), or event and probability_at (a fragility probability), not both");
    if (!t.contains("event") || !t.contains("probability_at"))
      r.fail(n, path, "event and probability_at go together: P(event | IM = probability_at), e.g. "
                      "{event = \"contact1.impacts > 0\", probability_at = 0.35}");
    g.event = r.string(t, "event", path + ".event");
    g.probability_at = r.number(t.get("probability_at"), path + ".probability_at");
    if (!(g.probability_at > 0.0)) r.fail(t.get("probability_at"), path + ".probability_at", "expected an intensity > 0 (g)");
  } else {
    g.edp = r.string(t, "edp", path + ".edp");
    if (const toml::node* s = t.get("statistic")) {
      const auto stat = s->is_string() ? statistic_from_name(s->as_string()->get()) : std::nullopt;
      if (!stat) r.fail(s, path + ".statistic", "expected \"mean\", \"median\", \"p84\" or \"max\" (over the suite's runs)");
      g.statistic = *stat;
    }
  }
  if (limit) {
    if (!t.contains("max")) r.fail(n, path, "missing max (the constraint is statistic(edp) <= max)");
    g.max = r.number(t.get("max"), path + ".max");
  }
  return g;
}

void read_variables(const StudyReader& r, const toml::table& o, OptimizeStudy& study) {
  const toml::node* n = o.get("variables");
  if (!n) return;
  const auto& list = r.array(n, "variables", "[{key = \"link.1.slip_force\", min = 1.0e4, max = 5.0e5}]");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "variables[" + std::to_string(i + 1) + "]";
    const toml::table& t = r.table(list.get(i), path, "{key = \"link.1.slip_force\", min = 1.0e4, max = 5.0e5}");
    r.check_keys(t, {"key", "min", "max", "start"}, path + ".");
    OptimizeVariable v;
    v.key = r.string(t, "key", path + ".key");
    if (!t.contains("min") || !t.contains("max")) r.fail(&t, path, "expected min and max (the variable's bounds)");
    v.min = r.number(t.get("min"), path + ".min");
    v.max = r.number(t.get("max"), path + ".max");
    if (!(v.min < v.max))
      r.fail(t.get("min"), path + ".min", "min = " + sweep_number_cell(v.min) + " must be below max = " + sweep_number_cell(v.max));
    if (const toml::node* s = t.get("start")) {
      v.start = r.number(s, path + ".start");
      if (*v.start < v.min || *v.start > v.max) r.fail(s, path + ".start", "expected a value from min to max");
    }
    for (const auto& w : study.variables)
      if (w.key == v.key) r.fail(&t, path + ".key", "\"" + v.key + "\" is already a variable");
    study.variables.push_back(v);
    study.variable_lines.push_back(r.line(&t));
  }
}

void read_placements(const StudyReader& r, const toml::table& o, OptimizeStudy& study) {
  const toml::node* n = o.get("placements");
  if (!n) return;
  const auto& list = r.array(n, "placements", "[{key = \"link.1.floors\", values = [[1, 1], [2, 2], [3, 3]]}]");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "placements[" + std::to_string(i + 1) + "]";
    const toml::table& t = r.table(list.get(i), path, "{key = \"link.1.floors\", values = [[1, 1], [2, 2]]}");
    r.check_keys(t, {"key", "values"}, path + ".");
    StudyPlacement p;
    p.key = r.string(t, "key", path + ".key");
    p.line = r.line(&t);
    for (const auto& v : r.array(t.get("values"), path + ".values", "[[1, 1], [2, 2], [3, 3]]"))
      p.values.push_back(placement_value(r, v, path + ".values"));
    for (const auto& w : study.variables)
      if (w.key == p.key) r.fail(&t, path + ".key", "\"" + p.key + "\" is a variable too");
    study.placements.push_back(std::move(p));
  }
}

void read_goals(const StudyReader& r, const toml::table& o, OptimizeStudy& study) {
  const toml::node* one = o.get("objective");
  const toml::node* two = o.get("objectives");
  if (!one == !two)
    r.fail(one ? one : &o, "objective", "give objective = {edp = \"...\", statistic = \"mean\"}, or objectives = [{...}, {...}] (two: a Pareto front)");
  if (one) study.objectives.push_back(read_goal(r, one, "objective", false));
  else {
    const auto& list = r.array(two, "objectives", "[{edp = \"A.drift_ratio_max\"}, {edp = \"link1.force_max\"}]");
    if (list.size() != 2) r.fail(two, "objectives", "expected two objectives (a Pareto front); give objective = {...} for one");
    for (std::size_t i = 0; i < 2; ++i) study.objectives.push_back(read_goal(r, list.get(i), "objectives[" + std::to_string(i + 1) + "]", false));
  }
  if (const toml::node* c = o.get("constraints")) {
    const auto& list = r.array(c, "constraints", "[{edp = \"link1.stroke_max\", statistic = \"max\", max = 0.05}]");
    for (std::size_t i = 0; i < list.size(); ++i)
      study.constraints.push_back(read_goal(r, list.get(i), "constraints[" + std::to_string(i + 1) + "]", true));
  }
}

void read_options(const StudyReader& r, const toml::table& o, OptimizeStudy& study) {
  OptimizeOptions& opt = study.options;
  if (const toml::node* n = o.get("method")) {
    if (!n->is_string() || !find_optimize_method(n->as_string()->get()))
      r.fail(n, "method", (n->is_string() ? "\"" + n->as_string()->get() + "\" is not a method; " : std::string()) +
                              "expected one of " + optimize_method_names());
    opt.method = n->as_string()->get();
  }
  if (const toml::node* n = o.get("tolerance")) {
    opt.tolerance = r.number(n, "tolerance");
    if (!(opt.tolerance > 0.0 && opt.tolerance < 1.0))
      r.fail(n, "tolerance", "expected a number in (0, 1): a fraction of each variable's range");
  }
  if (const toml::node* n = o.get("max_evaluations"))
    opt.max_evaluations = static_cast<std::size_t>(r.integer(n, "max_evaluations", 1, 100000));
  if (const toml::node* n = o.get("seed")) opt.seed = static_cast<std::uint32_t>(r.integer(n, "seed", 0, 4294967295));
  if (const toml::node* n = o.get("pareto_points")) {
    if (study.objectives.size() != 2) r.fail(n, "pareto_points", "only with two objectives (objectives = [...])");
    opt.pareto_points = static_cast<std::size_t>(r.integer(n, "pareto_points", 2, 100));
  }
}

void read_suite_keys(const StudyReader& r, const toml::table& o, const fs::path& folder, OptimizeStudy& study) {
  const toml::node* s = o.get("suite");
  if (!s) r.fail(&o, "suite", "missing (record files or folders, relative to the study file)");
  if (s->is_string()) study.suite.push_back(relative_to(folder, s->as_string()->get()).string());
  else
    for (const auto& e : r.array(s, "suite", "[\"records/real/peer\", \"records/real/smc\"]")) {
      if (!e.is_string()) r.fail(&e, "suite", "expected file or folder names (strings)");
      study.suite.push_back(relative_to(folder, e.as_string()->get()).string());
    }
  if (const toml::node* n = o.get("units")) study.units = r.string(o, "units", "units"), (void)n;
  const toml::node* im = o.get("im");
  const toml::node* level = o.get("level");
  const toml::node* levels = o.get("levels");
  if (level && levels) r.fail(levels, "levels", "give level (one IM) or levels (stripes), not both");
  if (!level) level = levels;
  if (!im != !level)
    r.fail(im ? im : level, im ? "level" : "im", "im and level (or levels) go together: each record scaled so that its im equals the level (g)");
  if (!im) return;
  try {
    study.im = parse_intensity_measure(im->is_string() ? im->as_string()->get() : std::string("?"));
  } catch (const InputError&) {
    r.fail(im, "im", "expected \"pga\" or \"sa:T\" (the 5 %-damped PSA at period T in s, e.g. \"sa:1.0\")");
  }
  const std::string key = levels ? "levels" : "level";
  std::vector<const toml::node*> values{level};
  if (levels) {
    values.clear();
    for (const auto& v : r.array(levels, key, "[0.1, 0.2, 0.3, 0.4]")) values.push_back(&v);
  }
  for (const toml::node* v : values) {
    const double x = r.number(v, key);
    if (!(x > 0.0)) r.fail(v, key, "expected intensities > 0 (g)");
    if (std::find(study.levels.begin(), study.levels.end(), x) != study.levels.end())
      r.fail(v, key, "the level " + sweep_number_cell(x) + " appears twice");
    study.levels.push_back(x);
  }
}

// Messages of the suite's reader name --suite and --units (ida's options): here they are keys.
InputError as_key(const StudyReader& r, const toml::node* n, const InputError& e) {
  std::string m = e.what();
  for (const std::string option : {"--suite", "--units"})
    if (m.rfind(option, 0) == 0) m = m.substr(2);
  return InputError(r.where(n) + m);
}

// Tries a design's edit on the scene (each bound, each placement value) so that a key the
// scene does not take is named with its line in the study file.
void try_edit(const OptimizeStudy& study, const std::string& key, const SweepValue& value, std::size_t line) {
  SweepSpec spec = study.sweep;
  spec.common.set = {{key, value}};
  spec.common.line = line;
  (void)sweep_scene(spec, 0);
}

void prepare(const StudyReader& r, const toml::table& o, const std::string& text, OptimizeStudy& study,
             std::vector<std::string>* skipped) {
  try {
    study.records = read_ida_suite(study.suite, study.units, study.im.value_or(IntensityMeasure{}), skipped, "--units");
  } catch (const InputError& e) {
    throw as_key(r, o.get("suite"), e);
  }
  std::vector<IdaMotion> motions;
  for (std::size_t k = 0; k < study.runs(); ++k) {
    const IdaRecord& rec = study.run_record(k);
    motions.push_back({rec.name, rec.file, study.im ? study.run_level(k) / rec.im : 1.0});
  }
  try {
    study.sweep = ida_sweep(study.scene, motions, study.units, r.name());
  } catch (const InputError& e) {
    throw InputError(r.where(o.get("scene")) + "scene: " + e.what());
  }
  const auto use = [&](const std::string& column) {
    if (std::find(study.edps.begin(), study.edps.end(), column) == study.edps.end()) study.edps.push_back(column);
  };
  std::vector<std::string> columns;
  for (const auto& c : sweep_columns(study.sweep)) columns.push_back(c.name);
  for (auto* goals : {&study.objectives, &study.constraints})
    for (auto& g : *goals) {
      const std::string at = r.name() + ":" + std::to_string(g.line) + ": " + g.key;
      if (!g.fragility()) {
        check_ida_edps(study.sweep, {g.edp}, at + ".edp");
        use(g.edp);
        continue;
      }
      if (study.levels.size() < 2)
        throw InputError(at + ": a fragility probability is fitted to stripes: give im and levels = [L1, L2, ...] (at least two IM levels, g)");
      try {
        g.parsed = FragilityEvent::parse(g.event, columns);
      } catch (const InputError& e) {
        std::string m = e.what();
        if (m.rfind("--event ", 0) == 0) m = m.substr(8);
        throw InputError(at + ".event " + m);
      }
      for (std::size_t c : g.parsed->columns_used()) use(columns[c]);
    }
  for (std::size_t i = 0; i < study.variables.size(); ++i)
    for (double v : {study.variables[i].min, study.variables[i].max})
      try_edit(study, study.variables[i].key, SweepValue{v, toml_float(v)}, study.variable_lines[i]);
  for (const auto& p : study.placements)
    for (const auto& v : p.values) try_edit(study, p.key, v, p.line);
  study.fingerprint = sweep_fingerprint(text, study.sweep.fingerprint);
}

}  // namespace

std::string StudyGoal::name() const {
  if (!fragility()) return statistic_name(statistic) + "(" + edp + ")";
  return "P(" + event + " | im = " + sweep_number_cell(probability_at) + ")";
}

std::string OptimizeStudy::run_name(std::size_t r) const {
  return run_record(r).name + (levels.size() > 1 ? "@" + sweep_number_cell(run_level(r)) : std::string());
}

std::size_t OptimizeStudy::choices() const {
  std::size_t n = 1;
  for (const auto& p : placements) n *= p.values.size();
  return n;
}

std::vector<std::size_t> OptimizeStudy::choice_values(std::size_t choice) const {
  std::vector<std::size_t> at(placements.size());
  for (std::size_t k = placements.size(); k-- > 0;) {
    at[k] = choice % placements[k].values.size();
    choice /= placements[k].values.size();
  }
  return at;
}

std::string OptimizeStudy::choice_label(std::size_t choice) const {
  std::string label;
  const auto at = choice_values(choice);
  for (std::size_t k = 0; k < placements.size(); ++k)
    label += (label.empty() ? "" : ", ") + placements[k].key + "=" + placements[k].values[at[k]].text;
  return label;
}

std::vector<double> OptimizeStudy::limits() const {
  std::vector<double> l;
  for (const auto& c : constraints) l.push_back(c.max);
  return l;
}

OptimizeStudy load_optimize_study(const fs::path& file, std::vector<std::string>* skipped) {
  const std::string text = read_text_file(file, "study");
  const StudyReader r(file.string());
  toml::table root;
  try {
    root = toml::parse(text, file.string());
  } catch (const toml::parse_error& e) {
    throw InputError(file.string() + ":" + std::to_string(e.source().begin.line) + ": not valid TOML: " + std::string(e.description()));
  }
  r.check_keys(root, {"optimize"}, "");
  const toml::table& o = r.table(root.get("optimize"), "[optimize]", "[optimize] with scene, suite, variables, objective");
  r.check_keys(o, kKeys, "");
  OptimizeStudy study;
  study.file = file;
  study.name = file.stem().string();
  const fs::path folder = file.parent_path();
  study.scene = relative_to(folder, r.string(o, "scene", "scene"));
  read_suite_keys(r, o, folder, study);
  read_variables(r, o, study);
  read_placements(r, o, study);
  if (study.variables.empty() && study.placements.empty())
    r.fail(&o, "variables", "expected variables = [{key = ..., min = ..., max = ...}] or placements = [{key = ..., values = [...]}]");
  read_goals(r, o, study);
  read_options(r, o, study);
  prepare(r, o, text, study, skipped);
  return study;
}

SweepSpec design_sweep(const OptimizeStudy& study, std::size_t choice, const std::vector<double>& x) {
  SweepSpec spec = study.sweep;
  spec.common.set.clear();
  const auto at = study.choice_values(choice);
  for (std::size_t k = 0; k < study.placements.size(); ++k)
    spec.common.set.emplace_back(study.placements[k].key, study.placements[k].values[at[k]]);
  for (std::size_t i = 0; i < study.variables.size(); ++i)
    spec.common.set.emplace_back(study.variables[i].key, SweepValue{x[i], toml_float(x[i])});
  return spec;
}

}  // namespace adjoin
