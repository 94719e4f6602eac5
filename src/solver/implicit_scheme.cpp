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

#include "adjoin/core/errors.hpp"
#include "adjoin/fractional/weights.hpp"
#include "rod_law.hpp"
#include "onset.hpp"
#include "schemes.hpp"
#include "time_loop.hpp"

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

// The scheme as a stepper of the time loop (time_loop.hpp).
class ImplicitStepper {
 public:
  ImplicitStepper(const SolverOptions& options, const Model& model, const GroundMotion& ground)
      : options_(options), model_(model), ground_(ground), h_(options.h), n_steps_(options.steps()),
        rho_(model.rho), mu_(model.mu), damper_(mu_ > 0.0),
        rod1_(model.rod1, 1.0, h_, options.history, weights(options, model.rod1)),
        rod2_(model.rod2, model.eps, h_, options.history, weights(options, model.rod2)),
        k1_(rod1_.stiffness()), k2_(rod2_.stiffness()),
        damped_steps_(damped_steps(options, h_, rho_, k1_, k2_)) {}

  RunInfo info() const { return RunInfo{model_, h_, n_steps_, options_.history}; }
  std::size_t steps() const { return n_steps_; }
  std::size_t history_bytes() const { return rod1_.bytes() + rod2_.bytes(); }

  const State& start() {
    now_ = State{};  // at rest at t = 0
    now_.ag = ground_.ag(0.0);
    now_.a1 = now_.a2 = 0.0;
    rod1_.commit(0.0, 0.0);
    rod2_.commit(0.0, 0.0);
    return now_;
  }

  // The step from t_n to t_{n+1}.
  const State& advance(std::size_t n) {
    // `now` becomes the state the last advance returned only here, after the observers have
    // read it: the state they read is then the one this step wrote field by field, not a
    // fresh copy of it (copying at the end of the step instead made the strong scene with
    // elastic rods, where the step is cheapest, about 10 % slower).
    if (n > 0) now_ = next_;
    State& next = next_;
    next = State{};
    next.t = static_cast<double>(n + 1) * h_;
    next.ag = ground_.ag(next.t);
    const double r1 = rod1_.offset(), r2 = rod2_.offset();
    // The mechanics' weight of the step's end: 1/2 trapezoidal, 1 backward Euler.
    const double th = damped_left_ > 0 ? 1.0 : 0.5;
    if (damped_left_ > 0) --damped_left_;
    const double d1 = 1.0 + th * th * h_ * h_ * k1_;
    const double d2 = 1.0 + th * th * rho_ * h_ * h_ * k2_;
    const double b1 = h_ / d1, b2 = rho_ * h_ / d2, s = b1 + b2;
    const double impulse_ground = h_ * ((1.0 - th) * now_.ag + th * next.ag);

    // Velocities affine in the damper force Q: v1 = a1 - b1 Q, v2 = a2 + b2 Q.
    const double a1 = (now_.v1 + impulse_ground - (1.0 - th) * h_ * now_.f1 -
                       th * h_ * (k1_ * (now_.x1 + (1.0 - th) * h_ * now_.v1) + r1)) / d1;
    const double a2 = (now_.v2 + impulse_ground - (1.0 - th) * rho_ * h_ * now_.f2 -
                       th * rho_ * h_ * (k2_ * (now_.x2 + (1.0 - th) * h_ * now_.v2) + r2)) / d2;

    // The rod forces at t_{n+1} if the step ends with velocities (u1, u2).
    const auto end_forces = [&](double u1, double u2) {
      const double x1 = now_.x1 + h_ * ((1.0 - th) * now_.v1 + th * u1);
      const double x2 = now_.x2 + h_ * ((1.0 - th) * now_.v2 + th * u2);
      return std::pair{k1_ * x1 + r1, k2_ * x2 + r2};
    };
    double q = 0.0;
    double kink = 0.0;  // a slip ended inside this step (into stick, or turned): see below
    if (damper_) {
      const double stuck_v = (a1 * b2 + a2 * b1) / s;  // the one velocity if the blocks stick
      // The stick force at the fraction theta of a step spent slipping on in the current
      // direction: the rod forces interpolated between t_n and that slip's end.
      const auto stick_force_at = [&](double theta) {
        const double d = now_.phase == Phase::slip_right ? 1.0 : -1.0;
        const auto [f1e, f2e] = end_forces(a1 - b1 * mu_ * d, a2 + b2 * mu_ * d);
        return stick_force(model_, now_.f1 + theta * (f1e - now_.f1), now_.f2 + theta * (f2e - now_.f2));
      };
      const Relay r = resolve_relay(a1 - a2, s, mu_, now_.phase, now_.v1 - now_.v2, n == 0, previous_same_slip_,
                                    previous_w_, stick_force_at);
      if (r.phase == Phase::stick && now_.phase != Phase::stick) {
        stick_start_t_ = now_.t + r.theta * h_;
        stick_start_q_ = stick_force_at(r.theta);
      }
      q = r.q;
      next.phase = r.phase;
      if (n > 0 && th == 0.5 && now_.phase != Phase::stick && r.phase != now_.phase) {
        const double d = now_.phase == Phase::slip_right ? 1.0 : -1.0;
        const double q_after = r.phase == Phase::stick ? stick_force_at(r.theta) : -mu_ * d;
        kink = 0.5 * h_ * h_ * r.theta * (1.0 - r.theta) * (q_after - mu_ * d);
      }
      double onset = -1.0;  // where a stick -> slip happens in this step, as a fraction of it
      if (now_.phase == Phase::stick && n > 0 && std::abs(now_stick_q_) > mu_) {
        // A stick that began inside the last step (from a reversal whose crossing lay in the
        // cone) and whose stick force left the cone before t_n: the blocks slip already. The
        // onset lies between the stick's start and t_n, on the line between the stick forces
        // there; this step slips throughout.
        const double d = now_stick_q_ > 0.0 ? 1.0 : -1.0;
        if ((a1 - a2 - s * mu_ * d) * d > 0.0) {
          q = mu_ * d;
          next.phase = slip_towards(d);
          if (stick_start_t_ > now_.t - h_) {
            const double f = (mu_ * d - stick_start_q_) / (now_stick_q_ - stick_start_q_);
            onset = (stick_start_t_ + clamp01(f) * (now_.t - stick_start_t_) - now_.t) / h_;
          } else {
            // A longer stick whose last step was (barely) too short to slip: the onset lies in
            // that step.
            const auto [f1e, f2e] = end_forces(stuck_v, stuck_v);
            onset = locate_onset(mu_ * d, previous_stuck_, previous_q_, now_stick_q_, stick_force(model_, f1e, f2e), -1.0);
            onset = std::min(onset, 0.0);
          }
        }
      } else if (now_.phase == Phase::stick && n > 0) {
        // Stuck at t_n (so |stick force| <= mu there). The blocks slip from where the stick
        // force, had they stayed stuck, leaves the cone; decided at the grid point t_{n+1}
        // (not on the step's average force, which would snap onsets to the grid or put them
        // in the step before) and located on a parabola of grid stick forces.
        const auto [f1e, f2e] = end_forces(stuck_v, stuck_v);
        const double q_end = stick_force(model_, f1e, f2e);
        if (std::abs(q_end) > mu_) {
          const double d = q_end > 0.0 ? 1.0 : -1.0;
          const double theta = locate_onset(mu_ * d, previous_stuck_, previous_q_, now_stick_q_, q_end, 0.0);
          // The step's average force: the stick force (about linear) up to the onset, the
          // limit after it.
          const double q_slip = theta * 0.5 * (std::clamp(now_stick_q_, -mu_, mu_) + mu_ * d) + (1.0 - theta) * mu_ * d;
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
      if (options_.locate_switches && next.phase != now_.phase && n > 0) {
        next.t_switch = now_.t + (now_.phase == Phase::stick ? onset : r.theta) * h_;
      }
    } else {
      next.v1 = a1;
      next.v2 = a2;
      const double w = a1 - a2;
      next.phase = w > 0.0 ? Phase::slip_right : (w < 0.0 ? Phase::slip_left : Phase::stick);
      // Without a damper a "phase" is the sign of the relative velocity: its changes are
      // located where w crosses zero (linear interpolation, second order).
      const double w_now = now_.v1 - now_.v2;
      if (options_.locate_switches && next.phase != now_.phase && n > 0 && w_now != w)
        next.t_switch = now_.t + clamp01(w_now / (w_now - w)) * h_;
    }

    next.x1 = now_.x1 + h_ * ((1.0 - th) * now_.v1 + th * next.v1);
    next.x2 = now_.x2 + h_ * ((1.0 - th) * now_.v2 + th * next.v2);
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
      next.x2 -= rho_ * kink;
    }
    if (damper_ && next.phase != now_.phase && n > 0) damped_left_ = damped_steps_;
    next.f1 = k1_ * next.x1 + r1;
    next.f2 = k2_ * next.x2 + r2;
    // The reported damper force is its value at t_{n+1} (not the step's average Q, which is
    // the force half a step earlier): the stick force while stuck, the limit while slipping.
    // A stick that began inside this step (at a reversal) can end in the next one with its
    // grid stick force already beyond mu: the damper slips there already (the next step
    // locates the onset before t_{n+1}), and its force is the limit. Clamping reports exactly
    // that (and keeps |q| <= mu).
    const double next_stick_q = stick_force(model_, next.f1, next.f2);
    if (damper_)
      next.q = next.phase == Phase::stick ? std::clamp(next_stick_q, -mu_, mu_)
                                          : (next.phase == Phase::slip_right ? mu_ : -mu_);
    next.a1 = -next.f1 - next.q;
    next.a2 = rho_ * (next.q - next.f2);
    if (!(std::abs(next.x1) < kRunaway && std::abs(next.x2) < kRunaway && std::abs(next.f1) < kRunaway &&
          std::abs(next.f2) < kRunaway && std::isfinite(next.v1 + next.v2))) {
      runaway(next);
    }
    rod1_.commit(next.x1, next.f1);
    rod2_.commit(next.x2, next.f2);

    previous_stuck_ = now_.phase == Phase::stick && n > 0;
    previous_same_slip_ = n > 0 && now_.phase != Phase::stick && next.phase == now_.phase;
    previous_w_ = now_.v1 - now_.v2;
    previous_q_ = now_stick_q_;
    now_stick_q_ = next_stick_q;
    return next_;
  }

 private:
  [[noreturn]] void runaway(const State& next) const {
    std::ostringstream m;
    m << "the response became " << (std::isfinite(next.x1 + next.x2 + next.f1 + next.f2) ? "larger than 1e12" : "non-finite")
      << " at t = " << next.t << " with the " << to_string(options_.scheme) << " scheme at solver.h = " << h_
      << "; check the ground motion's scale (ground.*) and the rods, or reduce solver.h";
    throw NumericalError(m.str(), next.t);
  }
  static std::vector<double> weights(const SolverOptions& options, const Rod& rod) {
    if (rod.elastic) return std::vector<double>{};
    const std::size_t n = options.steps() + 2;
    return options.scheme != Scheme::implicit_gl ? bdf2_weights(rod.order, n) : grunwald_letnikov_weights(rod.order, n);
  }
  // Backward-Euler steps after a switch (see the header): always for implicit-damped; for the
  // other implicit schemes when the stiffest mode is not resolved by the step.
  static int damped_steps(const SolverOptions& options, double h, double rho, double k1, double k2) {
    const double omega_h = h * std::sqrt(std::max({k1, rho * k2, (k1 + rho * k2) / (1.0 + rho)}));
    return options.scheme == Scheme::implicit_damped || omega_h > kResolvedOmegaH ? 1 : 0;
  }

  const SolverOptions& options_;
  const Model& model_;
  const GroundMotion& ground_;
  const double h_;
  const std::size_t n_steps_;
  const double rho_, mu_;
  const bool damper_;
  RodLaw rod1_, rod2_;
  const double k1_, k2_;
  const int damped_steps_;
  int damped_left_ = 0;

  State now_, next_;
  bool previous_stuck_ = false;  // the grid point before `now` was stuck, and its stick force
  double previous_q_ = 0.0;
  bool previous_same_slip_ = false;  // the grid point before `now` slipped as `now` does, and its w
  double previous_w_ = 0.0;
  double now_stick_q_ = 0.0;     // the stick force at `now` (unclamped; = now.q while inside the cone)
  double stick_start_t_ = 0.0, stick_start_q_ = 0.0;  // where the last stick began, and its force
};

}  // namespace

LoopResult run_implicit_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                               Observer& observer) {
  return integrate<ImplicitStepper>(observer, options, model, ground);
}

}  // namespace adjoin::detail
