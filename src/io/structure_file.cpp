#include "adjoin/io/structure_file.hpp"

#include "adjoin/structure/two_block.hpp"

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <toml++/toml.h>

#include "adjoin/structure/contact_rules.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "element_keys.hpp"
#include "structure_edits.hpp"
#include "sweep_scene_tree.hpp"
#include "toml_text.hpp"

#include "adjoin/core/errors.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/structure/rules.hpp"
#include "adjoin/structure/parameters.hpp"
#include "adjoin/core/units.hpp"

namespace adjoin {
namespace {

using structure::Building;
using structure::DampingModel;
using structure::DeviceType;
using structure::LinkType;
using detail::device_keys;
using detail::link_keys;

using Origins = std::map<std::string, std::string>;

using structure::bounded_problem;
using structure::kAlphaRange;
using structure::kDashpotRange;
using structure::kForceRange;
using structure::kMassRange;
using structure::kSlipRatioRange;
using structure::kStiffnessRange;
using structure::Range;

// Reads the keys of one table, each named by its dotted path in messages with the line.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, std::string file, const Origins* origins = nullptr,
              const detail::CopiedFrom* copied = nullptr)
      : table_(table), path_(std::move(path)), file_(std::move(file)), origins_(origins), copied_(copied) {}
  // A reader of a table inside this one (same file, same edits).
  TableReader inner(const toml::table& table, const std::string& path) const {
    return {table, path, file_, origins_, copied_};
  }

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    const toml::node* node = key.empty() ? nullptr : table_.get(key);
    const auto& source = source_of(node ? *node : table_);
    std::ostringstream m;
    // A value a --set put there is blamed on the --set; the others on their file line.
    // (A --set of a key the file has keeps the file's node, and with it the file's line.)
    const std::string full = key.empty() ? path_ : path_ + "." + key;
    if (origins_ && origins_->count(full)) {
      m << origins_->at(full) << ": " << text_excerpt(full) << ": " << message;
      throw InputError(m.str(), full);
    }
    // A table a --set added (link.2.floors on a scene with one link) has no file line: blame
    // the --set that made it.
    if (origins_ && source.begin.line == 0)
      if (const auto made = origins_->lower_bound(path_ + "."); made != origins_->end() && made->first.rfind(path_ + ".", 0) == 0) {
        m << made->second << ": " << text_excerpt(full) << ": " << message << " (" << path_ << " is a table --set added)";
        throw InputError(m.str(), full);
      }
    m << file_;
    if (source.begin.line > 0) m << ":" << source.begin.line;
    m << ": " << text_excerpt(full) << ": " << message;
    throw InputError(m.str(), full);
  }
  // A key the table must have and has not: the table's line, the key's field.
  [[noreturn]] void missing(const std::string& key) const {
    try {
      // A type an edit set names the key its type needs (a friction link made a dashpot needs c).
      const std::string type = path_ + ".type";
      fail("", "missing key " + key +
                   (origins_ && origins_->count(type) ? " (the type " + origins_->at(type) + " gave it needs it)" : ""));
    } catch (const InputError& e) {
      throw InputError(e.what(), path_ + "." + key);
    }
  }
  bool has(const std::string& key) const { return table_.contains(key); }
  void only(const std::set<std::string>& known) const {
    for (const auto& [k, v] : table_) {
      const std::string key(k.str());
      if (known.count(key)) continue;
      std::string list;
      for (const auto& name : known) list += (list.empty() ? "" : ", ") + name;
      fail(key, "unknown key; expected one of " + list);
    }
  }
  // Refuses a key of the table's schema that does not apply here (`why`: what it is here).
  void only_with(const std::set<std::string>& applies, const std::string& why) const {
    for (const auto& [k, v] : table_)
      if (!applies.count(std::string(k.str()))) fail(std::string(k.str()), "does not apply to " + why + "; remove it");
  }
  double number(const std::string& key) const {
    const toml::node* n = table_.get(key);
    if (!n) missing(key);
    const auto v = n->value<double>();
    if (!v || !std::isfinite(*v)) fail(key, "expected a finite number");
    return *v;
  }
  double number(const std::string& key, double fallback) const { return has(key) ? number(key) : fallback; }
  double positive(const std::string& key) const {
    const double v = number(key);
    if (!(v > 0.0)) fail(key, "expected a positive number");
    return v;
  }
  // A positive value within `range` (structure/rules.hpp).
  double bounded(const std::string& key, const Range& range) const {
    const double v = number(key);
    if (const std::string problem = bounded_problem(v, range); !problem.empty()) fail(key, problem);
    return v;
  }
  int integer(const std::string& key, int lo, int hi) const {
    const toml::node* n = table_.get(key);
    if (!n) missing(key);
    const auto v = n->value_exact<std::int64_t>();
    if (!v || *v < lo || *v > hi) fail(key, "expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return static_cast<int>(*v);
  }
  std::string text(const std::string& key, const std::set<std::string>& allowed) const {
    const toml::node* n = table_.get(key);
    if (!n) missing(key);
    const auto v = n->value_exact<std::string>();
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
    if (!v || !allowed.count(*v)) fail(key, "expected one of " + list);
    return *v;
  }
  // One of E's names (core/enum_names.hpp), as text() checks it.
  template <NamedEnum E>
  E choice(const std::string& key) const {
    const std::vector<std::string> list = names<E>();
    E value{};
    parse_enum(text(key, {list.begin(), list.end()}), &value);
    return value;
  }
  std::vector<double> numbers(const std::string& key, std::size_t size) const {
    const toml::array* a = table_.get_as<toml::array>(key);
    if (!a) fail(key, "expected a list of numbers");
    if (size && a->size() != size) fail(key, "expected " + std::to_string(size) + " values, one per storey (bottom up)");
    std::vector<double> out;
    for (const auto& e : *a) {
      const auto v = e.value<double>();
      if (!v || !std::isfinite(*v)) fail(key, "expected a list of finite numbers");
      out.push_back(*v);
    }
    return out;
  }
  std::vector<int> integers(const std::string& key, std::size_t size) const {
    const toml::array* a = table_.get_as<toml::array>(key);
    if (!a || (size && a->size() != size)) fail(key, size ? "expected " + std::to_string(size) + " whole numbers" : "expected a list of whole numbers");
    std::vector<int> out;
    for (const auto& e : *a) {
      const auto v = e.value_exact<std::int64_t>();
      if (!v || *v < 1 || *v > 100000) fail(key, "expected whole numbers from 1");
      out.push_back(static_cast<int>(*v));
    }
    return out;
  }
  // A device's storeys: whole numbers, by the rules of structure/rules.hpp.
  std::vector<int> storeys(const std::string& key, int n) const {
    std::vector<int> out = integers(key, 0);
    if (const std::string problem = structure::device_storeys_problem(out, n); !problem.empty()) fail(key, problem);
    return out;
  }
  const toml::table& table() const { return table_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }

 private:
  // Where `node` was written: its own source, or in a copy of the parsed tree the source of the
  // node it was copied from.
  const toml::source_region& source_of(const toml::node& node) const {
    if (copied_)
      if (const auto it = copied_->find(&node); it != copied_->end()) return it->second->source();
    return node.source();
  }

  const toml::table& table_;
  std::string path_, file_;
  const Origins* origins_ = nullptr;
  const detail::CopiedFrom* copied_ = nullptr;
};

// A uniform storey stiffness for `period` (s), within the rules' stiffness range.
double stiffness_for_period(const TableReader& r, const Eigen::VectorXd& masses) {
  std::string problem;
  const double k = structure::stiffness_for_period_in_range(masses, r.positive("period"), &problem);
  if (!problem.empty()) r.fail("period", problem);
  return k;
}

// Storey heights, P-Delta and the collapse drift ratio (SPEC §7).
void read_heights(const TableReader& r, Building* b) {
  const int n = b->floors();
  if (r.has("height") && r.has("heights")) r.fail("", "give the storey heights as height (every storey) or heights (a list), one of them");
  if (r.has("height")) b->heights = Eigen::VectorXd::Constant(n, r.bounded("height", structure::kHeightRange));
  if (r.has("heights")) {
    const auto h = r.numbers("heights", n);
    for (int i = 0; i < n; ++i)
      if (const std::string problem = structure::bounded_problem(h[i], structure::kHeightRange); !problem.empty())
        r.fail("heights", "storey " + std::to_string(i + 1) + ": " + problem + " (a height in m)");
    b->heights = Eigen::Map<const Eigen::VectorXd>(h.data(), n);
  }
  if (r.has("p_delta")) {
    const auto v = r.table().get("p_delta")->value_exact<bool>();
    if (!v) r.fail("p_delta", "expected true or false");
    b->p_delta = *v;
  }
  if (r.has("collapse_drift_ratio")) b->collapse_drift_ratio = r.bounded("collapse_drift_ratio", structure::kDriftRatioRange);
  std::string key;
  if (const std::string problem = structure::heights_problem(*b, r.has("collapse_drift_ratio"), &key); !problem.empty())
    r.fail(key, problem);
}

// A link's keys, by its kind (structure/link_kinds.hpp), as a device's (below).
void read_link_keys(const TableReader& r, structure::Link* link) {
  const structure::LinkKind& kind = structure::kind_of(*link);
  for (const structure::LinkKey& key : kind.keys) {
    const double v = key.required ? r.number(key.name) : r.number(key.name, key.fallback);
    if (const std::string problem = key.problem(v); !problem.empty()) r.fail(key.name, problem);
    key.field(*link) = v;
  }
  if (const std::string problem = kind.joint_problem(*link); !problem.empty()) {
    const char* blamed = kind.joint_keys.back();
    for (const char* key : kind.joint_keys)
      if (r.has(key)) {
        blamed = key;
        break;
      }
    r.fail(blamed, problem);
  }
}

// A device's keys, by its kind (structure/device_kinds.hpp): only the kind's keys; each key's
// value (or its default) and its check, in the kind's order; then the rule between keys.
void read_device_keys(const TableReader& r, structure::StoreyDevice* dev) {
  const structure::DeviceKind& kind = structure::kind_of(*dev);
  r.only(device_keys(dev->type));
  for (const structure::DeviceKey& key : kind.keys) {
    const double v = key.required ? r.number(key.name) : r.number(key.name, key.fallback);
    if (const std::string problem = key.problem(v); !problem.empty()) r.fail(key.name, problem);
    key.field(*dev) = v;
  }
  if (const std::string problem = kind.joint_problem(*dev); !problem.empty())
    r.fail(structure::joint_key(kind, [&](const char* key) { return r.has(key); }), problem);
}

// A bilinear law's post-yield stiffness ratio b, in [0, 1) (default 0: elastic-perfectly-plastic).
double read_hardening(const TableReader& r) {
  const double b = r.number("hardening", 0.0);
  if (const std::string problem = structure::hardening_problem(b); !problem.empty()) r.fail("hardening", problem);
  return b;
}

// A Bouc-Wen law's shape (SPEC §7): n (default 2) in [1, 20], beta and gamma (default 0.5 each)
// with beta + gamma > 0, into (n, beta, gamma).
void read_bouc_wen_shape(const TableReader& r, double* n, double* beta, double* gamma) {
  *n = r.number("n", 2.0);
  if (const std::string problem = structure::bouc_wen_exponent_problem(*n); !problem.empty()) r.fail("n", problem);
  *beta = r.number("beta", 0.5);
  *gamma = r.number("gamma", 0.5);
  if (const std::string problem = structure::bouc_wen_shape_problem(*beta, *gamma); !problem.empty())
    r.fail(r.has("gamma") ? "gamma" : "beta", problem);
}

// A building's storey law (SPEC §7): hysteresis = { model = "bilinear", yield_force = ...,
// hardening = 0.05 } (or yield_forces = [...] per storey, or yield_drift_ratio = 0.01: its
// forces need the springs and heights, so read_building turns it into forces last);
// model = "elastic" is the default.
structure::StoreyHysteresis read_hysteresis(const toml::table& building, const TableReader& r, int n) {
  const toml::table* h = building.get_as<toml::table>("hysteresis");
  if (!h) r.fail("hysteresis", "expected a table: { model = \"bilinear\", yield_force = 160.0e3, hardening = 0.05 }");
  const TableReader hr = r.inner(*h, r.path() + ".hysteresis");
  hr.only({"model", "yield_force", "yield_forces", "yield_drift_ratio", "hardening", "n", "beta", "gamma"});
  structure::StoreyHysteresis y;
  y.model = hr.choice<structure::HysteresisModel>("model");
  if (y.model == structure::HysteresisModel::elastic) {
    hr.only_with({"model"}, "the model \"elastic\" (no yielding)");
    return y;
  }
  if (y.model == structure::HysteresisModel::bouc_wen) read_bouc_wen_shape(hr, &y.n, &y.beta, &y.gamma);
  else hr.only_with({"model", "yield_force", "yield_forces", "yield_drift_ratio", "hardening"}, "the model \"bilinear\" (n, beta, gamma are Bouc-Wen's)");
  if (hr.has("yield_force") + hr.has("yield_forces") + hr.has("yield_drift_ratio") != 1)
    hr.fail("", "give the yield force as yield_force (every storey), yield_forces (a list) or yield_drift_ratio "
                "(F_y = k x ratio x h, needs heights), one of them");
  y.hardening = read_hardening(hr);
  if (hr.has("yield_drift_ratio")) {
    y.yield_drift_ratio = hr.bounded("yield_drift_ratio", structure::kDriftRatioRange);
    return y;
  }
  if (hr.has("yield_force")) {
    y.yield_forces = Eigen::VectorXd::Constant(n, hr.bounded("yield_force", kForceRange));
  } else {
    const auto f = hr.numbers("yield_forces", n);
    y.yield_forces = Eigen::Map<const Eigen::VectorXd>(f.data(), n);
    for (int i = 0; i < n; ++i)
      if (const std::string problem = bounded_problem(f[static_cast<std::size_t>(i)], kForceRange); !problem.empty())
        hr.fail("yield_forces", "storey " + std::to_string(i + 1) + ": " + problem);
  }
  return y;
}

// An isolated base (SPEC §7): [building.X.base] mass, model ("flat-slider" or
// "friction-pendulum"), friction (mu > 0, of the total weight), radius (friction-pendulum only).
structure::Base read_base(const toml::table& building, const TableReader& r) {
  const toml::table* t = building.get_as<toml::table>("base");
  if (!t) r.fail("base", "expected a table: [building.X.base] with mass, model, friction (and radius)");
  const TableReader br = r.inner(*t, r.path() + ".base");
  br.only({"mass", "model", "friction", "radius"});
  structure::Base base;
  base.mass = br.number("mass");
  if (const std::string problem = structure::base_mass_problem(base.mass); !problem.empty()) br.fail("mass", problem);
  base.model = br.choice<structure::BaseModel>("model");
  base.friction = br.number("friction");
  if (const std::string problem = structure::base_friction_problem(base.friction); !problem.empty()) br.fail("friction", problem);
  if (base.model == structure::BaseModel::friction_pendulum) {
    base.radius = br.number("radius");
    if (const std::string problem = structure::base_radius_problem(base.radius); !problem.empty()) br.fail("radius", problem);
  } else if (br.has("radius")) {
    br.fail("radius", "a flat slider has no radius; remove it, or use model = \"friction-pendulum\"");
  }
  return base;
}

// The yield forces of a law given by its yield drift ratio, from the building's final springs
// and heights; the problem (no heights, a storey without a spring) blamed on the key.
void resolve_yield_drift_ratio(const toml::table& building, const TableReader& r, Building* b) {
  const TableReader hr = r.inner(*building.get_as<toml::table>("hysteresis"), r.path() + ".hysteresis");
  if (const std::string problem = structure::yield_forces_from_drift_ratio(b, b->hysteresis.yield_drift_ratio); !problem.empty())
    hr.fail("yield_drift_ratio", problem);
}

Building read_building(const toml::table& root, const std::string& name, const TableReader& top) {
  const toml::table* t = root["building"][name].as_table();
  const TableReader r = top.inner(*t, "building." + name);
  r.only({"storeys", "mass", "masses", "stiffness", "stiffnesses", "period", "damping", "device", "height", "heights", "p_delta",
          "collapse_drift_ratio", "hysteresis", "base"});
  Building b;
  b.name = name;
  const int n = r.integer("storeys", 1, structure::kMaxStoreys);
  if (r.has("mass") == r.has("masses")) r.fail("", "give the floor masses as mass (every floor) or masses (a list), one of them");
  b.masses = r.has("mass") ? Eigen::VectorXd::Constant(n, r.bounded("mass", kMassRange)) : Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(r.numbers("masses", n).data(), n));
  for (int i = 0; i < n; ++i) {
    if (!(b.masses[i] > 0.0)) r.fail("masses", "floor " + std::to_string(i + 1) + ": expected a positive mass (kg)");
    if (const std::string problem = kMassRange.problem(b.masses[i]); !problem.empty())
      r.fail("masses", "floor " + std::to_string(i + 1) + ": " + problem);
  }
  const int given = r.has("stiffness") + r.has("stiffnesses") + r.has("period");
  if (given > 1) r.fail("", "give one of stiffness, stiffnesses or period");
  if (r.has("stiffness")) {
    b.springs = Eigen::VectorXd::Constant(n, r.bounded("stiffness", kStiffnessRange));
  } else if (r.has("stiffnesses")) {
    const auto k = r.numbers("stiffnesses", n);
    b.springs = Eigen::Map<const Eigen::VectorXd>(k.data(), n);
    for (int i = 0; i < n; ++i) {
      if (!(b.springs[i] >= 0.0)) r.fail("stiffnesses", "storey " + std::to_string(i + 1) + ": expected a non-negative stiffness (N/m)");
      // 0: a storey stiffened by its devices only.
      if (const std::string problem = kStiffnessRange.problem(b.springs[i]); b.springs[i] > 0.0 && !problem.empty())
        r.fail("stiffnesses", "storey " + std::to_string(i + 1) + ": " + problem + "; or 0 for a storey its devices stiffen");
    }
  } else if (r.has("period")) {
    b.springs = Eigen::VectorXd::Constant(n, stiffness_for_period(r, b.masses));
  } else {
    b.springs = Eigen::VectorXd::Zero(n);  // the storeys' devices give the stiffness (checked below)
  }
  if (r.has("damping")) {
    const toml::table* d = t->get_as<toml::table>("damping");
    if (!d) r.fail("damping", "expected a table: { model = \"modal\", ratio = 0.05 }");
    const TableReader dr = r.inner(*d, r.path() + ".damping");
    dr.only({"model", "ratio", "modes"});
    b.damping.model = dr.choice<DampingModel>("model");
    // The keys each model takes: one it ignores would be a setting silently lost.
    if (b.damping.model == DampingModel::none) dr.only_with({"model"}, "the model \"none\" (no inherent damping)");
    if (b.damping.model == DampingModel::modal)
      dr.only_with({"model", "ratio"}, "the model \"modal\" (one ratio for every mode; modes is Rayleigh's)");
    if (b.damping.model != DampingModel::none) {
      b.damping.ratio = dr.number("ratio");
      if (const std::string problem = structure::damping_ratio_problem(b.damping.ratio); !problem.empty()) dr.fail("ratio", problem);
    }
    if (b.damping.model == DampingModel::rayleigh) {
      const auto modes = dr.has("modes") ? dr.integers("modes", 2) : std::vector<int>{1, 2};
      b.damping.mode_i = modes[0];
      b.damping.mode_j = modes[1];
      if (const std::string problem = structure::rayleigh_modes_problem(modes[0], modes[1], n); !problem.empty())
        dr.fail(dr.has("modes") ? "modes" : "", problem);
    }
  }
  if (r.has("device")) {
    const toml::array* devices = t->get_as<toml::array>("device");
    if (!devices) r.fail("device", "expected [[building." + name + ".device]] tables");
    int index = 0;
    for (const auto& node : *devices) {
      ++index;
      const toml::table* dt = node.as_table();
      if (!dt) r.fail("device", "expected [[building." + name + ".device]] tables");
      const TableReader dr = r.inner(*dt, r.path() + ".device[" + std::to_string(index) + "]");
      structure::StoreyDevice dev;
      dev.type = dr.choice<DeviceType>("type");
      dev.storeys = dr.storeys("storeys", n);
      read_device_keys(dr, &dev);
      b.devices.push_back(dev);
    }
  }
  if (r.has("hysteresis")) b.hysteresis = read_hysteresis(*t, r, n);
  if (r.has("period") && !b.devices.empty()) {
    // The period is the building's with its devices (their relaxed stiffness).
    std::string problem;
    const double k = structure::spring_for_period_with_devices(b, r.positive("period"), b.springs[0], &problem);
    if (!problem.empty()) r.fail("period", problem);
    b.springs = Eigen::VectorXd::Constant(n, k);
  }
  if (const std::string problem = structure::storey_stiffness_problem(b); !problem.empty()) r.fail("", problem);
  read_heights(r, &b);
  if (r.has("base")) b.base = read_base(*t, r);
  if (b.hysteresis.yield_drift_ratio > 0.0) resolve_yield_drift_ratio(*t, r, &b);
  return b;
}

// A [[contact]]'s law (SPEC §6): model (default "none"), stiffness [N/m or N/m^1.5],
// restitution, damping, tension_cut, by the rules of structure/contact_rules.hpp.
structure::ContactLaw read_contact_law(const TableReader& r) {
  structure::ContactModel model = structure::ContactModel::none;
  if (r.has("model")) {
    const toml::node* n = r.table().get("model");
    const auto word = n->value_exact<std::string>();
    if (!word || !parse_enum(*word, &model))
      r.fail("model", "expected one of " + join_names(names<structure::ContactModel>(), "\"", ", ", ", "));
  }
  structure::ContactTable t;
  t.where = r.path();
  t.has = [&](const std::string& key) { return r.has(key); };
  t.number = [&](const std::string& key) { return r.number(key); };
  t.boolean = [&](const std::string& key) {
    const auto v = r.table().get(key)->value_exact<bool>();
    if (!v) r.fail(key, "expected true or false");
    return *v;
  };
  t.fail = [&](const std::string& key, const std::string& message) { r.fail(key, message); };
  t.stiffness_unit = [](structure::ContactModel m) { return m == structure::ContactModel::linear ? "N/m" : "N/m^1.5"; };
  const structure::ContactLaw law = structure::contact_law_from(t, model);
  if (const std::string problem = structure::contact_stiffness_problem(law.stiffness, t.stiffness_unit(model));
      r.has("stiffness") && !problem.empty())
    r.fail("stiffness", problem);
  return law;
}

}  // namespace

bool is_building_scene(const std::filesystem::path& file) {
  const std::string text = read_text_file(file, "scene");
  try {
    const toml::table root = toml::parse(text, file.string());
    return root.contains("building");
  } catch (const toml::parse_error&) {
    return false;  // the scene loader reports the syntax error with its line
  }
}

structure::Structure read_structure(const std::filesystem::path& path) {
  return parse_structure(read_text_file(path, "scene"), path.string());
}

structure::Structure parse_structure(const std::string& text, const std::string& file) {
  return parse_structure(text, file, {}, {});
}

bool is_structure_key(const std::string& key) { return detail::is_structure_key(key); }

structure::Structure parse_structure(const std::string& text, const std::string& file,
                                     const std::vector<std::string>& overrides, const std::vector<std::string>& unsets) {
  toml::table root = detail::parse_toml_text(text, file);
  return detail::structure_from_tree(root, file, overrides, unsets);
}

structure::Structure detail::structure_from_tree(toml::table& root, const std::string& file,
                                                 const std::vector<std::string>& overrides,
                                                 const std::vector<std::string>& unsets, const CopiedFrom* copied) {
  Origins origins;
  detail::edit_structure(root, overrides, unsets, origins);
  TableReader top(root, "scene", file, &origins, copied);
  const toml::table* model = root["model"].as_table();
  if (!model || root["model"]["units"].value<std::string>() != "SI")
    top.fail("", "a building scene is in SI units: add [model] with units = \"SI\"");
  top.inner(*model, "model").only({"units"});  // the buildings carry the rest
  const toml::table* buildings = root["building"].as_table();
  if (!buildings) top.fail("", "missing section [building.A]");
  const TableReader br = top.inner(*buildings, "building");
  br.only({"A", "B"});
  if (!buildings->get_as<toml::table>("A")) br.fail("", "missing section [building.A] (the left building)");
  structure::Structure s;
  s.a = read_building(root, "A", top);
  if (buildings->get_as<toml::table>("B")) s.b = read_building(root, "B", top);

  auto floors_of = [&](const TableReader& r) {
    const auto f = r.integers("floors", 2);
    if (!s.b) r.fail("", "links and contacts join building A to building B: add [building.B]");
    for (const auto& [name, floor, b] : {std::tuple{'A', f[0], &s.a}, std::tuple{'B', f[1], &*s.b}})
      if (const std::string problem = structure::floor_problem(name, floor, *b); !problem.empty()) r.fail("floors", problem);
    return f;
  };
  if (const toml::array* links = root.get_as<toml::array>("link")) {
    int index = 0;
    for (const auto& node : *links) {
      ++index;
      const toml::table* lt = node.as_table();
      if (!lt) top.fail("link", "expected [[link]] tables");
      const TableReader r = top.inner(*lt, "link[" + std::to_string(index) + "]");
      structure::Link l;
      const auto f = floors_of(r);
      l.floor_a = f[0];
      l.floor_b = f[1];
      l.type = r.choice<LinkType>("type");
      r.only(link_keys(l.type));
      if (structure::kind_of(l).family(l) == structure::LinkFamily::friction) {
        // Its own rule: slip_force [N], or slip_ratio of a building's weight (structure/rules.hpp).
        if (r.has("slip_force") == r.has("slip_ratio")) r.fail("", "give slip_force [N] or slip_ratio with of = \"A\" or \"B\", one of them");
        if (r.has("slip_force")) {
          if (r.has("of")) r.fail("of", "of names the building whose weight slip_ratio is a fraction of; slip_force is in N: remove of, or give slip_ratio");
          l.slip_force = r.bounded("slip_force", kForceRange);
        } else {
          const double ratio = r.bounded("slip_ratio", kSlipRatioRange);
          const std::string of = r.text("of", {"A", "B"});
          l.slip_force = structure::slip_force_from_ratio(ratio, of == "A" ? s.a : *s.b);
        }
      }
      read_link_keys(r, &l);
      s.links.push_back(l);
    }
  } else if (root.contains("link")) {
    top.fail("link", "expected [[link]] tables");
  }
  if (const toml::array* contacts = root.get_as<toml::array>("contact")) {
    int index = 0;
    for (const auto& node : *contacts) {
      ++index;
      const toml::table* ct = node.as_table();
      if (!ct) top.fail("contact", "expected [[contact]] tables");
      const TableReader r = top.inner(*ct, "contact[" + std::to_string(index) + "]");
      r.only({"floors", "gap", "model", "stiffness", "restitution", "damping", "tension_cut"});
      structure::Contact c;
      const auto f = floors_of(r);
      c.floor_a = f[0];
      c.floor_b = f[1];
      c.gap = r.number("gap");
      if (!(c.gap >= 0.0)) r.fail("gap", "expected a clear distance at rest >= 0 (m)");
      c.law = read_contact_law(r);
      s.contacts.push_back(c);
    }
  } else if (root.contains("contact")) {
    top.fail("contact", "expected [[contact]] tables");
  }
  std::string error;
  if (!s.IsValid(&error)) throw InputError(file + ": " + error);
  return s;
}

structure::Structure structure_of(const Scene& scene) {
  return scene.two_block() ? structure::two_block_structure(two_block_model(scene), scene.scales) : scene.structure;
}

}  // namespace adjoin
