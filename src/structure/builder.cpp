#include "adjoin/structure/builder.hpp"

#include <cmath>

#include "adjoin/core/errors.hpp"
#include "adjoin/structure/contact_rules.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "adjoin/structure/rules.hpp"

namespace adjoin::structure {
namespace {

// Throws FieldError for `field` when `problem` says something is wrong.
void check(const std::string& field, const std::string& problem) {
  if (!problem.empty()) throw FieldError(field, problem);
}

std::string item(const std::string& path, std::size_t index) { return path + "[" + std::to_string(index + 1) + "]"; }

}  // namespace

// ---- buildings ----

BuildingBuilder::BuildingBuilder(char name, int storeys) : path_(std::string("building.") + name) {
  if (name != 'A' && name != 'B') throw FieldError("building", std::string("expected A or B, not ") + name);
  if (storeys < 1 || storeys > kMaxStoreys)
    throw FieldError(path_ + ".storeys", "expected a whole number from 1 to " + std::to_string(kMaxStoreys));
  b_.name = std::string(1, name);
  b_.masses = Eigen::VectorXd::Zero(storeys);
  b_.springs = Eigen::VectorXd::Zero(storeys);
}

BuildingBuilder& BuildingBuilder::mass(double kg) {
  check(path_ + ".mass", bounded_problem(kg, kMassRange));
  b_.masses.setConstant(kg);
  mass_given_ = true;
  return *this;
}

BuildingBuilder& BuildingBuilder::masses(const std::vector<double>& kg) {
  const auto n = static_cast<std::size_t>(b_.floors());
  if (kg.size() != n) throw FieldError(path_ + ".masses", "expected " + std::to_string(n) + " values, one per floor (bottom up)");
  for (std::size_t i = 0; i < n; ++i) check(item(path_ + ".masses", i), bounded_problem(kg[i], kMassRange));
  b_.masses = Eigen::Map<const Eigen::VectorXd>(kg.data(), static_cast<Eigen::Index>(n));
  mass_given_ = true;
  return *this;
}

BuildingBuilder& BuildingBuilder::stiffness(double n_per_m) {
  check(path_ + ".stiffness", bounded_problem(n_per_m, kStiffnessRange));
  b_.springs.setConstant(n_per_m);
  stiffness_given_ = "stiffness";
  return *this;
}

BuildingBuilder& BuildingBuilder::stiffnesses(const std::vector<double>& n_per_m) {
  const auto n = static_cast<std::size_t>(b_.floors());
  if (n_per_m.size() != n)
    throw FieldError(path_ + ".stiffnesses", "expected " + std::to_string(n) + " values, one per storey (bottom up)");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(n_per_m[i] >= 0.0)) throw FieldError(item(path_ + ".stiffnesses", i), "expected a non-negative stiffness (N/m)");
    // 0: a storey stiffened by its devices only.
    if (n_per_m[i] > 0.0) check(item(path_ + ".stiffnesses", i), kStiffnessRange.problem(n_per_m[i]));
  }
  b_.springs = Eigen::Map<const Eigen::VectorXd>(n_per_m.data(), static_cast<Eigen::Index>(n));
  stiffness_given_ = "stiffnesses";
  return *this;
}

BuildingBuilder& BuildingBuilder::period(double seconds) {
  if (!(std::isfinite(seconds) && seconds > 0.0)) throw FieldError(path_ + ".period", "expected a positive number");
  period_ = seconds;
  b_.springs.setZero();
  stiffness_given_ = "period";
  return *this;
}

BuildingBuilder& BuildingBuilder::no_damping() {
  b_.damping = InherentDamping{};
  return *this;
}

BuildingBuilder& BuildingBuilder::modal_damping(double ratio) {
  check(path_ + ".damping.ratio", damping_ratio_problem(ratio));
  b_.damping = InherentDamping{DampingModel::modal, ratio, 1, 2};
  return *this;
}

BuildingBuilder& BuildingBuilder::rayleigh_damping(double ratio, int mode_i, int mode_j) {
  check(path_ + ".damping.ratio", damping_ratio_problem(ratio));
  check(path_ + ".damping.modes", rayleigh_modes_problem(mode_i, mode_j, b_.floors()));
  b_.damping = InherentDamping{DampingModel::rayleigh, ratio, mode_i, mode_j};
  return *this;
}

BuildingBuilder& BuildingBuilder::height(double m) {
  check(path_ + ".height", bounded_problem(m, kHeightRange));
  b_.heights = Eigen::VectorXd::Constant(b_.floors(), m);
  return *this;
}

BuildingBuilder& BuildingBuilder::heights(const std::vector<double>& m) {
  const auto n = static_cast<std::size_t>(b_.floors());
  if (m.size() != n) throw FieldError(path_ + ".heights", "expected " + std::to_string(n) + " values, one per storey (bottom up)");
  for (std::size_t i = 0; i < n; ++i) check(item(path_ + ".heights", i), bounded_problem(m[i], kHeightRange));
  b_.heights = Eigen::Map<const Eigen::VectorXd>(m.data(), static_cast<Eigen::Index>(n));
  return *this;
}

BuildingBuilder& BuildingBuilder::p_delta(bool on) {
  b_.p_delta = on;
  return *this;
}

BuildingBuilder& BuildingBuilder::collapse_drift_ratio(double ratio) {
  check(path_ + ".collapse_drift_ratio", bounded_problem(ratio, kDriftRatioRange));
  b_.collapse_drift_ratio = ratio;
  collapse_given_ = true;
  return *this;
}

BuildingBuilder& BuildingBuilder::bilinear(double yield_force, double hardening) {
  return bilinear_per_storey(std::vector<double>(static_cast<std::size_t>(b_.floors()), yield_force), hardening);
}

BuildingBuilder& BuildingBuilder::bilinear_per_storey(const std::vector<double>& yield_forces, double hardening) {
  return hysteresis(HysteresisModel::bilinear, &yield_forces, 0.0, hardening, {});
}

BuildingBuilder& BuildingBuilder::bilinear_drift_ratio(double yield_drift_ratio, double hardening) {
  return hysteresis(HysteresisModel::bilinear, nullptr, yield_drift_ratio, hardening, {});
}

BuildingBuilder& BuildingBuilder::bouc_wen(double yield_force, double hardening, BoucWenShape shape) {
  return bouc_wen_per_storey(std::vector<double>(static_cast<std::size_t>(b_.floors()), yield_force), hardening, shape);
}

BuildingBuilder& BuildingBuilder::bouc_wen_per_storey(const std::vector<double>& yield_forces, double hardening, BoucWenShape shape) {
  return hysteresis(HysteresisModel::bouc_wen, &yield_forces, 0.0, hardening, shape);
}

BuildingBuilder& BuildingBuilder::bouc_wen_drift_ratio(double yield_drift_ratio, double hardening, BoucWenShape shape) {
  return hysteresis(HysteresisModel::bouc_wen, nullptr, yield_drift_ratio, hardening, shape);
}

namespace {

// A Bouc-Wen shape's fields under `path` (".n", ".beta" or ".gamma"); beta + gamma is blamed on
// gamma when it was changed from its default, as a scene blames the key it was given.
void check_bouc_wen_shape(const std::string& path, const BoucWenShape& shape) {
  check(path + ".n", bouc_wen_exponent_problem(shape.n));
  check(path + (shape.gamma != BoucWenShape{}.gamma ? ".gamma" : ".beta"), bouc_wen_shape_problem(shape.beta, shape.gamma));
}

}  // namespace

BuildingBuilder& BuildingBuilder::hysteresis(HysteresisModel model, const std::vector<double>* yield_forces,
                                             double yield_drift_ratio, double hardening, const BoucWenShape& shape) {
  const std::string path = path_ + ".hysteresis";
  const auto n = static_cast<std::size_t>(b_.floors());
  if (model == HysteresisModel::bouc_wen) check_bouc_wen_shape(path, shape);
  StoreyHysteresis y;
  y.model = model;
  if (!yield_forces) {
    check(path + ".yield_drift_ratio", bounded_problem(yield_drift_ratio, kDriftRatioRange));
    y.yield_drift_ratio = yield_drift_ratio;  // its forces need the final springs and heights: build()
  } else {
    if (yield_forces->size() != n)
      throw FieldError(path + ".yield_forces", "expected " + std::to_string(n) + " values, one per storey (bottom up)");
    for (std::size_t i = 0; i < n; ++i) check(item(path + ".yield_forces", i), bounded_problem((*yield_forces)[i], kForceRange));
    y.yield_forces = Eigen::Map<const Eigen::VectorXd>(yield_forces->data(), static_cast<Eigen::Index>(n));
  }
  check(path + ".hardening", hardening_problem(hardening));
  y.hardening = hardening;
  if (model == HysteresisModel::bouc_wen) {
    y.n = shape.n;
    y.beta = shape.beta;
    y.gamma = shape.gamma;
  }
  b_.hysteresis = y;
  return *this;
}

BuildingBuilder& BuildingBuilder::flat_slider(double base_mass, double friction) {
  return isolated_base({base_mass, BaseModel::flat_slider, friction, 0.0});
}

BuildingBuilder& BuildingBuilder::friction_pendulum(double base_mass, double friction, double radius) {
  check(path_ + ".base.radius", base_radius_problem(radius));
  return isolated_base({base_mass, BaseModel::friction_pendulum, friction, radius});
}

BuildingBuilder& BuildingBuilder::isolated_base(const Base& base) {
  check(path_ + ".base.mass", base_mass_problem(base.mass));
  check(path_ + ".base.friction", base_friction_problem(base.friction));
  b_.base = base;
  return *this;
}

std::string BuildingBuilder::device_path() const { return item(path_ + ".device", b_.devices.size()); }

void BuildingBuilder::add_device(StoreyDevice device, const std::vector<int>& storeys) {
  check(device_path() + ".storeys", device_storeys_problem(storeys, b_.floors()));
  device.storeys = storeys;
  b_.devices.push_back(std::move(device));
}

BuildingBuilder& BuildingBuilder::device(DeviceType type, const std::vector<int>& storeys, const std::map<std::string, double>& values) {
  const DeviceKind& kind = device_kind(type);
  const std::string path = device_path();
  for (const auto& [name, value] : values) {
    bool known = false;
    for (const DeviceKey& key : kind.keys) known = known || name == key.name;
    if (!known) throw FieldError(path + "." + name, "not a key of a " + to_string(type) + " device");
  }
  StoreyDevice d;
  d.type = type;
  for (const DeviceKey& key : kind.keys) {
    const auto given = values.find(key.name);
    if (given == values.end() && key.required) throw FieldError(path + "." + key.name, "missing: a " + to_string(type) + " device needs it");
    const double v = given == values.end() ? key.fallback : given->second;
    check(path + "." + key.name, key.problem(v));
    key.field(d) = v;
  }
  // The rule between keys is blamed on the first of its keys changed from its default.
  auto changed = [&](const char* name) {
    for (const DeviceKey& key : kind.keys)
      if (name == std::string(key.name)) return key.required || key.field(d) != key.fallback;
    return false;
  };
  check(path + "." + joint_key(kind, changed), kind.joint_problem(d));
  add_device(d, storeys);
  return *this;
}

BuildingBuilder& BuildingBuilder::spring(const std::vector<int>& storeys, double k) {
  return device(DeviceType::spring, storeys, {{"stiffness", k}});
}

BuildingBuilder& BuildingBuilder::dashpot(const std::vector<int>& storeys, double c, double alpha) {
  return device(DeviceType::dashpot, storeys, {{"c", c}, {"alpha", alpha}});
}

BuildingBuilder& BuildingBuilder::bilinear_device(const std::vector<int>& storeys, double k, double yield_force, double hardening) {
  return device(DeviceType::bilinear, storeys, {{"stiffness", k}, {"yield_force", yield_force}, {"hardening", hardening}});
}

BuildingBuilder& BuildingBuilder::bouc_wen_device(const std::vector<int>& storeys, double k, double yield_force, double hardening,
                                                  BoucWenShape shape) {
  return device(DeviceType::bouc_wen, storeys,
                {{"stiffness", k}, {"yield_force", yield_force}, {"hardening", hardening}, {"n", shape.n}, {"beta", shape.beta}, {"gamma", shape.gamma}});
}

BuildingBuilder& BuildingBuilder::zener(const std::vector<int>& storeys, const Zener& z) {
  return device(DeviceType::zener, storeys, {{"stiffness", z.k}, {"order", z.order}, {"tau_f", z.tau_f}, {"tau_x", z.tau_x}});
}

Building BuildingBuilder::build() const {
  if (!mass_given_) throw FieldError(path_ + ".mass", "missing: give the floor masses (mass or masses)");
  Building b = b_;
  if (stiffness_given_ == "period") {
    std::string problem;
    const double k = stiffness_for_period_in_range(b.masses, period_, &problem);
    check(path_ + ".period", problem);
    b.springs.setConstant(k);
    if (!b.devices.empty()) {
      b.springs.setConstant(spring_for_period_with_devices(b, period_, k, &problem));
      check(path_ + ".period", problem);
    }
  }
  check(path_, storey_stiffness_problem(b));
  std::string key;
  if (const std::string problem = heights_problem(b, collapse_given_, &key); !problem.empty())
    throw FieldError(path_ + "." + key, problem);
  if (b.hysteresis.yield_drift_ratio > 0.0)
    check(path_ + ".hysteresis.yield_drift_ratio", yield_forces_from_drift_ratio(&b, b.hysteresis.yield_drift_ratio));
  return b;
}

// ---- contacts ----

ContactBuilder::ContactBuilder(std::string path, int floor_a, int floor_b, double gap) : path_(std::move(path)) {
  if (!(std::isfinite(gap) && gap >= 0.0)) throw FieldError(path_ + ".gap", "expected a clear distance at rest >= 0 (m)");
  c_.floor_a = floor_a;
  c_.floor_b = floor_b;
  c_.gap = gap;
}

ContactBuilder& ContactBuilder::model(ContactModel model) {
  c_.law.model = model;
  return *this;
}
ContactBuilder& ContactBuilder::stiffness(double k) {
  stiffness_ = k;
  return *this;
}
ContactBuilder& ContactBuilder::restitution(double e) {
  restitution_ = e;
  return *this;
}
ContactBuilder& ContactBuilder::damping(double value) {
  damping_ = value;
  return *this;
}
ContactBuilder& ContactBuilder::tension_cut(bool cut) {
  tension_cut_ = cut;
  return *this;
}

Contact ContactBuilder::build() const {
  // The values given are read as a scene's keys are: one set of rules for both.
  const auto value = [&](const std::string& key) -> const std::optional<double>& {
    return key == "stiffness" ? stiffness_ : key == "restitution" ? restitution_ : damping_;
  };
  ContactTable t;
  t.where = path_;
  t.has = [&](const std::string& key) { return key == "tension_cut" ? tension_cut_.has_value() : value(key).has_value(); };
  t.number = [&](const std::string& key) { return *value(key); };
  t.boolean = [&](const std::string&) { return *tension_cut_; };
  t.fail = [&](const std::string& key, const std::string& message) {
    throw FieldError(key.empty() ? path_ : path_ + "." + key, message);
  };
  t.stiffness_unit = [](ContactModel m) -> std::string { return m == ContactModel::linear ? "N/m" : "N/m^1.5"; };
  Contact c = c_;
  c.law = contact_law_from(t, c_.law.model);
  if (stiffness_) check(path_ + ".stiffness", contact_stiffness_problem(c.law.stiffness, t.stiffness_unit(c.law.model)));
  return c;
}

// ---- the structure ----

BuildingBuilder& StructureBuilder::building(char name, int storeys) {
  std::optional<BuildingBuilder>& slot = name == 'B' ? b_ : a_;
  if (!slot) {
    slot.emplace(name, storeys);
  } else if (slot->storeys() != storeys) {
    throw FieldError(slot->path() + ".storeys", "the building has " + std::to_string(slot->storeys()) + " storeys, not " +
                                                    std::to_string(storeys));
  }
  return *slot;
}

std::string StructureBuilder::link_path() const { return "link[" + std::to_string(links_.size() + 1) + "]"; }

StructureBuilder& StructureBuilder::add_link(Link link) {
  links_.push_back({link, std::nullopt, 'B'});
  return *this;
}

StructureBuilder& StructureBuilder::friction_link(int floor_a, int floor_b, double slip_force) {
  check(link_path() + ".slip_force", bounded_problem(slip_force, kForceRange));
  return add_link({LinkType::friction, floor_a, floor_b, slip_force, 0.0, 0.0, {}});
}

StructureBuilder& StructureBuilder::friction_link_ratio(int floor_a, int floor_b, double slip_ratio, char of) {
  check(link_path() + ".slip_ratio", bounded_problem(slip_ratio, kSlipRatioRange));
  if (of != 'A' && of != 'B') throw FieldError(link_path() + ".of", "expected \"A\" or \"B\"");
  links_.push_back({{LinkType::friction, floor_a, floor_b, 0.0, 0.0, 0.0, {}}, slip_ratio, of});
  return *this;
}

StructureBuilder& StructureBuilder::link(LinkType type, int floor_a, int floor_b, const std::map<std::string, double>& values) {
  const LinkKind& kind = link_kind(type);
  const std::string path = link_path();
  if (!kind.own_keys.empty())
    throw FieldError(path + ".type", "a " + to_string(type) + " link has a rule of its own: use friction_link or friction_link_ratio");
  for (const auto& [name, value] : values) {
    bool known = false;
    for (const LinkKey& key : kind.keys) known = known || name == key.name;
    if (!known) throw FieldError(path + "." + name, "not a key of a " + to_string(type) + " link");
  }
  Link l;
  l.type = type;
  l.floor_a = floor_a;
  l.floor_b = floor_b;
  for (const LinkKey& key : kind.keys) {
    const auto given = values.find(key.name);
    if (given == values.end() && key.required) throw FieldError(path + "." + key.name, "missing: a " + to_string(type) + " link needs it");
    const double v = given == values.end() ? key.fallback : given->second;
    check(path + "." + key.name, key.problem(v));
    key.field(l) = v;
  }
  if (const std::string problem = kind.joint_problem(l); !problem.empty()) check(path + "." + kind.joint_keys.front(), problem);
  return add_link(l);
}

StructureBuilder& StructureBuilder::dashpot_link(int floor_a, int floor_b, double c, double alpha) {
  return link(LinkType::dashpot, floor_a, floor_b, {{"c", c}, {"alpha", alpha}});
}

StructureBuilder& StructureBuilder::spring_link(int floor_a, int floor_b, double k) {
  return link(LinkType::spring, floor_a, floor_b, {{"stiffness", k}});
}

StructureBuilder& StructureBuilder::zener_link(int floor_a, int floor_b, const Zener& z) {
  return link(LinkType::zener, floor_a, floor_b, {{"stiffness", z.k}, {"order", z.order}, {"tau_f", z.tau_f}, {"tau_x", z.tau_x}});
}

ContactBuilder& StructureBuilder::contact(int floor_a, int floor_b, double gap) {
  return contacts_.emplace_back("contact[" + std::to_string(contacts_.size() + 1) + "]", floor_a, floor_b, gap);
}

namespace {

// A link's or contact pair's floors: of A and of B, within each building.
void check_floors(const std::string& path, int floor_a, int floor_b, const Structure& s) {
  if (!s.b) throw FieldError(path, "links and contacts join building A to building B: add building B");
  check(path + ".floors", floor_problem('A', floor_a, s.a));
  check(path + ".floors", floor_problem('B', floor_b, *s.b));
}

}  // namespace

Structure StructureBuilder::build() const {
  if (!a_) throw FieldError("building.A", "missing: a structure has building A (the left building)");
  Structure s;
  s.a = a_->build();
  if (b_) s.b = b_->build();
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const std::string path = "link[" + std::to_string(i + 1) + "]";
    Link link = links_[i].link;
    check_floors(path, link.floor_a, link.floor_b, s);
    if (links_[i].slip_ratio) link.slip_force = slip_force_from_ratio(*links_[i].slip_ratio, links_[i].of == 'A' ? s.a : *s.b);
    s.links.push_back(link);
  }
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    Contact c = contacts_[i].build();
    check_floors("contact[" + std::to_string(i + 1) + "]", c.floor_a, c.floor_b, s);
    s.contacts.push_back(c);
  }
  std::string error;
  if (!s.IsValid(&error)) throw InputError(error);
  return s;
}

}  // namespace adjoin::structure
