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

double channel_value(const structure::Structure& s, const structure::Channel& c, const StructureState& state);

class ChannelValues {
 public:
  ChannelValues(const structure::Structure& s, std::vector<structure::Channel> channels)
      : s_(&s), channels_(std::move(channels)) {}
  const std::vector<structure::Channel>& channels() const { return channels_; }
  std::size_t size() const { return channels_.size(); }
  // out[k] = the value of channels()[k] at `state`.
  void read(const StructureState& state, double* out) const {
    for (std::size_t k = 0; k < channels_.size(); ++k) out[k] = channel_value(*s_, channels_[k], state);
  }

 private:
  const structure::Structure* s_;
  std::vector<structure::Channel> channels_;
};

}  // namespace adjoin
