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
