#include "adjoin/observe/channel_recorder.hpp"

#include <algorithm>

#include "adjoin/core/errors.hpp"

namespace adjoin {

ChannelRecorder::ChannelRecorder(std::vector<std::string> names, std::size_t every)
    : asked_(std::move(names)), every_(std::max<std::size_t>(every, 1)) {}

void ChannelRecorder::begin(const structure::Structure& s, const StructureSolverOptions& options) {
  structure_ = s;
  std::vector<structure::Channel> channels;
  if (asked_.empty()) {
    channels = structure::channels(structure_);
  } else {
    for (std::size_t i = 0; i < asked_.size(); ++i) {
      const auto channel = structure::find_channel(structure_, asked_[i]);
      if (!channel)
        throw FieldError("channels[" + std::to_string(i + 1) + "]",
                         "\"" + asked_[i] + "\" is not a channel of this structure (A.x1, A.a1_abs, A.drift1, A.shear1, "
                         "A.base_shear, link1.force, contact1.gap, ...: structure/channels.hpp)");
      channels.push_back(*channel);
    }
  }
  names_.clear();
  for (const auto& c : channels) names_.push_back(c.name);
  reader_ = ChannelValues(structure_, std::move(channels));
  // The grid has steps() + 1 points (t = 0 included); a row for every every_-th of them.
  const auto rows = static_cast<Eigen::Index>(options.steps() / every_ + 1);
  times_.resize(rows);
  values_.resize(rows, static_cast<Eigen::Index>(names_.size()));
  row_.resize(static_cast<Eigen::Index>(names_.size()));
  seen_ = rows_ = 0;
}

void ChannelRecorder::observe(const StructureState& state) {
  if (seen_++ % every_ != 0) return;
  if (rows_ == static_cast<std::size_t>(times_.size())) {  // a grid longer than steps() said: grow
    const Eigen::Index more = std::max<Eigen::Index>(16, times_.size() / 2);
    times_.conservativeResize(times_.size() + more);
    values_.conservativeResize(values_.rows() + more, Eigen::NoChange);
  }
  reader_.read(state, row_.data());
  const auto r = static_cast<Eigen::Index>(rows_++);
  times_[r] = state.t;
  values_.row(r) = row_.transpose();
}

Eigen::VectorXd ChannelRecorder::column(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) throw FieldError("channels", "\"" + name + "\" was not recorded");
  return values().col(static_cast<Eigen::Index>(it - names_.begin()));
}

}  // namespace adjoin
