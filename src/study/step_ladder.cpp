#include "step_ladder.hpp"

#include <algorithm>
#include <cmath>

namespace adjoin::detail {

namespace {

// The step factor the tolerance asks for, by the observed error and the order; at most 16x
// finer per rung, and an error that cannot be measured halves the step.
double factor(double error, double tolerance, int order) {
  const double f = std::isfinite(error) && error > 0.0 ? std::pow(0.7 * tolerance / error, 1.0 / order) : 0.5;
  return std::clamp(f, 1.0 / 16.0, 0.5);
}

}  // namespace

LadderOutcome climb_to_tolerance(StepLadder& rungs, double h0, double tolerance, int order) {
  LadderOutcome out;
  double h = h0, previous_h = 0.0;
  constexpr int kRungs = 6;
  for (int rung = 0; rung < kRungs; ++rung) {
    const bool last = rung == kRungs - 1;
    out.ladder.push_back(h);
    rungs.run(h);
    // After the first rung, the previous rung (at least 2h) is a free companion: its estimate
    // decides whether this rung can meet the tolerance and, if not, the next step. Only a rung
    // that looks good pays for the run at 2h, whose estimate is the one reported (the
    // previous rung is too coarse to be trusted for that).
    if (rung > 0 && !last) {
      const double guess = rungs.quick_error(previous_h / h);
      if (std::isfinite(guess) && guess > 2.0 * tolerance) {
        previous_h = h;
        h *= factor(guess, tolerance, order);
        continue;
      }
    }
    const double achieved = rungs.estimate();
    if (achieved <= tolerance || last) {
      out.h = h;
      out.met = achieved <= tolerance;
      return out;
    }
    previous_h = h;
    h *= factor(achieved, tolerance, order);
  }
  return out;  // not reached
}

}  // namespace adjoin::detail
