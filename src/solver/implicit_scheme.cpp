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
// h (no explicit stability bound). But it does not damp modes the step does not resolve
// (omega h >> 1): a switch (a jump of the damper force) excites the stiffest mode, which then
// rings with undiminished amplitude and can drive the relative velocity through zero again
// and again, i.e. spurious switches (chatter). So the step after a switch is taken with
// backward-Euler mechanics (theta = 1 in x_{n+1} = x_n + h((1 - theta) v_n + theta v_{n+1})
// and the same for v), which damps a mode by 1/sqrt(1 + (omega h)^2) in one step: the
// restart that circuit simulators make after every breakpoint. One first-order step per
// switch keeps the scheme second order (finitely many O(h^2) local errors), at the price of
// larger error constants on the quantities near a switch; "implicit" does it only when the
// stiffest mode is unresolved (omega h > kResolvedOmegaH), "implicit-damped" after every
// switch. The reported q at t_{n+1} is the damper force at that
// instant (the stick force (rho f2 - f1)/(rho + 1) while stuck, +-mu while slipping), not the
// step's average Q, so q, the accelerations and the switching instants located from them are
// second order.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <sstream>

#include "adjoin/errors.hpp"
#include "adjoin/fractional/weights.hpp"
#include "rod_law.hpp"
#include "onset.hpp"
#include "schemes.hpp"

namespace adjoin::detail {
namespace {

constexpr double kRunaway = 1e12;
// Modes with omega h above this are not resolved by the step: trapezoidal mechanics passes
// them undamped (its amplification tends to -1), so what a switch excites rings on.
constexpr double kResolvedOmegaH = 1.0;

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
// From stick: stuck on (the caller decides an onset from the stick force at the step's end);
// at the first step, from rest, the closed-form relay (stick if |w0| <= mu s).
// From slip in direction d: if slipping on would not bring w to zero, Q = mu d. Otherwise w
// reaches zero at the fraction theta of the step (linear in time). What happens next is
// decided by the stick force at that instant, `stick_force_at(theta)` (from the state
// interpolated along the slip), as the physics decides it: the blocks stick if it lies in
// the cone [-mu, mu], and slip the other way if not. (Deciding from the force averaged over
// the rest of the step, which divides by 1 - theta, made spurious sticks shorter than a step
// at near-threshold reversals.) Splitting the step's impulse at theta keeps reversals second
// order.
template <class StickForceAt>
Relay resolve_relay(double w0, double s, double mu, Phase before, double w_before, bool first,
                    bool have_prev, double w_prev, const StickForceAt& stick_force_at) {
  if (first) {
    if (std::abs(w0) <= mu * s) return {w0 / s, Phase::stick, 1.0};
    return {w0 > 0.0 ? mu : -mu, slip_towards(w0), 0.0};
  }
  if (before == Phase::stick) return {w0 / s, Phase::stick, 1.0};  // the caller checks the end
  const double d = before == Phase::slip_right ? 1.0 : -1.0;
  const double w_end = w0 - s * mu * d;  // slipping on for the whole step
  if (w_end * d > 0.0) return {mu * d, before, 1.0};
  // The crossing on the parabola through the relative velocities at t_{n-1}, t_n and the
  // slip's end (when t_{n-1} was in this slip too), else on the line: a line's error,
  // w'' theta (1 - theta) h^2 / (2 w'), depends on where in the step the crossing falls, and
  // made the instants' errors irregular in h (no estimate from two steps could follow them).
  const double theta = have_prev ? locate_onset(0.0, true, w_prev, w_before, w_end, 0.0)
                       : (w_before != w_end ? clamp01(w_before / (w_before - w_end)) : 1.0);
  if (std::abs(stick_force_at(theta)) <= mu) return {w0 / s, Phase::stick, theta};
  return {mu * d * (2.0 * theta - 1.0), d > 0.0 ? Phase::slip_left : Phase::slip_right, theta};
}

}  // namespace

std::size_t run_implicit_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                         Observer& observer) {
  const double h = options.h;
  const std::size_t n_steps = options.steps();
  const double rho = model.rho, mu = model.mu;
  const bool damper = mu > 0.0;
  const bool second_order = options.scheme != Scheme::implicit_gl;

  auto weights = [&](const Rod& rod) {
    if (rod.elastic) return std::vector<double>{};
    return second_order ? bdf2_weights(rod.order, n_steps + 2) : grunwald_letnikov_weights(rod.order, n_steps + 2);
  };
  RodLaw rod1(model.rod1, 1.0, h, options.history, weights(model.rod1));
  RodLaw rod2(model.rod2, model.eps, h, options.history, weights(model.rod2));
  const double k1 = rod1.stiffness(), k2 = rod2.stiffness();
  // Backward-Euler steps after a switch (see the header): always for implicit-damped; for the
  // other implicit schemes when the stiffest mode is not resolved by the step.
  const double omega_h = h * std::sqrt(std::max({k1, rho * k2, (k1 + rho * k2) / (1.0 + rho)}));
  const int damped_steps =
      options.scheme == Scheme::implicit_damped || omega_h > kResolvedOmegaH ? 1 : 0;
  int damped_left = 0;

  observer.begin(RunInfo{model, h, n_steps});

  State now;  // at rest at t = 0
  now.ag = ground.ag(0.0);
  now.a1 = now.a2 = 0.0;
  rod1.commit(0.0, 0.0);
  rod2.commit(0.0, 0.0);
  observer.observe(now);
  bool previous_stuck = false;  // the grid point before `now` was stuck, and its stick force
  double previous_q = 0.0;
  bool previous_same_slip = false;  // the grid point before `now` slipped as `now` does, and its w
  double previous_w = 0.0;
  double now_stick_q = 0.0;     // the stick force at `now` (unclamped; = now.q while inside the cone)
  double stick_start_t = 0.0, stick_start_q = 0.0;  // where the last stick began, and its force

  for (std::size_t n = 0; n < n_steps; ++n) {
    State next;
    next.t = static_cast<double>(n + 1) * h;
    next.ag = ground.ag(next.t);
    const double r1 = rod1.offset(), r2 = rod2.offset();
    // The mechanics' weight of the step's end: 1/2 trapezoidal, 1 backward Euler.
    const double th = damped_left > 0 ? 1.0 : 0.5;
    if (damped_left > 0) --damped_left;
    const double d1 = 1.0 + th * th * h * h * k1;
    const double d2 = 1.0 + th * th * rho * h * h * k2;
    const double b1 = h / d1, b2 = rho * h / d2, s = b1 + b2;
    const double impulse_ground = h * ((1.0 - th) * now.ag + th * next.ag);

    // Velocities affine in the damper force Q: v1 = a1 - b1 Q, v2 = a2 + b2 Q.
    const double a1 = (now.v1 + impulse_ground - (1.0 - th) * h * now.f1 -
                       th * h * (k1 * (now.x1 + (1.0 - th) * h * now.v1) + r1)) / d1;
    const double a2 = (now.v2 + impulse_ground - (1.0 - th) * rho * h * now.f2 -
                       th * rho * h * (k2 * (now.x2 + (1.0 - th) * h * now.v2) + r2)) / d2;

    // The rod forces at t_{n+1} if the step ends with velocities (u1, u2).
    const auto end_forces = [&](double u1, double u2) {
      const double x1 = now.x1 + h * ((1.0 - th) * now.v1 + th * u1);
      const double x2 = now.x2 + h * ((1.0 - th) * now.v2 + th * u2);
      return std::pair{k1 * x1 + r1, k2 * x2 + r2};
    };
    double q = 0.0;
    double kink = 0.0;  // a slip ended inside this step (into stick, or turned): see below
    if (damper) {
      const double stuck_v = (a1 * b2 + a2 * b1) / s;  // the one velocity if the blocks stick
      // The stick force at the fraction theta of a step spent slipping on in the current
      // direction: the rod forces interpolated between t_n and that slip's end.
      const auto stick_force_at = [&](double theta) {
        const double d = now.phase == Phase::slip_right ? 1.0 : -1.0;
        const auto [f1e, f2e] = end_forces(a1 - b1 * mu * d, a2 + b2 * mu * d);
        return stick_force(model, now.f1 + theta * (f1e - now.f1), now.f2 + theta * (f2e - now.f2));
      };
      const Relay r = resolve_relay(a1 - a2, s, mu, now.phase, now.v1 - now.v2, n == 0, previous_same_slip,
                                    previous_w, stick_force_at);
      if (r.phase == Phase::stick && now.phase != Phase::stick) {
        stick_start_t = now.t + r.theta * h;
        stick_start_q = stick_force_at(r.theta);
      }
      q = r.q;
      next.phase = r.phase;
      if (n > 0 && th == 0.5 && now.phase != Phase::stick && r.phase != now.phase) {
        const double d = now.phase == Phase::slip_right ? 1.0 : -1.0;
        const double q_after = r.phase == Phase::stick ? stick_force_at(r.theta) : -mu * d;
        kink = 0.5 * h * h * r.theta * (1.0 - r.theta) * (q_after - mu * d);
      }
      double onset = -1.0;  // where a stick -> slip happens in this step, as a fraction of it
      if (now.phase == Phase::stick && n > 0 && std::abs(now_stick_q) > mu) {
        // A stick that began inside the last step (from a reversal whose crossing lay in the
        // cone) and whose stick force left the cone before t_n: the blocks slip already. The
        // onset lies between the stick's start and t_n, on the line between the stick forces
        // there; this step slips throughout.
        const double d = now_stick_q > 0.0 ? 1.0 : -1.0;
        if ((a1 - a2 - s * mu * d) * d > 0.0) {
          q = mu * d;
          next.phase = slip_towards(d);
          if (stick_start_t > now.t - h) {
            const double f = (mu * d - stick_start_q) / (now_stick_q - stick_start_q);
            onset = (stick_start_t + clamp01(f) * (now.t - stick_start_t) - now.t) / h;
          } else {
            // A longer stick whose last step was (barely) too short to slip: the onset lies in
            // that step.
            const auto [f1e, f2e] = end_forces(stuck_v, stuck_v);
            onset = locate_onset(mu * d, previous_stuck, previous_q, now_stick_q, stick_force(model, f1e, f2e), -1.0);
            onset = std::min(onset, 0.0);
          }
        }
      } else if (now.phase == Phase::stick && n > 0) {
        // Stuck at t_n (so |stick force| <= mu there). The blocks slip from where the stick
        // force, had they stayed stuck, leaves the cone; decided at the grid point t_{n+1}
        // (not on the step's average force, which would snap onsets to the grid or put them
        // in the step before) and located on a parabola of grid stick forces.
        const auto [f1e, f2e] = end_forces(stuck_v, stuck_v);
        const double q_end = stick_force(model, f1e, f2e);
        if (std::abs(q_end) > mu) {
          const double d = q_end > 0.0 ? 1.0 : -1.0;
          const double theta = locate_onset(mu * d, previous_stuck, previous_q, now_stick_q, q_end, 0.0);
          // The step's average force: the stick force (about linear) up to the onset, the
          // limit after it.
          const double q_slip = theta * 0.5 * (std::clamp(now_stick_q, -mu, mu) + mu * d) + (1.0 - theta) * mu * d;
          if ((a1 - a2 - s * q_slip) * d > 0.0) {
            q = q_slip;
            next.phase = slip_towards(d);
            onset = theta;
          }
        }
      }
      if (next.phase == Phase::stick) {
        next.v1 = next.v2 = stuck_v;  // exactly one velocity
      } else {
        next.v1 = a1 - b1 * q;
        next.v2 = a2 + b2 * q;
      }
      if (options.locate_switches && next.phase != now.phase && n > 0) {
        next.t_switch = now.t + (now.phase == Phase::stick ? onset : r.theta) * h;
      }
    } else {
      next.v1 = a1;
      next.v2 = a2;
      const double w = a1 - a2;
      next.phase = w > 0.0 ? Phase::slip_right : (w < 0.0 ? Phase::slip_left : Phase::stick);
      // Without a damper a "phase" is the sign of the relative velocity: its changes are
      // located where w crosses zero (linear interpolation, second order).
      const double w_now = now.v1 - now.v2;
      if (options.locate_switches && next.phase != now.phase && n > 0 && w_now != w)
        next.t_switch = now.t + clamp01(w_now / (w_now - w)) * h;
    }

    next.x1 = now.x1 + h * ((1.0 - th) * now.v1 + th * next.v1);
    next.x2 = now.x2 + h * ((1.0 - th) * now.v2 + th * next.v2);
    if (kink != 0.0) {
      // Where a slip ends inside the step, the damper force jumps by dq (from +-mu to the
      // stick force, or to -+mu), so each block's velocity has a kink there, which the
      // trapezoidal rule above integrates as if the velocity were smooth: an O(h^2) local
      // error, -(jump of x'') h^2 theta (1 - theta) / 2, whose size depends on where in the
      // step the slip ended. Into a stick the stroke x1 - x2 is then frozen, and the stick
      // force that decides the next onset carries the error on; near a grazing onset (the
      // stick force barely reaching mu) the instants' errors were irregular in h, which
      // defeats an error estimate from two steps. The kink's part is integrated exactly here
      // (x1'' jumps by -dq, x2'' by rho dq; the mass-weighted mean is untouched, as the damper
      // does no work on it). A stick -> slip onset needs nothing: the force reaches mu
      // continuously there, no kink.
      next.x1 += kink;
      next.x2 -= rho * kink;
    }
    if (damper && next.phase != now.phase && n > 0) damped_left = damped_steps;
    next.f1 = k1 * next.x1 + r1;
    next.f2 = k2 * next.x2 + r2;
    // The reported damper force is its value at t_{n+1} (not the step's average Q, which is
    // the force half a step earlier): the stick force while stuck, the limit while slipping.
    // A stick that began inside this step (at a reversal) can end in the next one with its
    // grid stick force already beyond mu: the damper slips there already (the next step
    // locates the onset before t_{n+1}), and its force is the limit. Clamping reports exactly
    // that (and keeps |q| <= mu).
    const double next_stick_q = stick_force(model, next.f1, next.f2);
    if (damper)
      next.q = next.phase == Phase::stick ? std::clamp(next_stick_q, -mu, mu)
                                          : (next.phase == Phase::slip_right ? mu : -mu);
    next.a1 = -next.f1 - next.q;
    next.a2 = rho * (next.q - next.f2);
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
    previous_stuck = now.phase == Phase::stick && n > 0;
    previous_same_slip = n > 0 && now.phase != Phase::stick && next.phase == now.phase;
    previous_w = now.v1 - now.v2;
    previous_q = now_stick_q;
    now_stick_q = next_stick_q;
    now = next;
  }
  observer.end();
  return rod1.bytes() + rod2.bytes();
}

}  // namespace adjoin::detail
