#include "adjoin/structure/two_block.hpp"

#include <cmath>

namespace adjoin::structure {

Structure two_block_structure(const Model& m, const Scales& k) {
  const double m1 = k.force / k.acceleration, k1 = k.force / k.length;  // 1 and 1 when dimensionless
  auto storey = [&](const Rod& rod, double mass, double stiffness, const char* name) {
    Building b;
    b.name = name;
    b.masses = Eigen::VectorXd::Constant(1, mass);
    if (rod.elastic) {
      b.springs = Eigen::VectorXd::Constant(1, stiffness);
    } else {
      b.springs = Eigen::VectorXd::Zero(1);
      StoreyDevice d;
      d.type = DeviceType::zener;
      d.storeys = {1};
      const double time_power = std::pow(k.time, rod.order);  // tau in s^order
      d.zener = {stiffness, rod.order, rod.tau_x * time_power, rod.tau_f * time_power};
      b.devices.push_back(d);
    }
    return b;
  };
  Structure s;
  s.a = storey(m.rod1, m1, k1, "A");
  s.b = storey(m.rod2, m1 / m.rho, m.eps * k1, "B");
  // Base friction (SPEC §7): each block on its base with friction mu_b m_i g (m1 g = k.force).
  s.a.ground_friction = m.base_friction * k.force;
  s.b->ground_friction = m.base_friction / m.rho * k.force;
  if (m.mu > 0.0) {
    Link l;
    l.type = LinkType::friction;
    l.slip_force = m.mu * k.force;
    s.links.push_back(l);
  }
  Contact contact;
  contact.gap = m.gap0 * k.length;
  contact.law = m.contact;
  // Dimensionless stiffness in units of k1 (linear) or k1 / L^(1/2) (Hertz-type laws).
  contact.law.stiffness *= m.contact.model == ContactModel::linear ? k1 : k.force / std::pow(k.length, 1.5);
  s.contacts.push_back(contact);
  return s;
}

namespace {

// A block of the 1 + 1 structure: one storey with a spring alone (an elastic rod) or a Zener
// device alone, nothing else. Its stiffness and rod, or the reason it is not such a block.
std::string block_problem(const Building& b, double* stiffness, Rod* rod) {
  if (b.floors() != 1) return "building " + b.name + " has " + std::to_string(b.floors()) + " floors, not 1";
  if (b.damping.model != DampingModel::none || b.hysteresis.model != HysteresisModel::elastic || b.base || b.p_delta)
    return "building " + b.name + " has damping, hysteresis, an isolated base or P-Delta";
  if (b.devices.empty()) {
    *rod = Rod::Elastic();
    *stiffness = b.springs[0];
    return "";
  }
  const StoreyDevice& d = b.devices[0];
  if (b.devices.size() > 1 || d.type != DeviceType::zener || b.springs[0] != 0.0)
    return "building " + b.name + "'s storey is not one Zener rod or one spring";
  *rod = Rod{d.zener.order, d.zener.tau_x, d.zener.tau_f, false};
  *stiffness = d.zener.k;
  return "";
}

std::string model_problem(const Structure& s, Model* m) {
  if (!s.b) return "there is no building B";
  double k1 = 0.0, k2 = 0.0;
  if (std::string p = block_problem(s.a, &k1, &m->rod1); !p.empty()) return p;
  if (std::string p = block_problem(*s.b, &k2, &m->rod2); !p.empty()) return p;
  if (s.a.masses[0] != 1.0 || k1 != 1.0) return "building A's mass and stiffness are not 1 (the model's units)";
  m->rho = 1.0 / s.b->masses[0];
  m->eps = k2;
  m->base_friction = s.a.ground_friction;
  // (mu_b / rho against mu_b (1 / rho): equal but for rounding)
  if (std::abs(s.b->ground_friction - m->base_friction / m->rho) > 1e-14 * s.b->ground_friction) return "the blocks' base frictions are not one coefficient";
  if (s.links.size() > 1 || (s.links.size() == 1 && (s.links[0].type != LinkType::friction || s.links[0].floor_a != 1 ||
                                                       s.links[0].floor_b != 1 || !(s.links[0].slip_force > 0.0))))
    return "the links are not one friction damper between the blocks";
  m->mu = s.links.empty() ? 0.0 : s.links[0].slip_force;
  if (s.contacts.size() != 1 || s.contacts[0].floor_a != 1 || s.contacts[0].floor_b != 1)
    return "there is not one contact pair between the blocks";
  m->gap0 = s.contacts[0].gap;
  m->contact = s.contacts[0].law;
  return "";
}

}  // namespace

std::optional<Model> two_block_model(const Structure& s, std::string* why) {
  Model m;
  const std::string problem = model_problem(s, &m);
  if (problem.empty()) return m;
  if (why) *why = "not the two-block structure: " + problem;
  return std::nullopt;
}

std::string two_block_channel(const std::string& name) {
  static const std::pair<const char*, const char*> names[] = {
      {"x1", "A.x1"},     {"x2", "B.x1"},     {"drift", "link1.stroke"}, {"f1", "A.shear1"},      {"f2", "B.shear1"},
      {"q", "link1.force"}, {"a1_abs", "A.a1_abs"}, {"a2_abs", "B.a1_abs"}, {"gap", "contact1.gap"},
      {"v1", "A.v1"},     {"v2", "B.v1"},     {"ag", "ag"}};
  for (const auto& [frozen, channel] : names)
    if (name == frozen) return channel;
  return "";
}

}  // namespace adjoin::structure
