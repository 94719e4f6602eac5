#include "adjoin/observe/channel_values.hpp"

namespace adjoin {

using structure::Quantity;

double channel_value(const structure::Structure& s, const structure::Channel& c, const StructureState& st) {
  const auto k = static_cast<Eigen::Index>(c.index - 1);  // a link's or contact pair's index
  switch (c.quantity) {
    case Quantity::displacement: return st.x[c.dof];
    case Quantity::absolute_acceleration: return st.a_abs[c.dof];
    case Quantity::drift: return st.x[c.dof] - (c.index > 1 ? st.x[c.dof - 1] : 0.0);
    case Quantity::storey_shear: return st.storey_force[c.dof];
    case Quantity::base_shear: {
      // The sum of the floors' inertia forces.
      const structure::Building& b = c.building == 'A' ? s.a : *s.b;
      const int first = s.dof(c.building, 1);
      double shear = 0.0;
      for (int i = 0; i < b.floors(); ++i) shear -= b.masses[i] * st.a_abs[first + i];
      return shear;
    }
    case Quantity::link_force: return st.link_force[k];
    case Quantity::link_stroke: return st.link_stroke[k];
    case Quantity::contact_gap: {
      if (st.contact_gap.size() == static_cast<Eigen::Index>(s.contacts.size())) return st.contact_gap[k];
      const structure::Contact& pair = s.contacts[static_cast<std::size_t>(k)];
      return pair.gap - (st.x[s.dof('A', pair.floor_a)] - st.x[s.dof('B', pair.floor_b)]);
    }
    case Quantity::contact_force:
      return st.contact_force.size() == static_cast<Eigen::Index>(s.contacts.size()) ? st.contact_force[k] : 0.0;
  }
  return 0.0;
}

}  // namespace adjoin
