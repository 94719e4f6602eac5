#pragma once
// Keeps the states at every `every`-th grid point (and always the last one) in memory.
// For long runs prefer a streaming writer (io/timeseries_csv.hpp), which keeps nothing.
#include <vector>

#include "adjoin/structure/observer.hpp"

namespace adjoin {

class TimeSeriesRecorder final : public Observer {
 public:
  explicit TimeSeriesRecorder(std::size_t every = 1) : every_(every == 0 ? 1 : every) {}
  void begin(const RunInfo& info) override {
    states_.clear();
    steps_ = info.steps;
    states_.reserve(info.steps / every_ + 2);
    count_ = 0;
  }
  void observe(const State& s) override {
    if (count_ % every_ == 0 || count_ == steps_) states_.push_back(s);
    ++count_;
  }
  const std::vector<State>& states() const { return states_; }

 private:
  std::size_t every_;
  std::size_t steps_ = 0, count_ = 0;
  std::vector<State> states_;
};

}  // namespace adjoin
