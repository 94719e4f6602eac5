#pragma once
// The pounding margin: the gap xi(t) = gap0 + x2 - x1 between the blocks. xi <= 0 means the
// structures pound, where the model no longer holds. The minimum is refined between samples
// by a parabola through the three samples around it (extremum.hpp); the first contact time
// is interpolated linearly between the grid points that bracket it.
#include <optional>

#include "adjoin/observe/observer.hpp"

namespace adjoin {

struct PoundingMargin {
  double min_gap = 0.0;
  double t_min_gap = 0.0;
  bool contact = false;
  std::optional<double> t_first_contact;
};

class PoundingObserver final : public Observer {
 public:
  void begin(const RunInfo& info) override;
  void observe(const State& s) override;
  const PoundingMargin& margin() const { return margin_; }

 private:
  double gap0_ = 0.0;
  bool started_ = false;
  double previous_gap_ = 0.0, before_previous_gap_ = 0.0, previous_t_ = 0.0;
  std::size_t samples_ = 0;
  PoundingMargin margin_;
};

}  // namespace adjoin
