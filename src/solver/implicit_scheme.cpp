// The implicit schemes ("implicit": BDF2 convolution quadrature; "implicit-gl": Grünwald–
// Letnikov). One step from t_n to t_{n+1}:
//
//   rods:       f_{n+1} = K x_{n+1} + r_{n+1}      (RodLaw: K the effective stiffness, r the
//                                                   history, both known before the step)
//   blocks:     x_{n+1} = x_n + h/2 (v_n + v_{n+1})                     (trapezoidal rule)
//               v1_{n+1} = v1_n + h/2 (ag_n + ag_{n+1} - f1_n - f1_{n+1}) - h Q
//               v2_{n+1} = v2_n + h/2 (ag_n + ag_{n+1}) - rho h/2 (f2_n + f2_{n+1}) + rho h Q
//   damper:     Q in mu Sign(v1_{n+1} - v2_{n+1})                       (relay)
//
// Q is the damper force averaged over the step (an impulse / h, as in Moreau's time-stepping).
// Eliminating x and f, each velocity is affine in Q: v1 = A1 - B1 Q, v2 = A2 + B2 Q with
// B1, B2 > 0, hence the relative velocity w = w0 - S Q with S = B1 + B2, and the relay has a
// closed-form solution (resolve_relay below): in its simplest form
//
//     |w0| <= mu S :  Q = w0 / S, w = 0            (stick: exactly, both blocks one velocity)
//     otherwise    :  Q = mu sign(w0), w = w0 - S Q  (slip in the direction of w0)
//
// refined for a slip whose relative velocity reaches zero inside the step, where the impulse
// is split at the located zero crossing.
//
// Trapezoidal mechanics is A-stable and the rods are implicit, so the step is stable for any
// h (no explicit stability bound). Reported q at t_{n+1} is the step's Q; in the step of a
// slip reversal it is the average of the force that flips from one limit to the other.
#include <cmath>
#include <limits>
#include <sstream>

#include "adjoin/errors.hpp"
#include "adjoin/fractional/weights.hpp"
#include "rod_law.hpp"
#include "schemes.hpp"

namespace adjoin::detail {
namespace {

constexpr double kRunaway = 1e12;

Phase slip_towards(double w) { return w > 0.0 ? Phase::slip_right : Phase::slip_left; }

double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

struct Relay {
  double q;      // the damper force averaged over the step
  Phase phase;   // at the end of the step
  double theta;  // fraction of the step before the phase changed (1 if it did not)
};

// The damper over one step, given the free relative velocity w0 (what w_{n+1} would be with
// Q = 0) and w_{n+1} = w0 - s Q.
//
// From stick: the closed-form relay (stick if |w0| <= mu s).
// From slip in direction d: if slipping on would not bring w to zero, Q = mu d. Otherwise w
// reaches zero at the fraction theta of the step (linear in time), and for the rest of the
// step the blocks stick if the force that takes, (w0/s - mu d theta)/(1 - theta), is within
// the cone, or slip the other way. Splitting the step's impulse at theta (instead of giving
// the whole step one limit) keeps reversals second order.
Relay resolve_relay(double w0, double s, double mu, Phase before, double w_before, double q_before, bool first) {
  if (before == Phase::stick || first) {
    if (std::abs(w0) <= mu * s) return {w0 / s, Phase::stick, 1.0};
    const double target = w0 > 0.0 ? mu : -mu, needed = w0 / s;
    // The force needed to stick went from q_before (inside the cone) to `needed` (outside).
    // Both are step averages, i.e. values at the middle of their steps, half a step apart.
    const double crossing = clamp01((target - q_before) / (needed - q_before));
    return {target, slip_towards(w0), clamp01(crossing - 0.5)};
  }
  const double d = before == Phase::slip_right ? 1.0 : -1.0;
  const double w_end = w0 - s * mu * d;  // slipping on for the whole step
  if (w_end * d > 0.0) return {mu * d, before, 1.0};
  const double theta = w_before != w_end ? clamp01(w_before / (w_before - w_end)) : 1.0;
  if (std::abs(w0 / s - mu * d * theta) <= mu * (1.0 - theta)) return {w0 / s, Phase::stick, theta};
  return {mu * d * (2.0 * theta - 1.0), d > 0.0 ? Phase::slip_left : Phase::slip_right, theta};
}

}  // namespace

std::size_t run_implicit_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                         Observer& observer) {
  const double h = options.h;
  const std::size_t n_steps = options.steps();
  const double rho = model.rho, mu = model.mu;
  const bool damper = mu > 0.0;
  const bool second_order = options.scheme == Scheme::implicit;

  auto weights = [&](const Rod& rod) {
    if (rod.elastic) return std::vector<double>{};
    return second_order ? bdf2_weights(rod.order, n_steps + 2) : grunwald_letnikov_weights(rod.order, n_steps + 2);
  };
  RodLaw rod1(model.rod1, 1.0, h, options.history, weights(model.rod1));
  RodLaw rod2(model.rod2, model.eps, h, options.history, weights(model.rod2));
  const double k1 = rod1.stiffness(), k2 = rod2.stiffness();
  const double d1 = 1.0 + 0.25 * h * h * k1;
  const double d2 = 1.0 + 0.25 * rho * h * h * k2;
  const double b1 = h / d1, b2 = rho * h / d2, s = b1 + b2;

  observer.begin(RunInfo{model, h, n_steps});

  State now;  // at rest at t = 0
  now.ag = ground.ag(0.0);
  now.a1 = now.a2 = 0.0;
  rod1.commit(0.0, 0.0);
  rod2.commit(0.0, 0.0);
  observer.observe(now);

  for (std::size_t n = 0; n < n_steps; ++n) {
    State next;
    next.t = static_cast<double>(n + 1) * h;
    next.ag = ground.ag(next.t);
    const double r1 = rod1.offset(), r2 = rod2.offset();
    const double impulse_ground = 0.5 * h * (now.ag + next.ag);

    // Velocities affine in the damper force Q: v1 = a1 - b1 Q, v2 = a2 + b2 Q.
    const double a1 = (now.v1 + impulse_ground - 0.5 * h * now.f1 - 0.5 * h * (k1 * (now.x1 + 0.5 * h * now.v1) + r1)) / d1;
    const double a2 = (now.v2 + impulse_ground - 0.5 * rho * h * now.f2 -
                       0.5 * rho * h * (k2 * (now.x2 + 0.5 * h * now.v2) + r2)) / d2;

    double q = 0.0;
    if (damper) {
      const Relay r = resolve_relay(a1 - a2, s, mu, now.phase, now.v1 - now.v2, now.q, n == 0);
      q = r.q;
      next.phase = r.phase;
      if (r.phase == Phase::stick) {
        next.v1 = next.v2 = (a1 * b2 + a2 * b1) / s;  // exactly one velocity
      } else {
        next.v1 = a1 - b1 * q;
        next.v2 = a2 + b2 * q;
      }
      if (options.locate_switches && next.phase != now.phase && n > 0) next.t_switch = now.t + r.theta * h;
    } else {
      next.v1 = a1;
      next.v2 = a2;
      const double w = a1 - a2;
      next.phase = w > 0.0 ? Phase::slip_right : (w < 0.0 ? Phase::slip_left : Phase::stick);
    }

    next.x1 = now.x1 + 0.5 * h * (now.v1 + next.v1);
    next.x2 = now.x2 + 0.5 * h * (now.v2 + next.v2);
    next.f1 = k1 * next.x1 + r1;
    next.f2 = k2 * next.x2 + r2;
    next.q = q;
    next.a1 = -next.f1 - q;
    next.a2 = rho * (q - next.f2);
    if (!(std::abs(next.x1) < kRunaway && std::abs(next.x2) < kRunaway && std::abs(next.f1) < kRunaway &&
          std::abs(next.f2) < kRunaway && std::isfinite(next.v1 + next.v2))) {
      std::ostringstream m;
      m << "the response became " << (std::isfinite(next.x1 + next.x2 + next.f1 + next.f2) ? "larger than 1e12" : "non-finite")
        << " at t = " << next.t << " with the " << to_string(options.scheme) << " scheme at solver.h = " << h
        << "; check the ground motion's scale (ground.*) and the rods, or reduce solver.h";
      throw NumericalError(m.str(), next.t);
    }
    rod1.commit(next.x1, next.f1);
    rod2.commit(next.x2, next.f2);

    observer.observe(next);
    now = next;
  }
  observer.end();
  return rod1.bytes() + rod2.bytes();
}

}  // namespace adjoin::detail
