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

// Reads many channels at each grid point. The common channels (floors' displacements and
// absolute accelerations, drifts and drift ratios, storey shears, links' forces and strokes) are
// each one or two entries of a state vector: read() takes them in plain loops over index lists
// made once, per vector, with no switch per channel; the rest go through channel_value. The
// values are channel_value's, bit for bit.
class ChannelValues {
 public:
  ChannelValues() = default;  // no channels
  ChannelValues(const structure::Structure& s, std::vector<structure::Channel> channels)
      : s_(&s), channels_(std::move(channels)) {
    using structure::Quantity;
    for (std::size_t k = 0; k < channels_.size(); ++k) {
      const structure::Channel& c = channels_[k];
      const int link = c.index - 1;
      switch (c.quantity) {
        case Quantity::displacement: add(kX, {k, c.dof, -1, 1.0}); break;
        case Quantity::absolute_acceleration: add(kAcceleration, {k, c.dof, -1, 1.0}); break;
        case Quantity::storey_shear: add(kStoreyForce, {k, c.dof, -1, 1.0}); break;
        case Quantity::link_force: add(kLinkForce, {k, link, -1, 1.0}); break;
        case Quantity::link_stroke: add(kLinkStroke, {k, link, -1, 1.0}); break;
        case Quantity::drift:
        case Quantity::drift_ratio: {
          // x[dof] minus the floor below's, or the isolated base's (-1: the ground's 0).
          const int below = c.index > 1 ? c.dof - 1 : s.base_dof(c.building);
          const structure::Building& b = c.building == 'A' ? s.a : *s.b;
          add(kX, {k, c.dof, below, c.quantity == Quantity::drift ? 1.0 : b.heights[c.index - 1]});
          break;
        }
        default: other_.push_back(k);
      }
    }
  }
  const std::vector<structure::Channel>& channels() const { return channels_; }
  std::size_t size() const { return channels_.size(); }
  // out[k] = the value of channels()[k] at `state`.
  void read(const StructureState& state, double* out) const {
    const double* vectors[kVectors] = {state.x.data(), state.a_abs.data(), state.storey_force.data(),
                                       state.link_force.data(), state.link_stroke.data()};
    for (int v = 0; v < kVectors; ++v) {
      const double* y = vectors[v];
      for (const Copy& c : copies_[v]) out[c.channel] = y[c.i];
      for (const Term& t : plan_[v]) out[t.channel] = (y[t.i] - (t.j >= 0 ? y[t.j] : 0.0)) / t.divisor;
    }
    for (std::size_t k : other_) out[k] = channel_value(*s_, channels_[k], state);
  }

 private:
  // out[channel] = (y[i] - y[j]) / divisor, y one of the state's vectors (j < 0: y[i] / divisor).
  struct Term {
    std::size_t channel;
    int i, j;
    double divisor;
  };
  // out[channel] = y[i]: most channels (the terms with j < 0 and divisor 1, which would give
  // the same bits in twice the instructions: y - 0.0 and y / 1.0 are y).
  struct Copy {
    std::size_t channel;
    int i;
  };
  enum { kX, kAcceleration, kStoreyForce, kLinkForce, kLinkStroke, kVectors };
  void add(int vector, const Term& t) {
    if (t.j < 0 && t.divisor == 1.0) copies_[vector].push_back({t.channel, t.i});
    else plan_[vector].push_back(t);
  }
  const structure::Structure* s_ = nullptr;
  std::vector<structure::Channel> channels_;
  std::vector<Copy> copies_[kVectors];
  std::vector<Term> plan_[kVectors];
  std::vector<std::size_t> other_;  // read by channel_value
};

}  // namespace adjoin
