#include "contact_step.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "adjoin/core/errors.hpp"

namespace adjoin::detail {
namespace {

using structure::ContactModel;

// The pair's state in contact with the step's running integrals: penetration, its rate, the
// impulse I, the moment J = int (h - tau) p and the work W = int p w.
struct Y {
  double delta = 0.0, w = 0.0, impulse = 0.0, moment = 0.0, work = 0.0;
  Y operator+(const Y& o) const { return {delta + o.delta, w + o.w, impulse + o.impulse, moment + o.moment, work + o.work}; }
  Y operator*(double s) const { return {delta * s, w * s, impulse * s, moment * s, work * s}; }
};

// The first instant in [0, r] at which the parabola d + w s + a s^2 / 2 touches 0 while
// rising (a touch), or r + 1 if none. d > 0 (overlapping) with w > 0 touches at once. Written
// to avoid cancellation.
double first_touch(double d, double w, double a, double r) {
  const double none = r + 1.0;
  if (d >= 0.0) {
    if (w > 0.0 || (w == 0.0 && a > 0.0)) return 0.0;
    if (d == 0.0 && w < 0.0 && a > 0.0 && -2.0 * w / a <= r) return -2.0 * w / a;
    return none;
  }
  double best = none;
  auto consider = [&](double s) {
    if (s > 0.0 && s <= r && w + a * s > 0.0 && s < best) best = s;
  };
  if (a == 0.0) {
    if (w > 0.0) consider(-d / w);
    return best;
  }
  const double disc = w * w - 2.0 * a * d;
  if (disc < 0.0) return none;
  const double sq = std::sqrt(disc);
  const double qq = -(w + std::copysign(sq, w));  // roots of (a/2) s^2 + w s + d: qq / a and 2 d / qq
  if (qq != 0.0) {
    consider(qq / a);
    consider(2.0 * d / qq);
  } else {
    consider(std::sqrt(-2.0 * d / a));
  }
  return best;
}

}  // namespace

struct ContactStepper::Flow {
  const ContactStepper& c;
  double a, kappa, h, v0;
  // The force (never NaN: delta <= 0 gives 0 for the Hertz-type laws).
  double p(double delta, double w) const { return c.force(delta, w, v0); }
  Y rate(double tau, const Y& y) const {
    const double f = p(y.delta, y.w);
    return {y.w, a - kappa * f, f, (h - tau) * f, f * y.w};
  }
  // Separation: the penetration returning to 0 (laws that do not pull give 0 force before it).
  double apart(const Y& y) const { return y.delta; }
  // The force's rate along the flow, by a central difference over a small time eps (only its
  // sign is used: the maximum is then located on the force itself).
  double force_rate(const Y& y, double eps) const {
    const Y r = rate(0.0, y);
    return p(y.delta + eps * r.delta, y.w + eps * r.w) - p(y.delta - eps * r.delta, y.w - eps * r.w);
  }
  // One Dormand-Prince 5(4) step of size dt from (tau, y); `err` the scaled error estimate.
  Y step(double tau, const Y& y, double dt, double delta_ref, double w_ref, double* err) const {
    static constexpr double a21 = 1.0 / 5, a31 = 3.0 / 40, a32 = 9.0 / 40, a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9,
                            a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729,
                            a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                            a65 = -5103.0 / 18656, b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784,
                            b6 = 11.0 / 84, e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                            e6 = 22.0 / 525, e7 = -1.0 / 40;
    const Y k1 = rate(tau, y);
    const Y k2 = rate(tau + dt / 5, y + k1 * (dt * a21));
    const Y k3 = rate(tau + 3 * dt / 10, y + (k1 * a31 + k2 * a32) * dt);
    const Y k4 = rate(tau + 4 * dt / 5, y + (k1 * a41 + k2 * a42 + k3 * a43) * dt);
    const Y k5 = rate(tau + 8 * dt / 9, y + (k1 * a51 + k2 * a52 + k3 * a53 + k4 * a54) * dt);
    const Y k6 = rate(tau + dt, y + (k1 * a61 + k2 * a62 + k3 * a63 + k4 * a64 + k5 * a65) * dt);
    const Y y1 = y + (k1 * b1 + k3 * b3 + k4 * b4 + k5 * b5 + k6 * b6) * dt;
    if (err) {
      const Y k7 = rate(tau + dt, y1);
      const Y e = (k1 * e1 + k3 * e3 + k4 * e4 + k5 * e5 + k6 * e6 + k7 * e7) * dt;
      *err = std::max(std::abs(e.delta) / delta_ref, std::abs(e.w) / w_ref);
    }
    return y1;
  }
};

ContactStepper::ContactStepper(const structure::ContactLaw& law, double m_eff, int index)
    : law_(law), m_eff_(m_eff), index_(index), damping_(law.damping_parameter()) {
  if (law.model == ContactModel::linear) c_linear_ = 2.0 * damping_ * std::sqrt(law.stiffness * m_eff);
  inv_125_m_eff_ = 1.0 / (1.25 * m_eff);
}

double ContactStepper::force(double delta, double w, double v0) const {
  if (delta <= 0.0) return 0.0;
  const double k = law_.stiffness;
  switch (law_.model) {
    case ContactModel::linear: {
      const double f = k * delta + c_linear_ * w;
      return law_.tension_cut ? std::max(f, 0.0) : f;
    }
    case ContactModel::hertz: return k * delta * std::sqrt(delta);
    case ContactModel::hertzdamp: {
      const double f = k * delta * std::sqrt(delta);
      // v0 is never taken below the approach speed a free impact needs to reach this
      // penetration (1/2 m_eff v^2 = 2/5 k delta^(5/2)): a free impact never reaches that bound,
      // and a contact that starts at rest (v0 = 0) or is pressed past its impact's peak keeps
      // a finite damping, xi_bar sqrt(5/24) of critical at the tangent stiffness.
      const double v = std::max(v0, std::sqrt(f * delta * inv_125_m_eff_));
      return std::max(f * (1.0 + damping_ * w / v), 0.0);
    }
    case ContactModel::jankowski: {
      const double f = k * delta * std::sqrt(delta);
      if (w <= 0.0) return f;
      return f + 2.0 * damping_ * std::sqrt(k * std::sqrt(delta) * m_eff_) * w;
    }
    default: return 0.0;
  }
}

double ContactStepper::stored(double delta) const {
  if (delta <= 0.0) return 0.0;
  if (law_.model == ContactModel::linear) return 0.5 * law_.stiffness * delta * delta;
  if (law_.compliant()) return 0.4 * law_.stiffness * delta * delta * std::sqrt(delta);
  return 0.0;
}

ContactStepper::Scale ContactStepper::static_scale(double acceleration, double kappa) const {
  Scale s;
  const double k = law_.stiffness, force = acceleration / kappa;  // the load in force units
  if (!(force > 0.0)) return s;
  if (law_.model == ContactModel::linear) {
    s.delta = force / k;
    s.omega = std::sqrt(kappa * k);
  } else {
    s.delta = std::cbrt(force * force / (k * k));  // (F/k)^(2/3)
    s.omega = std::sqrt(1.5 * kappa * k * std::sqrt(s.delta));
  }
  s.speed = s.omega * s.delta;
  return s;
}

void ContactStepper::fail_bound(double t, double delta, double w, const std::string& what) const {
  std::ostringstream m;
  m << "contact pair " << index_ + 1 << " (" << structure::to_string(law_.model) << "): its motion in contact " << what
    << " in one step at t = " << t << " (penetration " << delta << ", rate " << w << "); the contact's sub-steps grow "
    << "with its stiffness (about k^(1/3) for a pressed Hertz contact): lower the pair's stiffness to the values of "
    << "guidance in docs/how-to/choose-contact-stiffness.md, or make solver.h smaller";
  throw NumericalError(m.str(), t);
}

bool ContactStepper::quiet(const ContactMemory& memory, const ContactStepIn& in) const {
  if (memory.engaged || law_.model == ContactModel::none) return !memory.engaged;
  // The parabola's largest value over [0, h].
  double top = std::max(in.delta0, in.delta0 + in.w0 * in.h + 0.5 * in.a * in.h * in.h);
  if (in.a < 0.0 && in.w0 > 0.0 && -in.w0 / in.a < in.h) top = std::max(top, in.delta0 - 0.5 * in.w0 * in.w0 / in.a);
  return top < 0.0;
}

ContactStepOut ContactStepper::step(ContactMemory& memory, const ContactStepIn& in, std::vector<Impact>& ended) const {
  return law_.model == ContactModel::impact ? newton_step(memory, in, ended) : compliant_step(memory, in, ended);
}

ContactStepOut ContactStepper::compliant_step(ContactMemory& memory, const ContactStepIn& in, std::vector<Impact>& ended) const {
  ContactStepOut out;
  const double h = in.h;
  Y y{in.delta0, in.w0, 0.0, 0.0, 0.0};
  double tau = 0.0;
  double impulse_mark = 0.0;  // the step's impulse when the impact under way was (re)entered
  constexpr double kTol = 1e-11;
  long substeps = 0;  // Runge-Kutta steps tried in the step (bounded: kMaxSubsteps)
  for (int entries = 0; tau < h; ++entries) {
    if (entries == kMaxEntries) fail_bound(in.t0 + tau, y.delta, y.w, "touched and separated more than 1000 times");
    const double r = h - tau;
    if (!memory.engaged) {
      // Free flight: a parabola (a small overlap left by rounding while the floors move apart
      // is no contact).
      if (y.delta > 0.0 && y.w <= 0.0) y.delta = 0.0;
      const double s = first_touch(y.delta, y.w, in.a, r);
      if (s > r) {
        y.delta += y.w * r + 0.5 * in.a * r * r;
        y.w += in.a * r;
        tau = h;
        break;
      }
      if (s > 0.0) y.delta = 0.0;
      y.w += in.a * s;
      tau += s;
      memory.engaged = true;
      memory.approach = std::max(y.w, 0.0);
      memory.current = Impact{};
      memory.current.contact = index_;
      memory.current.start = in.t0 + tau;
      memory.current.approach_speed = y.w;
      memory.current.penetration_max = std::max(y.delta, 0.0);
      out.touched = true;
      impulse_mark = y.impulse;
      continue;
    }
    out.touched = true;
    // In contact: embedded Runge-Kutta to the separation or the end of the step.
    const Flow flow{*this, in.a, in.kappa, h, memory.approach};
    // The error's scales: the impact's own (its approach speed and largest penetration), and,
    // for a contact pressed at rest (no approach speed, a penetration that only creeps), the
    // static one of the load pressing the floors together (the step's a, or the force the
    // pair holds now): its penetration and the speed of the pair's oscillation about it.
    const double held = in.kappa * std::abs(force(y.delta, y.w, memory.approach));
    const Scale load = static_scale(std::max(std::abs(in.a), held), in.kappa);
    const double w_ref =
        std::max({std::abs(memory.current.approach_speed), std::abs(y.w), std::abs(in.a) * h, load.speed, 1e-300});
    // A first sub-step from the pair's contact frequency at its expected largest penetration.
    double omega = 0.0;
    if (law_.model == ContactModel::linear) {
      omega = std::sqrt(in.kappa * law_.stiffness) + in.kappa * c_linear_;
    } else {
      const double v = std::max(std::abs(y.w), 1e-300);
      const double d_est = std::max({y.delta, load.delta, std::pow(1.25 * v * v / (in.kappa * law_.stiffness), 0.4)});
      omega = std::sqrt(1.5 * in.kappa * law_.stiffness * std::sqrt(d_est));
    }
    double dt = std::min(r, 0.02 / std::max(omega, 1e-300));
    bool separated = false;
    while (tau < h && !separated) {
      if (++substeps > kMaxSubsteps)
        fail_bound(in.t0 + tau, y.delta, y.w, "needed more than " + std::to_string(kMaxSubsteps) + " sub-steps");
      dt = std::min(dt, h - tau);
      const double delta_ref =
          std::max({memory.current.penetration_max, std::abs(y.delta), load.delta, w_ref * dt, 1e-300});
      double err = 0.0;
      const Y y1 = flow.step(tau, y, dt, delta_ref * kTol, w_ref * kTol, &err);
      if (!(err <= 1.0)) {
        dt *= std::isfinite(err) ? std::clamp(0.9 * std::pow(err, -0.2), 0.1, 0.9) : 0.1;
        if (!(dt > 1e-13 * h)) {
          std::ostringstream m;
          m << "contact pair " << index_ + 1 << " (" << structure::to_string(law_.model) << "): its motion in contact could not be "
            << "integrated to the tolerance at t = " << in.t0 + tau << " (penetration " << y.delta << ", rate " << y.w
            << "); check its stiffness and restitution, or the ground motion's scale";
          throw NumericalError(m.str(), in.t0 + tau);
        }
        continue;
      }
      const double grow = std::clamp(0.9 * std::pow(std::max(err, 1e-30), -0.2), 1.0, 5.0);
      // Events inside the accepted step: separation, the largest penetration, the largest force.
      auto bisect = [&](auto&& value) {  // the instant in (0, dt] where value() leaves > 0
        double lo = 0.0, hi = dt;
        for (int i = 0; i < 100 && hi - lo > 1e-15 * h; ++i) {
          const double mid = 0.5 * (lo + hi);
          if (value(flow.step(tau, y, mid, 1.0, 1.0, nullptr)) > 0.0) lo = mid;
          else hi = mid;
        }
        return hi;
      };
      double end = dt;
      if (flow.apart(y1) <= 0.0) {
        end = bisect([&](const Y& z) { return flow.apart(z); });
        separated = true;
      }
      if (y.w > 0.0 && flow.step(tau, y, end, 1.0, 1.0, nullptr).w <= 0.0) {
        const double at = bisect([&](const Y& z) { return z.w; });
        memory.current.penetration_max = std::max(memory.current.penetration_max, flow.step(tau, y, at, 1.0, 1.0, nullptr).delta);
      }
      const double eps = 1e-6 * end;
      const double rate0 = flow.force_rate(y, eps);
      const Y y_end = end == dt ? y1 : flow.step(tau, y, end, 1.0, 1.0, nullptr);
      if (rate0 > 0.0 && flow.force_rate(y_end, eps) <= 0.0) {
        double lo = 0.0, hi = end;  // golden-section search of the force's maximum on [0, end]
        const double g = 0.5 * (std::sqrt(5.0) - 1.0);
        for (int i = 0; i < 100 && hi - lo > 1e-14 * h; ++i) {
          const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
          const Y z1 = flow.step(tau, y, m1, 1.0, 1.0, nullptr), z2 = flow.step(tau, y, m2, 1.0, 1.0, nullptr);
          if (flow.p(z1.delta, z1.w) < flow.p(z2.delta, z2.w)) lo = m1;
          else hi = m2;
        }
        const double at = 0.5 * (lo + hi);
        const Y z = flow.step(tau, y, at, 1.0, 1.0, nullptr);
        const double f = flow.p(z.delta, z.w);
        if (f > memory.current.force_max) {
          memory.current.force_max = f;
          memory.current.t_force_max = in.t0 + tau + at;
        }
      }
      y = y_end;
      tau += end;
      memory.current.penetration_max = std::max(memory.current.penetration_max, y.delta);
      const double f_end = flow.p(y.delta, y.w);
      if (f_end > memory.current.force_max) {
        memory.current.force_max = f_end;
        memory.current.t_force_max = in.t0 + tau;
      }
      if (!separated) dt *= grow;
    }
    if (separated) {
      memory.engaged = false;
      memory.current.duration = in.t0 + tau - memory.current.start;
      memory.current.rebound_speed = -y.w;
      memory.current.complete = true;
      y.delta = std::min(y.delta, 0.0);
      memory.current.impulse += y.impulse - impulse_mark;
      ended.push_back(memory.current);
    }
  }
  out.impulse = y.impulse;
  out.moment = y.moment;
  out.work = y.work;
  out.delta = y.delta;
  out.w = y.w;
  out.force = memory.engaged ? force(y.delta, y.w, memory.approach) : 0.0;
  if (memory.engaged) memory.current.impulse += y.impulse - impulse_mark;
  return out;
}

ContactStepOut ContactStepper::newton_step(ContactMemory& memory, const ContactStepIn& in, std::vector<Impact>& ended) const {
  ContactStepOut out;
  const double h = in.h, a = in.a, kappa = in.kappa, e = law_.restitution;
  double tau = 0.0, d = std::min(in.delta0, 0.0), w = in.w0;
  // A held contact (at rest against each other) stays while a pushes the floors together.
  auto hold_rest = [&](double from) {
    const double r = h - from;
    const double p = a / kappa;
    out.impulse += p * r;
    out.moment += p * 0.5 * r * r;
    memory.current.impulse += p * r;
    out.force = p;
    d = 0.0;
    w = 0.0;
    tau = h;
  };
  if (memory.engaged) {
    if (a > 0.0) {
      out.touched = true;
      hold_rest(0.0);
      out.delta = 0.0;
      out.w = 0.0;
      return out;
    }
    memory.engaged = false;
    memory.current.duration = in.t0 - memory.current.start;
    memory.current.complete = true;
    ended.push_back(memory.current);
    d = 0.0;
    w = std::min(w, 0.0);
  }
  for (int bounces = 0; tau < h; ++bounces) {
    if (bounces == 100000) fail_bound(in.t0 + tau, d, w, "bounced more than 100000 times");
    const double r = h - tau;
    const double s = first_touch(d, w, a, r);
    if (s > r) {
      d += w * r + 0.5 * a * r * r;
      w += a * r;
      tau = h;
      break;
    }
    out.touched = true;
    tau += s;
    const double w_minus = w + a * s;
    d = 0.0;
    if (!(w_minus > 0.0)) {  // at rest against each other, pushed together: held
      memory.engaged = true;
      memory.current = Impact{};
      memory.current.contact = index_;
      memory.current.start = in.t0 + tau;
      hold_rest(tau);
      break;
    }
    const double rebound = e * w_minus;
    const double r_after = h - tau;
    // The bounces that would follow under a pushing a: flights 2 rebound e^k / a, all over in
    // 2 rebound / (a (1 - e)). If that ends inside the step they are summed in closed form
    // (infinitely many, ever smaller: one impact that comes to rest).
    if (e < 1.0 && a > 0.0 && 2.0 * rebound / (a * (1.0 - e)) <= r_after) {
      const double c = 2.0 * rebound / (a * (1.0 - e));
      const double first = (1.0 + e) * w_minus / kappa;           // this landing
      const double rest = (1.0 + e) * rebound / ((1.0 - e) * kappa);  // the accumulating bounces
      // Their instants tau_k = tau + c (1 - e^k), k >= 1, with weights e^(k-1): the moment.
      const double sum_t = (tau + c) / (1.0 - e) - c * e / (1.0 - e * e);  // sum e^(k-1) tau_k
      out.impulse += first + rest;
      out.moment += first * (h - tau) + (1.0 + e) * rebound / kappa * (h / (1.0 - e) - sum_t);
      out.work += first * 0.5 * (w_minus - rebound) + rebound * rebound / (2.0 * kappa);
      memory.engaged = true;
      memory.current = Impact{};
      memory.current.contact = index_;
      memory.current.start = in.t0 + tau;
      memory.current.approach_speed = w_minus;
      memory.current.impulse = first + rest;
      hold_rest(tau + c);
      break;
    }
    const double impulse = (1.0 + e) * w_minus / kappa;
    out.impulse += impulse;
    out.moment += impulse * (h - tau);
    out.work += impulse * 0.5 * (w_minus - rebound);
    Impact impact;
    impact.contact = index_;
    impact.start = in.t0 + tau;
    impact.approach_speed = w_minus;
    impact.rebound_speed = rebound;
    impact.impulse = impulse;
    ended.push_back(impact);
    w = -rebound;
  }
  out.delta = d;
  out.w = w;
  return out;
}

}  // namespace adjoin::detail
