#pragma once
// The pounding margin: the gap xi(t) = gap0 + x2 - x1 between the blocks. xi <= 0 means the
// structures pound, where the model no longer holds. The minimum is refined between samples
// from the gap's derivatives, with the damper's located switch as a kink (step_extremum in
// extremum.hpp: second order even when the minimum sits on a switch); the first contact
// time is interpolated linearly between the grid points that bracket it.
#include <optional>

#include "adjoin/observe/extremum.hpp"
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
  Sample previous_{};  // the gap, its rate and its acceleration at the previous sample
  PoundingMargin margin_;
};

}  // namespace adjoin
