#pragma once
// The value of a structure's channel (structure/channels.hpp) at a grid point of the
// structure solver: the one place where a channel's quantity is read from a StructureState.
//
//     ChannelValues values(structure, structure::channels(structure));
//     values.read(state, row.data());   // row.size() == values.channels().size()
#include <algorithm>
#include <vector>

#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/channels.hpp"

namespace adjoin {

// The state's entry a channel of an `entry` quantity reads: its floor's or storey's (its dof),
// or its link's or contact pair's (its index).
inline int entry_index(const structure::QuantityInfo& q, const structure::Channel& c) {
  return q.scope == structure::ChannelScope::floor || q.scope == structure::ChannelScope::storey ? c.dof : c.index - 1;
}
// A storey's floor below: storey 1's is its building's isolated base, or -1 (the ground's 0).
inline int floor_below(const structure::Structure& s, const structure::Channel& c) {
  return c.index > 1 ? c.dof - 1 : s.base_dof(c.building);
}

// The value of channel c at the state, as its quantity's row says (structure/channels.hpp).
inline double channel_value(const structure::Structure& s, const structure::Channel& c, const StructureState& st) {
  using structure::StateRead;
  const structure::QuantityInfo& q = structure::info(c.quantity);
  if (q.read.form == StateRead::function) return q.read.value(s, c, st);
  const Eigen::VectorXd& y = st.*q.read.vector;
  if (q.read.form == StateRead::entry) return y[entry_index(q, c)];
  const int below = floor_below(s, c);
  const double d = y[c.dof] - (below >= 0 ? y[below] : 0.0);
  if (q.read.form == StateRead::drift) return d;
  const structure::Building& b = c.building == 'A' ? s.a : *s.b;
  return d / b.heights[c.index - 1];
}

// Reads many channels at each grid point. The channels whose value is an entry of a state
// vector, or a difference of two over a divisor (floors' displacements and absolute
// accelerations, drifts and drift ratios, storey shears, links' forces and strokes, ...), are
// taken in plain loops over index lists made once, per vector, with no switch per channel;
// the rest by their quantity's function. The values are channel_value's, bit for bit.
class ChannelValues {
 public:
  ChannelValues() = default;  // no channels
  ChannelValues(const structure::Structure& s, std::vector<structure::Channel> channels)
      : s_(&s), channels_(std::move(channels)) {
    using structure::StateRead;
    for (std::size_t k = 0; k < channels_.size(); ++k) {
      const structure::Channel& c = channels_[k];
      const structure::QuantityInfo& q = structure::info(c.quantity);
      switch (q.read.form) {
        case StateRead::entry: add(q.read.vector, {k, entry_index(q, c), -1, 1.0}); break;
        case StateRead::drift: add(q.read.vector, {k, c.dof, floor_below(s, c), 1.0}); break;
        case StateRead::drift_over_height: {
          const structure::Building& b = c.building == 'A' ? s.a : *s.b;
          add(q.read.vector, {k, c.dof, floor_below(s, c), b.heights[c.index - 1]});
          break;
        }
        case StateRead::function: other_.push_back({k, q.read.value}); break;
      }
    }
  }
  const std::vector<structure::Channel>& channels() const { return channels_; }
  std::size_t size() const { return channels_.size(); }
  // out[k] = the value of channels()[k] at `state`.
  void read(const StructureState& state, double* out) const {
    for (const Group& g : groups_) {
      const double* y = (state.*g.vector).data();
      for (const Copy& c : g.copies) out[c.channel] = y[c.i];
      for (const Term& t : g.terms) out[t.channel] = (y[t.i] - (t.j >= 0 ? y[t.j] : 0.0)) / t.divisor;
    }
    for (const Other& o : other_) out[o.channel] = o.value(*s_, channels_[o.channel], state);
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
  // The channels read from one of the state's vectors.
  struct Group {
    const Eigen::VectorXd StructureState::*vector;
    std::vector<Copy> copies;
    std::vector<Term> terms;
  };
  struct Other {
    std::size_t channel;
    double (*value)(const structure::Structure&, const structure::Channel&, const StructureState&);
  };
  void add(const Eigen::VectorXd StructureState::*vector, const Term& t) {
    auto g = std::find_if(groups_.begin(), groups_.end(), [&](const Group& h) { return h.vector == vector; });
    if (g == groups_.end()) g = groups_.insert(groups_.end(), Group{vector, {}, {}});
    if (t.j < 0 && t.divisor == 1.0) g->copies.push_back({t.channel, t.i});
    else g->terms.push_back(t);
  }
  const structure::Structure* s_ = nullptr;
  std::vector<structure::Channel> channels_;
  std::vector<Group> groups_;  // in the order their vectors first appear
  std::vector<Other> other_;   // read by their quantity's function
};

}  // namespace adjoin
