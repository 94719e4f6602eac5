#include "adjoin/io/building_scene.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/io/text_file.hpp"
#include "structure_edits.hpp"
#include "sweep_scene_tree.hpp"
#include "toml_text.hpp"
#include "adjoin/study/builder.hpp"

namespace adjoin {
namespace {

bool overridden(const std::vector<std::string>& overrides, const std::string& key) {
  return std::any_of(overrides.begin(), overrides.end(), [&](const std::string& o) {
    const auto eq = o.find('=');
    std::string k = o.substr(0, eq);
    k.erase(0, k.find_first_not_of(' '));
    k.erase(k.find_last_not_of(' ') + 1);
    return k == key;
  });
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// The in-structure spectra's signals: "ground" or a floor's absolute acceleration X.aN_abs.
void check_spectra_signals(const std::vector<std::string>& signals, const structure::Structure& s, const toml::table& parsed,
                           const std::string& file, const std::vector<std::string>& overrides) {
  std::set<std::string> seen;
  for (const auto& signal : signals) {
    if (!seen.insert(signal).second) {
      // A floor listed twice would get its spectra twice.
      const toml::node* n = parsed.at_path("output.spectra.signals").node();
      const std::string where = overridden(overrides, "output.spectra.signals") ? "--set output.spectra.signals"
                                : n ? file + ":" + std::to_string(n->source().begin.line) : file;
      throw InputError(where + ": output.spectra.signals: " + escaped_excerpt(signal) + " is listed twice; list each signal once",
                       "output.spectra.signals");
    }
    if (signal == "ground") continue;
    const structure::Building* b = nullptr;
    if (signal.rfind("A.a", 0) == 0) b = &s.a;
    if (signal.rfind("B.a", 0) == 0 && s.b) b = &*s.b;
    bool ok = false;
    if (b && signal.size() > 7 && signal.compare(signal.size() - 4, 4, "_abs") == 0) {
      const std::string digits = signal.substr(3, signal.size() - 7);
      std::size_t floor = 0;
      ok = digits.size() < 5 && parse_count(digits, &floor) && floor >= 1 && floor <= static_cast<std::size_t>(b->floors());
    }
    if (ok) continue;
    std::string where = file;
    if (overridden(overrides, "output.spectra.signals")) {
      where = "--set output.spectra.signals";
    } else if (const toml::node* n = parsed.at_path("output.spectra.signals").node()) {
      where += ":" + std::to_string(n->source().begin.line);
    }
    std::string expected = "\"ground\" or a floor's absolute acceleration A.aN_abs (N = 1.." + std::to_string(s.a.floors()) + ")";
    if (s.b) expected += " or B.aN_abs (N = 1.." + std::to_string(s.b->floors()) + ")";
    throw InputError(where + ": output.spectra.signals: " + escaped_excerpt(signal) + " is not a signal of this structure; expected " + expected,
                     "output.spectra.signals");
  }
}

// solver.scheme on a building scene: the structure step takes "implicit" (backward Euler after
// a damper's switch when the stiffest mode is not resolved) and "implicit-damped" (after every
// switch); the two-block system's other schemes would be silently ignored, so they are refused.
StructureSolverOptions::Restart restart_for_scheme(Scheme scheme, const toml::table& parsed, const std::string& file,
                                       const std::vector<std::string>& overrides) {
  if (scheme == Scheme::implicit) return StructureSolverOptions::Restart::automatic;
  if (scheme == Scheme::implicit_damped) return StructureSolverOptions::Restart::always;
  std::string where = file;
  if (overridden(overrides, "solver.scheme")) {
    for (const auto& o : overrides)
      if (overridden({o}, "solver.scheme")) where = "--set " + text_excerpt(o);  // the last one is in force
  } else if (const toml::node* n = parsed.at_path("solver.scheme").node()) {
    where += ":" + std::to_string(n->source().begin.line);
  }
  throw InputError(where + ": solver.scheme = \"" + to_string(scheme) +
                   "\": a building scene runs the structure step, which takes \"implicit\" (the default) or "
                   "\"implicit-damped\" (backward Euler after every damper switch); \"paper\" and \"implicit-gl\" are the "
                   "two-block system's",
                   "solver.scheme");
}

}  // namespace

BuildingScene load_building_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                                  const std::vector<std::string>& unsets) {
  return parse_building_scene(read_text_file(file, "scene"), file, overrides, unsets);
}

BuildingScene parse_building_scene(const std::string& text, const std::filesystem::path& file,
                                   const std::vector<std::string>& overrides, const std::vector<std::string>& unsets) {
  return detail::building_scene_from_tree(detail::parse_toml_text(text, file.string()), file, overrides, unsets);
}

detail::CopiedFrom detail::copied_from(const toml::node& copy, const toml::node& parsed) {
  CopiedFrom map;
  const auto walk = [&map](const auto& self, const toml::node& c, const toml::node& p) -> void {
    map.emplace(&c, &p);
    if (const toml::table* ct = c.as_table()) {
      const toml::table* pt = p.as_table();
      if (!pt) return;
      for (const auto& [key, node] : *ct)
        if (const toml::node* original = pt->get(key.str())) self(self, node, *original);
    } else if (const toml::array* ca = c.as_array()) {
      const toml::array* pa = p.as_array();
      if (!pa) return;
      for (std::size_t i = 0; i < ca->size() && i < pa->size(); ++i) self(self, *ca->get(i), *pa->get(i));
    }
  };
  walk(walk, copy, parsed);
  return map;
}

BuildingScene detail::building_scene_from_tree(const toml::table& parsed, const std::filesystem::path& file,
                                               const std::vector<std::string>& overrides,
                                               const std::vector<std::string>& unsets) {
  // The structure's edits go to its reader, the others to the ground, solver and output's.
  std::vector<std::string> base_overrides, base_unsets;
  for (const auto& o : overrides) {
    const std::string key = o.substr(0, o.find('='));
    if (key.rfind("model", 0) == 0 && (key.size() == 5 || key[5] == '.' || key[5] == ' '))
      throw InputError("--set " + text_excerpt(o) + ": a building scene's [model] holds only units = \"SI\"; the buildings, links "
                       "and contacts carry the rest (building.A.period, link.1.slip_ratio, ...)",
                       "model");
    if (!detail::is_structure_key(key)) base_overrides.push_back(o);
  }
  for (const auto& u : unsets)
    if (!detail::is_structure_key(u)) base_unsets.push_back(u);
  // One copy of the parsed tree: the structure's edits are made on it and its structure read,
  // then the rest (the base drops the structure's sections). Messages cite the parsed lines.
  toml::table tree = parsed;
  const CopiedFrom copied = copied_from(tree, parsed);
  structure::Structure structure = structure_from_tree(tree, file.string(), overrides, unsets, &copied);
  BuildingScene b = building_base_from_tree(std::move(tree), file.string(), base_overrides, base_unsets, &parsed);
  b.file = file;
  b.structure = std::move(structure);
  if (b.output.spectra) check_spectra_signals(b.output.spectra->signals, b.structure, parsed, file.string(), overrides);
  // (The base's warnings about periods are about its two-block rules, not this structure.)
  std::erase_if(b.warnings, [](const std::string& w) { return w.find("period") != std::string::npos; });

  // The base read [solver] after the --unset and --set edits: it chose a tolerance exactly
  // when solver.h is not given, and says a rule for t_end exactly when t_end is not. The
  // structure's periods decide the defaults, by the rules of study/builder.hpp.
  AccuracyOptions& a = b.accuracy;
  const bool h_given = !a.tolerance;
  const bool t_end_given = a.t_end_rule.empty();
  const double dt = b.ground->sample_interval();  // s (unit time scale)
  if (h_given) {
    a.h_rule = "given";
  } else {
    // Without solver.h the step is chosen for solver.tolerance (given, or the building
    // scenes' default).
    if (!a.tolerance_given) a.tolerance = kBuildingDefaultTolerance;
    const Chosen h = default_building_step(b.structure, dt, tolerance_rule(*a.tolerance, a.tolerance_given));
    b.solver.h = h.value;
    a.h_rule = h.rule;
  }
  if (t_end_given) {
    a.t_end_rule = "given";
  } else {
    const Chosen t_end = default_building_horizon(b.structure, b.ground->duration());
    b.solver.t_end = t_end.value;
    a.t_end_rule = t_end.rule;
  }
  b.solver = with_scheme(b.solver, b.solver.scheme);
  b.solver.restart = restart_for_scheme(b.solver.scheme, parsed, file.string(), overrides);
  std::string error;
  if (!b.solver.IsValid(&error)) throw InputError(file.string() + ": " + error);
  if (dt > 0.0 && b.solver.h > dt * (1 + 1e-9))
    b.warnings.push_back("solver.h = " + number(b.solver.h) + " s is coarser than the record's sampling interval " + number(dt) +
                         " s: the record's peaks between steps are not seen");
  return b;
}

}  // namespace adjoin
