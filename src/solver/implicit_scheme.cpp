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
// Q is the damper force averaged over the step (an impulse / h, as in Moreau's time-stepping),
// so a phase change inside the step needs no special treatment. Eliminating x and f, each
// velocity is affine in Q: v1 = A1 - B1 Q, v2 = A2 + B2 Q with B1, B2 > 0, hence the relative
// velocity w = w0 - S Q with S = B1 + B2, and the relay has the closed-form solution
//
//     |w0| <= mu S :  Q = w0 / S, w = 0            (stick: exactly, both blocks one velocity)
//     otherwise    :  Q = mu sign(w0), w = w0 - S Q  (slip in the direction of w0)
//
// Trapezoidal mechanics is A-stable and the rods are implicit, so the step is stable for any
// h (no explicit stability bound). Reported q at t_{n+1} is the step's Q; in the one step of
// a slip reversal it is the average of the force that flips from one limit to the other.
#include <cmath>
#include <limits>
#include <optional>
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

}  // namespace

void run_implicit_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
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
  std::optional<State> pending;  // the last state computed, not yet reported
  Phase emitted_phase = now.phase;

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
      const double w0 = a1 - a2;
      if (std::abs(w0) <= mu * s) {
        q = w0 / s;
        next.phase = Phase::stick;
        next.v1 = next.v2 = (a1 * b2 + a2 * b1) / s;  // exactly one velocity
      } else {
        q = w0 > 0.0 ? mu : -mu;
        next.phase = slip_towards(w0);
        next.v1 = a1 - b1 * q;
        next.v2 = a2 + b2 * q;
      }
      // Where inside the step did the phase change? Linear interpolation of what crossed.
      if (options.locate_switches && next.phase != now.phase && n > 0) {
        double theta = 1.0;
        const double w_now = now.v1 - now.v2;
        if (now.phase == Phase::stick) {
          // The force needed to stick went from now.q (inside the cone) to w0/s (outside).
          const double target = w0 > 0.0 ? mu : -mu, needed = w0 / s;
          theta = clamp01((target - now.q) / (needed - now.q));
        } else {
          // The relative velocity went from w_now to zero: towards its slip-continued value
          // (slip -> stick) or to its new value (slip reversal).
          const double w_end = next.phase == Phase::stick ? w0 - s * (w_now > 0.0 ? mu : -mu) : next.v1 - next.v2;
          theta = w_now != w_end ? clamp01(w_now / (w_now - w_end)) : 1.0;
        }
        next.t_switch = now.t + theta * h;
      }
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

    // A slip reversal passes through w = 0, and the relay may hold the blocks for the one step
    // in which w crosses zero even though the stick force is already beyond mu (the next step
    // slips the other way). That is not a stick phase: relabel such a single step as part of
    // the reversal, switching at the located zero crossing. Hence one step of delay.
    if (pending && pending->phase == Phase::stick && emitted_phase != Phase::stick &&
        next.phase != Phase::stick && next.phase != emitted_phase && n >= 2) {
      pending->phase = next.phase;
      next.t_switch = std::numeric_limits<double>::quiet_NaN();
    }
    if (pending) {
      observer.observe(*pending);
      emitted_phase = pending->phase;
    }
    pending = next;
    now = next;
  }
  if (pending) observer.observe(*pending);
  observer.end();
}

}  // namespace adjoin::detail
