#pragma once
// The ladder of run_to_tolerance (study/error_estimate.hpp states the rule), shared by the
// two-block runs and the building runs: only how a rung is run and estimated differs.
#include <vector>

namespace adjoin::detail {

class StepLadder {
 public:
  virtual ~StepLadder() = default;
  // Runs the rung at step h; the rung run before it becomes the previous one.
  virtual void run(double h) = 0;
  // The last rung's largest relative peak error estimated against the previous rung, whose
  // step is `ratio` times coarser (free: no run); +inf when it cannot be estimated.
  virtual double quick_error(double ratio) = 0;
  // The last rung's own estimate (its companion at about 2h), kept as the one reported; its
  // largest relative peak error, +inf when not available.
  virtual double estimate() = 0;
};

struct LadderOutcome {
  std::vector<double> ladder;  // the steps tried, in order (the last is h)
  double h = 0.0;
  bool met = false;
};

// From the first step h0: at most six rungs, each predicted from the observed error and the
// order p, h <- h (0.7 tol / E)^(1/p) clamped to [1/16, 1/2]. The last rung run is the one
// kept (its estimate() was the last called).
LadderOutcome climb_to_tolerance(StepLadder& rungs, double h0, double tolerance, int order);

}  // namespace adjoin::detail
