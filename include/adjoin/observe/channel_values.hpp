#pragma once
// The value of a structure's channel (structure/channels.hpp) at a grid point of the
// structure solver: the one place where a channel's quantity is read from a StructureState.
//
//     ChannelValues values(structure, structure::channels(structure));
//     values.read(state, row.data());   // row.size() == values.channels().size()
#include <vector>

#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/channels.hpp"

namespace adjoin {

// Under storey 1 of c's building: its isolated base's displacement (SPEC §7), or the ground's 0.
inline double base_x(const structure::Structure& s, const structure::Channel& c, const StructureState& st) {
  const int base = s.base_dof(c.building);
  return base >= 0 ? st.x[base] : 0.0;
}

// Inline: observers read every channel at every grid point.
inline double channel_value(const structure::Structure& s, const structure::Channel& c, const StructureState& st) {
  using structure::Quantity;
  const auto k = static_cast<Eigen::Index>(c.index - 1);  // a link's or contact pair's index
  switch (c.quantity) {
    case Quantity::displacement: return st.x[c.dof];
    case Quantity::absolute_acceleration: return st.a_abs[c.dof];
    case Quantity::drift: return st.x[c.dof] - (c.index > 1 ? st.x[c.dof - 1] : base_x(s, c, st));
    case Quantity::drift_ratio: {
      const structure::Building& b = c.building == 'A' ? s.a : *s.b;
      return (st.x[c.dof] - (c.index > 1 ? st.x[c.dof - 1] : base_x(s, c, st))) / b.heights[c.index - 1];
    }
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
    case Quantity::hysteretic: return st.hyst.size() > c.dof ? st.hyst[c.dof] : 0.0;
    case Quantity::contact_force:
      return st.contact_force.size() == static_cast<Eigen::Index>(s.contacts.size()) ? st.contact_force[k] : 0.0;
  }
  return 0.0;
}

class ChannelValues {
 public:
  ChannelValues() = default;  // no channels
  ChannelValues(const structure::Structure& s, std::vector<structure::Channel> channels)
      : s_(&s), channels_(std::move(channels)) {}
  const std::vector<structure::Channel>& channels() const { return channels_; }
  std::size_t size() const { return channels_.size(); }
  // out[k] = the value of channels()[k] at `state`.
  void read(const StructureState& state, double* out) const {
    for (std::size_t k = 0; k < channels_.size(); ++k) out[k] = channel_value(*s_, channels_[k], state);
  }

 private:
  const structure::Structure* s_ = nullptr;
  std::vector<structure::Channel> channels_;
};

}  // namespace adjoin
