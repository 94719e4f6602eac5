#include "adjoin/io/scene.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/structure_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <toml++/toml.h>

#include "adjoin/structure/contact_rules.hpp"
#include "sweep_scene_tree.hpp"
#include "toml_text.hpp"

#include "../detail/nearest.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"
#include "ground_sources/registry.hpp"
#include "scene_reader.hpp"
#include "adjoin/io/file_name.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/io/two_block_names.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/structure/two_block.hpp"

namespace adjoin {
namespace {

using detail::Kind;
using detail::KeySpec;
using detail::SceneReader;

// The scene schema: these keys, with [ground]'s from the ground sources' table
// (ground_sources/registry.cpp) after model's. Ground keys are checked again against the
// chosen source.
const std::vector<KeySpec>& schema() {
  static const std::vector<KeySpec> keys = [] {
    std::vector<KeySpec> out = {
      {"name", Kind::string},
      {"model.units", Kind::string},
      {"model.rho", Kind::number},        {"model.eps", Kind::number},
      {"model.mu", Kind::number},         {"model.gap0", Kind::number},
      {"model.base_friction", Kind::number},
      {"model.m1", Kind::number},         {"model.m2", Kind::number},
      {"model.k1", Kind::number},         {"model.k2", Kind::number},
      {"model.slip_force", Kind::number},
      {"model.rod1.order", Kind::number}, {"model.rod1.tau_x", Kind::number},
      {"model.rod1.tau_f", Kind::number}, {"model.rod1.elastic", Kind::boolean},
      {"model.rod2.order", Kind::number}, {"model.rod2.tau_x", Kind::number},
      {"model.rod2.tau_f", Kind::number}, {"model.rod2.elastic", Kind::boolean},
      {"model.contact.model", Kind::string},
      {"model.contact.stiffness", Kind::number}, {"model.contact.restitution", Kind::number},
      {"model.contact.damping", Kind::number},   {"model.contact.tension_cut", Kind::boolean},
    };
    out.push_back({"ground.source", Kind::string});
    out.push_back({"ground.scale", Kind::number});
    for (const detail::GroundSource& source : detail::ground_sources())
      for (const KeySpec& key : source.keys())
        if (std::none_of(out.begin(), out.end(), [&](const KeySpec& k) { return std::string_view(k.path) == key.path; }))
          out.push_back(key);
    out.insert(out.end(), {
      {"solver.scheme", Kind::string},    {"solver.history", Kind::string},
      {"solver.history_tolerance", Kind::number},
      {"solver.h", Kind::number},         {"solver.t_end", Kind::number},
      {"solver.locate_switches", Kind::boolean},
      {"solver.error_estimate", Kind::boolean}, {"solver.tolerance", Kind::number},
      {"output.timeseries", Kind::boolean}, {"output.every", Kind::integer},
      {"output.peaks", Kind::boolean},      {"output.phases", Kind::boolean},
      {"output.pounding", Kind::boolean},   {"output.energy", Kind::boolean},
      {"output.energy_history", Kind::boolean},
      {"output.spectra.signals", Kind::strings}, {"output.spectra.damping", Kind::numbers},
      {"output.spectra.periods", Kind::numbers},
    });
    return out;
  }();
  return keys;
}

const std::vector<std::string> kTables = {"model", "model.rod1", "model.rod2", "model.contact", "ground",
                                          "solver", "output", "output.spectra"};

using detail::nearest;

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
  return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
}

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::number: return "a number";
    case Kind::integer: return "an integer";
    case Kind::string: return "a string";
    case Kind::boolean: return "true or false";
    case Kind::numbers: return "an array of numbers";
    case Kind::strings: return "an array of strings";
  }
  return "?";
}

// Numbers in the scene's messages: 12 significant digits (io/text_file.hpp).
std::string format_number(double v) { return number_text(v, 12); }

std::vector<std::string> all_known_keys() {
  std::vector<std::string> keys;
  for (const auto& k : schema()) keys.emplace_back(k.path);
  return keys;
}

// Every key must be known and of the expected type.
void check_keys(const SceneReader& reader, const toml::table& table, const std::string& prefix) {
  for (const auto& [key, node] : table) {
    const std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
    if (node.is_table()) {
      if (std::find(kTables.begin(), kTables.end(), path) == kTables.end()) {
        std::vector<std::string> candidates = kTables;
        for (const auto& k : schema()) candidates.emplace_back(k.path);
        reader.fail(path, "unknown section [" + text_excerpt(path) + "]; did you mean " + nearest(path.substr(0, 200), candidates) + "?");
      }
      check_keys(reader, *node.as_table(), path);
      continue;
    }
    auto spec = std::find_if(schema().begin(), schema().end(),
                             [&](const KeySpec& s) { return path == s.path; });
    if (spec == schema().end()) {
      if (std::find(kTables.begin(), kTables.end(), path) != kTables.end())
        reader.fail(path, path + " must be a table ([" + path + "])");
      reader.fail(path, "unknown key " + text_excerpt(path) + "; did you mean " + nearest(path.substr(0, 200), all_known_keys()) + "?");
    }
    bool ok = false;
    switch (spec->kind) {
      case Kind::number: ok = node.is_floating_point() || node.is_integer(); break;
      case Kind::integer: ok = node.is_integer(); break;
      case Kind::string: ok = node.is_string(); break;
      case Kind::boolean: ok = node.is_boolean(); break;
      case Kind::numbers:
        ok = node.is_array() && node.as_array()->size() > 0 &&
             std::all_of(node.as_array()->begin(), node.as_array()->end(),
                         [](const toml::node& v) { return v.is_floating_point() || v.is_integer(); });
        break;
      case Kind::strings:
        ok = node.is_array() && node.as_array()->size() > 0 &&
             std::all_of(node.as_array()->begin(), node.as_array()->end(), [](const toml::node& v) { return v.is_string(); });
        break;
    }
    if (!ok) reader.fail(path, path + " must be " + kind_name(spec->kind));
  }
}

// Removes the dotted key (a value or a table) from the parsed table; false if it is not there.
// Removing nodes keeps the others' source lines, as re-parsing edited text would not.
bool remove_key(toml::table& table, const std::string& key) {
  toml::table* parent = &table;
  std::string leaf = key;
  if (const auto dot = key.rfind('.'); dot != std::string::npos) {
    parent = table.at_path(key.substr(0, dot)).as_table();
    leaf = key.substr(dot + 1);
  }
  if (!parent || !parent->contains(leaf)) return false;
  parent->erase(leaf);
  return true;
}

// Splits "a.b.c=value" and puts the TOML value (or a bare string) at that path; `typed` is the
// value already parsed ({"v" = value}; a sweep's), or null.
void apply_override(toml::table& table, const std::string& text, std::map<std::string, std::string>& origins,
                    const toml::table* typed = nullptr) {
  const auto eq = text.find('=');
  const std::string origin = "--set " + text_excerpt(text);
  if (eq == std::string::npos || eq == 0)
    throw InputError(origin + ": expected KEY=VALUE with a dotted key, e.g. solver.h=0.001");
  // "solver.h = 0.01" (spaces around '=', as in the scene file) means "solver.h=0.01".
  std::string key = trim(text.substr(0, eq));
  const std::string value = trim(text.substr(eq + 1));
  if (key.empty()) throw InputError(origin + ": expected KEY=VALUE with a dotted key, e.g. solver.h=0.001");
  const toml::table holder = typed ? toml::table{} : detail::toml_value_of(value);
  const toml::table& valued = typed ? *typed : holder;
  std::vector<std::string> parts;
  std::stringstream stream(key);
  for (std::string part; std::getline(stream, part, '.');) {
    if (part.empty()) throw InputError(origin + ": empty component in key " + escaped_excerpt(key));
    parts.push_back(part);
  }
  toml::table* current = &table;
  std::string path;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    path += (path.empty() ? "" : ".") + parts[i];
    auto* next = current->get(parts[i]);
    if (!next) {
      // A table the override creates is the override's: an error about it names the --set.
      current->insert(parts[i], toml::table{});
      next = current->get(parts[i]);
      origins.emplace(path, origin);
    }
    if (!next->is_table()) throw InputError(origin + ": " + text_excerpt(parts[i]) + " is not a table", field_path(key));
    current = next->as_table();
  }
  current->insert_or_assign(parts.back(), *valued.get("v"));
  origins[key] = origin;
}

Rod read_rod(const SceneReader& r, const std::string& prefix, double time_scale) {
  Rod rod;
  rod.elastic = r.boolean(prefix + ".elastic", false);
  if (rod.elastic) {
    for (const char* k : {".order", ".tau_x", ".tau_f"})
      if (r.has(prefix + k))
        r.fail(prefix + k, prefix + k + " is not used by an elastic rod (" + prefix +
                               ".elastic = true); remove it");
    return rod;
  }
  rod.order = r.number(prefix + ".order");
  rod.tau_x = r.number(prefix + ".tau_x");
  rod.tau_f = r.number(prefix + ".tau_f");
  // SI relaxation times [s^order] -> dimensionless: tau T0^{-order} (one time scale for both rods).
  if (time_scale != 1.0 && rod.order > 0.0 && rod.order < 1.0) {
    const double factor = std::pow(time_scale, -rod.order);
    rod.tau_x *= factor;
    rod.tau_f *= factor;
  }
  return rod;
}

// [model.contact] (SPEC §6): the law at the blocks' gap model.gap0, by the rules of
// structure/contact_rules.hpp, absent: model "none". A dimensionless scene gives the stiffness in units
// of k1 (linear) or k1 / X0^(1/2) (Hertz-type laws); an SI scene in N/m or N/m^1.5, scaled
// here to those units (divided by k1 = F0 / X0, or by F0 / X0^(3/2)).
structure::ContactLaw read_contact(const SceneReader& r, const Scales& scales) {
  structure::ContactModel model = structure::ContactModel::none;
  if (r.has("model.contact.model")) {
    const std::string word = r.string("model.contact.model", "");
    if (!parse_enum(word, &model))
      r.fail("model.contact.model", "model.contact.model = " + escaped_excerpt(word) + " must be one of \"none\", \"linear\", \"hertz\", "
                                    "\"hertzdamp\", \"jankowski\" or \"impact\"");
  }
  const auto linear = [](structure::ContactModel m) { return m == structure::ContactModel::linear; };
  structure::ContactTable t;
  t.where = "model.contact";
  t.has = [&](const std::string& key) { return r.has("model.contact." + key); };
  t.number = [&](const std::string& key) { return r.number("model.contact." + key); };
  t.boolean = [&](const std::string& key) { return r.boolean("model.contact." + key, false); };
  t.fail = [&](const std::string& key, const std::string& message) {
    const std::string path = key.empty() ? "model.contact" : "model.contact." + key;
    r.fail(path, path + ": " + message);
  };
  t.stiffness_unit = [&](structure::ContactModel m) -> std::string {
    if (scales.si) return linear(m) ? "N/m" : "N/m^1.5";
    return linear(m) ? "in units of k1" : "in units of k1 / X0^(1/2)";
  };
  structure::ContactLaw law = structure::contact_law_from(t, model);
  if (scales.si && law.compliant()) {
    const double unit = linear(model) ? scales.force / scales.length : scales.force / std::pow(scales.length, 1.5);
    law.stiffness /= unit;
    if (!(std::isfinite(law.stiffness) && law.stiffness > 0.0))
      r.fail("model.contact.stiffness", "model.contact.stiffness = " + format_number(r.number("model.contact.stiffness")) +
                                            " is out of range: divided by the scene's unit " + format_number(unit) +
                                            " it is not a finite positive number");
  }
  return law;
}

// A run that cannot fit in memory is refused before it starts (it would otherwise fail after
// minutes, or push the machine into swap): the solver's history plus the accelerations kept
// for in-run spectra, against 80 % of the machine's memory.
void check_memory(const SceneReader& r, const Scene& scene) {
  const double steps = static_cast<double>(scene.solver.steps());
  // (A building's base has no model: its memory is checked with its structure, study/run.hpp.)
  double need = scene.two_block() ? estimated_history_bytes(two_block_options(scene), scene.structure) : 4096.0;
  if (scene.output.spectra) need += 3.0 * 8.0 * (steps + 1.0);
  const std::string problem = memory_problem(
      need, "the " + to_string(scene.solver.history) + " history" +
                (scene.output.spectra ? " and the accelerations kept for output.spectra" : ""));
  if (problem.empty()) return;
  std::ostringstream s;
  s.precision(3);
  s << "solver.t_end / solver.h = " << steps << " steps " << problem << "; raise solver.h or shorten solver.t_end";
  r.fail(r.has("solver.h") ? "solver.h" : "solver", s.str());
}

// solver.h or solver.tolerance (or neither: tolerance 1e-6), solver.t_end (or the rule below),
// solver.error_estimate. Every default is stated in scene.accuracy's rules so that the summary
// and the terminal can say what was chosen.
void read_step_and_horizon(const SceneReader& r, Scene& scene) {
  StructureSolverOptions& o = scene.solver;
  AccuracyOptions& a = scene.accuracy;
  const double T = scene.scales.time;
  const std::string unit = scene.scales.si ? " s" : "";
  a.error_estimate = r.boolean("solver.error_estimate", true);
  if (r.has("solver.t_end")) {
    o.t_end = r.number("solver.t_end") / T;
  } else if (!std::isfinite(scene.ground->duration())) {
    o.t_end = 16.0;  // the paper's horizon for its decaying sine (dimensionless)
    a.t_end_rule = "16 (dimensionless), the paper's horizon for the decaying sine";
  } else {
    // The motion, then free vibration: five periods of the slowest mode of the blocks on
    // their relaxed rods (block 1 alone, block 2 alone, or both stuck together), for the
    // response to decay through the rods' and the damper's dissipation.
    // (A building's base has no model: its reader says its own rule, io/building_scene.cpp.)
    double omega2 = 1.0;
    if (scene.two_block()) {
      const Model m = two_block_model(scene);
      omega2 = std::min({1.0, m.rho * m.eps, m.rho * (1.0 + m.eps) / (1.0 + m.rho)});
    }
    const double period = 2.0 * std::numbers::pi / std::sqrt(omega2);
    o.t_end = scene.ground->duration() + 5.0 * period;
    char rule[160];
    std::snprintf(rule, sizeof rule, "the ground motion's %.4g%s + 5 x the slowest natural period %.4g%s",
                  scene.ground->duration() * T, unit.c_str(), period * T, unit.c_str());
    a.t_end_rule = rule;
  }
  if (r.has("solver.h") && r.has("solver.tolerance"))
    r.fail("solver.tolerance", "give solver.h or solver.tolerance, not both (the tolerance chooses the step)");
  if (r.has("solver.h")) {
    o.h = r.number("solver.h") / T;
    return;
  }
  const double tolerance = r.number("solver.tolerance", 1e-6);
  if (!(tolerance >= 1e-12 && tolerance <= 0.1))
    r.fail("solver.tolerance", "solver.tolerance = " + format_number(tolerance) +
                                   " must lie in [1e-12, 0.1] (relative error of the reported peaks)");
  a.tolerance = tolerance;
  a.tolerance_given = r.has("solver.tolerance");
  a.h_rule = "chosen for solver.tolerance = " + format_number(tolerance) + (r.has("solver.tolerance") ? "" : " (the default)");
  // A first guess for the checks below; run_to_tolerance picks the step.
  o.h = o.t_end / 4000.0;
  if (const double dt = scene.ground->sample_interval(); dt > 0.0) o.h = std::min(o.h, dt);
}

void add_warnings(const SceneReader& r, Scene& scene) {
  const double T = scene.scales.time;
  const std::string unit = scene.scales.si ? " s" : "";
  const auto number = [](double v) { return format_number(v); };
  const double dt = scene.ground->sample_interval();
  if (dt > 0.0 && scene.solver.h > dt * (1.0 + 1e-9))
    scene.warnings.push_back(r.where("solver.h") + "solver.h = " + number(scene.solver.h * T) + unit +
                             " is coarser than the record's sampling interval " + number(dt * T) + unit +
                             ": the solver steps over record samples and can miss its peaks; use solver.h <= " +
                             number(dt * T));
  const double duration = scene.ground->duration();
  if (std::isfinite(duration) && scene.solver.t_end < duration * (1.0 - 1e-9))
    scene.warnings.push_back(r.where("solver.t_end") + "solver.t_end = " + number(scene.solver.t_end * T) + unit +
                             " ends before the ground motion does (" + number(duration * T) + unit +
                             "): the rest of the motion is not applied");
  if (r.overridden("ground.file") && !r.overridden("ground.scale_pga") && r.has("ground.scale_pga"))
  {
    std::string at = r.where("ground.scale_pga");
    at = at.substr(0, at.size() - 2);  // "FILE:LINE"
    scene.warnings.push_back(r.where("ground.file") + "the scene scales its record to ground.scale_pga = " +
                             number(r.number("ground.scale_pga")) + " g (" + at +
                             "), so the new record is scaled to that PGA too; add --unset ground.scale_pga to keep its own amplitude");
  }
}

// [model], in the scene's units: the two blocks, their rods and contact law, and the scales.
void read_model(const SceneReader& r, Scene& scene) {
  const std::string units = r.string("model.units", "dimensionless");
  const std::vector<std::string> dimensionless_only = {"model.rho", "model.eps", "model.mu"};
  const std::vector<std::string> si_only = {"model.m1", "model.m2", "model.k1", "model.k2",
                                            "model.slip_force"};
  Model m;
  if (units == "dimensionless") {
    for (const auto& k : si_only)
      if (r.has(k)) r.fail(k, k + " belongs to SI scenes; this scene has model.units = \"dimensionless\" (use model.rho, model.eps, model.mu)");
    scene.scales = Scales::Dimensionless();
    m.rho = r.number("model.rho");
    m.eps = r.number("model.eps");
    m.mu = r.number("model.mu");
    m.gap0 = r.number("model.gap0");
  } else if (units == "SI") {
    for (const auto& k : dimensionless_only)
      if (r.has(k)) r.fail(k, k + " belongs to dimensionless scenes; an SI scene gives model.m1, m2, k1, k2 and slip_force");
    const double m1 = r.number("model.m1"), m2 = r.number("model.m2");
    const double k1 = r.number("model.k1"), k2 = r.number("model.k2");
    const double slip = r.number("model.slip_force");
    for (auto [key, value] : {std::pair{"model.m1", m1}, {"model.m2", m2}, {"model.k1", k1}, {"model.k2", k2}})
      if (!(std::isfinite(value) && value > 0.0))
        r.fail(key, std::string(key) + " = " + format_number(value) + " must be positive");
    // SI values are scaled by T0 = sqrt(m1/k1), X0 = m1 g/k1 and m1 g X0 (energies): inside
    // these ranges every scale and every reported SI number stays finite.
    const auto in_range = [&](const char* key, double value, double lo, double hi, const char* unit) {
      if (!(value >= lo && value <= hi))
        r.fail(key, std::string(key) + " = " + format_number(value) + " must lie in [" + format_number(lo) + ", " +
                        format_number(hi) + "] " + unit);
    };
    in_range("model.m1", m1, 1e-3, 1e12, "kg");
    in_range("model.m2", m2, 1e-3, 1e12, "kg");
    in_range("model.k1", k1, 1e-3, 1e15, "N/m");
    in_range("model.k2", k2, 1e-3, 1e15, "N/m");
    if (!(std::isfinite(slip) && slip >= 0.0))
      r.fail("model.slip_force", "model.slip_force = " + format_number(slip) + " must be zero or positive [N]");
    if (!(m1 / m2 >= 1.0 / kMaxRatio && m1 / m2 <= kMaxRatio))
      r.fail("model.m2", "model.m1 / model.m2 = " + format_number(m1 / m2) + " must lie in [" +
                             format_number(1.0 / kMaxRatio) + ", " + format_number(kMaxRatio) + "]");
    if (!(k2 / k1 >= 1.0 / kMaxRatio && k2 / k1 <= kMaxRatio))
      r.fail("model.k2", "model.k2 / model.k1 = " + format_number(k2 / k1) + " must lie in [" +
                             format_number(1.0 / kMaxRatio) + ", " + format_number(kMaxRatio) + "]");
    if (!(slip <= kMaxRatio * m1 * kStandardGravity))
      r.fail("model.slip_force", "model.slip_force = " + format_number(slip) + " N must be at most " +
                                     format_number(kMaxRatio) + " m1 g = " + format_number(kMaxRatio * m1 * kStandardGravity) + " N");
    scene.scales = Scales::SI(m1, k1);
    m.rho = m1 / m2;
    m.eps = k2 / k1;
    m.mu = slip / (m1 * kStandardGravity);
    m.gap0 = r.number("model.gap0") / scene.scales.length;
    if (!(std::abs(m.gap0) <= kMaxRatio))
      r.fail("model.gap0", "model.gap0 = " + format_number(r.number("model.gap0")) + " m must lie within +-" +
                               format_number(kMaxRatio * scene.scales.length) + " m (1e6 X0, X0 = m1 g / k1)");
  } else {
    r.fail("model.units", "model.units = " + escaped_excerpt(units) + " must be \"dimensionless\" or \"SI\"");
  }
  // mu_b, a friction coefficient in either unit system (SPEC §7).
  m.base_friction = r.number("model.base_friction", 0.0);
  if (!(m.base_friction >= 0.0 && m.base_friction <= 1.0))
    r.fail("model.base_friction", "model.base_friction = " + format_number(m.base_friction) +
                                      " must lie in [0, 1] (the blocks' friction coefficient on their bases; 0: none)");
  for (const char* rod : {"model.rod1", "model.rod2"})
    if (!r.has(rod)) r.fail(rod, std::string("missing section [") + rod + "]");
  m.rod1 = read_rod(r, "model.rod1", scene.scales.time);
  m.rod2 = read_rod(r, "model.rod2", scene.scales.time);
  m.contact = read_contact(r, scene.scales);
  if (m.contact.model != structure::ContactModel::none && !(m.gap0 >= 0.0))
    r.fail("model.gap0", "model.gap0 = " + format_number(r.number("model.gap0")) +
                             " is negative: with a contact law (model.contact.model = \"" + to_string(m.contact.model) +
                             "\") the blocks may not start inside each other; expected a gap >= 0");
  std::string error, key;
  if (!m.IsValid(&error, &key)) {
    // Word SI relaxation times back in the user's units by re-checking the raw values.
    if (scene.scales.si && key.find(".tau_") != std::string::npos) {
      const std::string prefix = key.substr(0, key.rfind('.'));
      error = prefix + ".tau_x = " + format_number(r.number(prefix + ".tau_x")) +
              " must be greater than tau_f = " + format_number(r.number(prefix + ".tau_f")) +
              " (second law)";
      if (!(r.number(prefix + ".tau_f") > 0.0))
        error = prefix + ".tau_f = " + format_number(r.number(prefix + ".tau_f")) + " must be positive (second law)";
    }
    r.fail(key, error);
  }
  scene.structure = structure::two_block_structure(m);
  scene.two_block_scene = true;
}

// [solver]: the scheme, the history engine, the step and the horizon.
void read_solver(const SceneReader& r, Scene& scene) {
  const structure::ContactModel contact = scene.two_block() ? scene.structure.contacts[0].law.model : structure::ContactModel::none;
  std::string error, key;
  StructureSolverOptions& o = scene.solver;
  const std::string scheme = r.string("solver.scheme", to_string(o.scheme));
  if (!parse_enum(scheme, &o.scheme))
    r.fail("solver.scheme", "solver.scheme = " + escaped_excerpt(scheme) + " is not a scheme; expected one of " + scheme_names());
  const std::string history = r.string("solver.history", to_string(o.history));
  if (!parse_enum(history, &o.history))
    r.fail("solver.history", "solver.history = " + escaped_excerpt(history) + " must be \"direct\", \"fft\" or \"soe\"");
  o.history_tolerance = r.number("solver.history_tolerance", o.history_tolerance);
  o.locate_switches = r.boolean("solver.locate_switches", o.locate_switches);
  read_step_and_horizon(r, scene);
  if (!two_block_options(scene).IsValid(&error, &key)) r.fail(key, error);
  if (contact != structure::ContactModel::none && o.scheme == Scheme::paper)
    r.fail("solver.scheme", "solver.scheme = " + escaped_excerpt(scheme) + ": the contact laws need the implicit scheme (model.contact.model = \"" +
                                to_string(contact) + "\"); remove solver.scheme (the default is \"implicit\") or choose an implicit one");
  if (scene.two_block() && scene.structure.a.ground_friction > 0.0 && o.scheme == Scheme::paper)
    r.fail("solver.scheme", "solver.scheme = " + escaped_excerpt(scheme) + ": the base friction (model.base_friction) runs on the implicit schemes only; "
                            "remove solver.scheme (the default is \"implicit\") or choose an implicit one");

}

// [output]: what the run computes and writes.
void read_output(const SceneReader& r, Scene& scene) {
  OutputOptions& out = scene.output;
  out.peaks = r.boolean("output.peaks", true);
  out.phases = r.boolean("output.phases", true);
  out.pounding = r.boolean("output.pounding", true);
  out.energy = r.boolean("output.energy", true);
  out.energy_history = r.boolean("output.energy_history", false);
  if (r.has("output.spectra")) {
    SpectraOutput spectra;
    // A two-block scene names its blocks' accelerations "block1" and "block2" (SPEC §3); the run
    // names them by the 1 + 1 structure's floors (A.a1_abs, B.a1_abs: the default), and its
    // files name them back (io/two_block_names.hpp). (A building scene's signals are checked
    // against its structure: io/building_scene.cpp.)
    if (r.has("output.spectra.signals")) {
      spectra.signals = r.strings("output.spectra.signals");
      for (auto signal = spectra.signals.begin(); signal != spectra.signals.end(); ++signal) {
        if (*signal != "ground" && *signal != "block1" && *signal != "block2")
          r.fail("output.spectra.signals", "output.spectra.signals: " + escaped_excerpt(*signal) + " must be \"ground\", \"block1\" or \"block2\"");
        if (std::find(spectra.signals.begin(), signal, *signal) != signal)
          r.fail("output.spectra.signals", "output.spectra.signals: " + escaped_excerpt(*signal) + " is listed twice; list each signal once");
      }
      for (std::string& signal : spectra.signals) signal = two_block_signal_channel(signal);
    }
    if (r.has("output.spectra.damping")) spectra.damping = r.numbers("output.spectra.damping");
    for (double d : spectra.damping)
      if (!(d >= 0.0 && d < 1.0))
        r.fail("output.spectra.damping", "output.spectra.damping: " + format_number(d) + " must be a damping ratio in [0, 1)");
    spectra.periods = r.numbers("output.spectra.periods");
    // A period or damping listed twice would be computed and written twice.
    for (const char* key : {"output.spectra.periods", "output.spectra.damping"}) {
      const std::vector<double> list = r.numbers(key);
      for (auto v = list.begin(); v != list.end(); ++v)
        if (std::find(list.begin(), v, *v) != v)
          r.fail(key, std::string(key) + ": " + format_number(*v) + " is listed twice; list each value once");
    }
    // Periods far outside the range of structures (in the scene's time unit) only lose
    // digits: 1e-200 once gave NaN spectra.
    for (double t : spectra.periods)
      if (!(t == 0.0 || (t >= 1e-4 && t <= 1e4)))
        r.fail("output.spectra.periods", "output.spectra.periods: " + format_number(t) +
                                             " must be 0 (the peak acceleration) or lie in [0.0001, 10000]");
    out.spectra = spectra;
  }
  scene.output.timeseries = r.boolean("output.timeseries", false);
  const std::int64_t every = r.integer("output.every", 0);  // 0: not given, the run's rule
  if (r.has("output.every") && every < 1) r.fail("output.every", "output.every = " + std::to_string(every) + " must be 1 or more");
  scene.output.every = static_cast<std::size_t>(every);
}

// The scene's name (out/<name>/), or its file's stem.
void read_name(const SceneReader& r, const std::string& file_name, Scene& scene) {
  scene.name = r.string("name", "");
  // The name picks the output folder (out/<name>/): a path there would write outside out/.
  if (r.has("name"))
    if (const std::string problem = plain_name_problem(scene.name); !problem.empty())
      r.fail("name", "name = " + escaped_excerpt(scene.name) + " " + problem +
                         "; expected a plain file name (it names the output folder out/<name>/)");
  if (scene.name.empty()) {
    scene.name = std::filesystem::path(file_name).stem().string();
    if (!plain_name_problem(scene.name).empty()) scene.name = "scene";  // "", or a file called "..toml"
  }
}

// What every scene has beside its structure, in its scales: the ground motion (from its
// source's plug-in, ground_sources/), the solver and the output, with the run's memory checked
// and its warnings gathered.
void read_run(const SceneReader& r, Scene& scene) {
  scene.ground = detail::read_ground(r, scene.scales);
  read_solver(r, scene);
  read_output(r, scene);
  check_memory(r, scene);
  add_warnings(r, scene);
}

// A building scene's [ground], [solver] and [output] (its structure is read by
// io/structure_file.cpp): in SI scales of 1 kg and 1 N/m, so that times are in seconds and the
// ground's a_g is in g. It has no two-block model.
Scene build_building_base(const SceneReader& r, const std::string& name) {
  Scene scene;
  read_name(r, name, scene);
  if (!r.has("ground")) r.fail("ground", "missing section [ground]");
  scene.scales = Scales::SI(1.0, 1.0);
  read_run(r, scene);
  return scene;
}

Scene build_scene(const SceneReader& r, const std::string& name) {
  Scene scene;
  read_name(r, name, scene);
  for (const auto& table : {"model", "ground"})
    if (!r.has(table)) r.fail(table, std::string("missing section [") + table + "]");

  read_model(r, scene);
  read_run(r, scene);
  return scene;
}

}  // namespace

const std::vector<std::string>& known_scene_keys() {
  static const std::vector<std::string> keys = all_known_keys();
  return keys;
}

Scene parse_scene(const std::string& text, const std::string& name, const std::vector<std::string>& overrides,
                  const std::vector<std::string>& removed) {
  std::vector<detail::SceneEdit> edits;
  for (const auto& o : overrides) edits.push_back({o});
  return detail::scene_from_tree(detail::parse_toml_text(text, name), name, edits, removed);
}

Scene detail::scene_from_tree(toml::table table, const std::string& name, const std::vector<SceneEdit>& edits,
                              const std::vector<std::string>& removed, const toml::table* lines) {
  if (const toml::node* building = table.get("building")) {
    // A building scene (SPEC §5): io/building_scene.hpp reads it (its structure, and its
    // ground, solver and output sections through parse_building_base below).
    throw InputError(name + ":" + std::to_string(building->source().begin.line) +
                     ": a building scene ([building.A] ...): read it with load_building_scene "
                     "(adjoin run, adjoin modes do)");
  }
  for (const auto& key : removed) remove_key(table, key);
  std::map<std::string, std::string> origins;
  for (const auto& e : edits) apply_override(table, e.text, origins, e.typed);
  SceneReader reader(std::move(table), name, std::move(origins), lines);
  check_keys(reader, reader.table(), "");
  return build_scene(reader, name);
}

Scene parse_building_base(const std::string& text, const std::string& name, const std::vector<std::string>& overrides,
                          const std::vector<std::string>& unsets) {
  return detail::building_base_from_tree(detail::parse_toml_text(text, name), name, overrides, unsets);
}

Scene detail::building_base_from_tree(toml::table table, const std::string& name, const std::vector<std::string>& overrides,
                                      const std::vector<std::string>& unsets, const toml::table* lines) {
  for (const auto& key : unsets)
    if (!remove_key(table, key))
      throw InputError("--unset " + text_excerpt(key) + ": the scene has no key or section " + text_excerpt(key), field_path(key));
  // The structure is read elsewhere; what stays is [ground], [solver], [output] and the name.
  for (const char* key : {"building", "link", "contact", "model"}) table.erase(key);
  std::map<std::string, std::string> origins;
  for (const auto& o : overrides) apply_override(table, o, origins);
  // In-structure spectra name the floors' channels (A.a3_abs), which only the structure can
  // check (io/building_scene.cpp does): they are set aside here, "ground" read in their place.
  std::optional<std::vector<std::string>> signals;
  if (toml::array* list = table.at_path("output.spectra.signals").as_array()) {
    signals.emplace();
    // A list no --set wrote is the file's: a copy's items find their lines in `lines`.
    const toml::array* parsed = lines && !origins.count("output.spectra.signals")
                                    ? lines->at_path("output.spectra.signals").as_array() : nullptr;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::node& item = *list->get(i);
      const toml::node* line = parsed && parsed->get(i) ? parsed->get(i) : &item;
      const auto signal = item.value_exact<std::string>();
      if (!signal) throw InputError(name + ":" + std::to_string(line->source().begin.line) + ": output.spectra.signals: expected a list of names (\"ground\", \"A.a3_abs\")");
      signals->push_back(*signal);
    }
    *list = toml::array{"ground"};
  }
  SceneReader reader(std::move(table), name, std::move(origins), lines);
  check_keys(reader, reader.table(), "");
  Scene scene = build_building_base(reader, name);
  if (signals && scene.output.spectra) scene.output.spectra->signals = *signals;
  return scene;
}

std::vector<std::string> implied_unsets(const std::string& key, const std::string& value,
                                        const std::string& current_source) {
  std::vector<std::string> out;
  const auto unquoted = [](std::string v) {
    if (v.size() >= 2 && (v.front() == '"' || v.front() == '\'') && v.back() == v.front()) v = v.substr(1, v.size() - 2);
    return v;
  };
  for (const char* rod : {"model.rod1", "model.rod2"})
    if (key == std::string(rod) + ".elastic" && value == "true")
      for (const char* k : {".order", ".tau_x", ".tau_f"}) out.push_back(std::string(rod) + k);
  if (key == "ground.source" && unquoted(value) != current_source) out.push_back("ground");
  // A contact law's restitution and damping replace each other; a model drops the keys it
  // does not take (structure/contact_rules.hpp), as editing the file would.
  if (key == "model.contact.restitution") out.push_back("model.contact.damping");
  if (key == "model.contact.damping") out.push_back("model.contact.restitution");
  structure::ContactModel model;
  if (key == "model.contact.model" && parse_enum(unquoted(value), &model))
    for (const auto& k : structure::contact_keys_refused(model)) out.push_back("model.contact." + k);
  return out;
}

Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                 const std::vector<std::string>& unsets) {
  // A building scene (SPEC §5) has its own reader: its structure, then the sections below.
  if (is_building_scene(file)) return load_building_scene(file, overrides, unsets);
  const std::string text = read_text_file(file, "scene");
  std::vector<std::string> removed;
  if (!unsets.empty() || !overrides.empty()) {
    toml::table table;
    try {
      table = toml::parse(text, file.string());
    } catch (const toml::parse_error&) {
      return parse_scene(text, file.string(), overrides);  // words the syntax error
    }
    for (const auto& key : unsets) {
      if (!table.at_path(key)) {
        std::vector<std::string> present;
        for (const auto& k : known_scene_keys())
          if (table.at_path(k)) present.push_back(k);
        throw InputError("--unset " + text_excerpt(key) + ": the scene has no key or section " + text_excerpt(key) +
                         (present.empty() ? std::string() : "; did you mean " + nearest(key.substr(0, 200), present) + "?"),
                         field_path(key));
      }
      removed.push_back(key);
    }
    const std::string source = table.at_path("ground.source").value_or(std::string());
    for (const auto& o : overrides) {
      const auto eq = o.find('=');
      if (eq == std::string::npos) continue;  // parse_scene words it
      for (auto& k : implied_unsets(trim(o.substr(0, eq)), trim(o.substr(eq + 1)), source))
        if (table.at_path(k)) removed.push_back(k);
    }
  }
  Scene scene = parse_scene(text, file.string(), overrides, removed);
  scene.file = file;
  return scene;
}

std::string detail::format_scene_number(double v) { return format_number(v); }

}  // namespace adjoin
