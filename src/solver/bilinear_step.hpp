#pragma once
// Bilinear elements in the structure step (SPEC §7; internal to the solver): a storey's own
// bilinear law or a bilinear storey device. Its linear part b k is a spring of K0; the rest is
// a spring k_h = (1 - b) k in series with a Coulomb slider of slip force F_h = (1 - b) F_y,
// whose force q is an unknown of the step beside the friction dampers' step forces (the box
// QP of box_qp.hpp), never part of K_eff:
//
//  - elastic through the step: q_n+1 = q_n + k_h (d_n+1 - d_n), with the step's mechanics
//    (weight theta: 1/2 trapezoidal, 1 backward Euler) d_n+1 - d_n = h ((1 - theta) w_n +
//    theta w_n+1), w the element's relative velocity. The step force it adds beyond what the
//    free step already holds (P at t_n, weight 1 - theta) is U = theta q_n+1, affine in w_n+1:
//    a held unknown of the QP with the compliance 1 / (theta^2 k_h h) on its diagonal (a
//    friction damper held stuck is the same with compliance 0);
//  - plastic: q = +-F_h, a fixed step force;
//  - yield inside the step: q reaches +-F_h at the located fraction tau (the root of q(t) with w
//    linear through the step), the step's force the trapezoid of q up to tau and F_h after;
//  - unloading inside the step: the plastic rate w reverses at the located tau (the root of w
//    through its last grid values, as a friction damper's slip ends), F_h up to tau, elastic
//    after.
// The force is continuous at both events (at an unloading its rate too: w = 0 there), so the
// step's mean force is exact to the step's order and no kink needs integrating; no iteration,
// no regularisation, and |q| <= F_h at every grid point (no overshoot of the yield surface).
#include <algorithm>
#include <cmath>
#include <limits>

#include "onset.hpp"

namespace adjoin::detail {

// The element as the model knows it: where it acts, its series spring and slip force.
struct BilinearElement {
  int i = -1, j = -1;      // its floors (dofs; -1 the ground): d = x_i - x_j
  int storey = -1;         // the storey it stands in (A's first)
  bool storey_law = false; // the storey spring's own law (its z is the channel X.hystN), or a device
  double k = 0.0;          // k_h = (1 - b) k [N/m]
  double limit = 0.0;      // F_h = (1 - b) F_y [N]
};

enum class YieldPhase : char { elastic, plastic_positive, plastic_negative };

// The element's state (per run): at t_n, and what the step decided.
struct BilinearState {
  YieldPhase phase = YieldPhase::elastic;
  double q = 0.0;       // force at t_n [N]
  double w = 0.0;       // relative velocity at t_n
  double w_prev = 0.0;  // ... at t_n-1
  bool prev_same = false;  // t_n-1 was in the same plastic excursion (for the unloading's parabola)
  // this step
  YieldPhase next = YieldPhase::elastic;
  double event = std::numeric_limits<double>::quiet_NaN();  // fraction of the step where it yielded or unloaded
  bool yielded = false;  // the event is a yield (else an unloading)
};

inline double sign_of(YieldPhase p) { return p == YieldPhase::plastic_positive ? 1.0 : -1.0; }

// The element as phased at t_n, for the QP: held elastic (with the right-hand side w0 of its
// row, whose matrix has the compliance 1 / (theta^2 k_h h)), or its fixed plastic step force.
inline void bilinear_as_phased(const BilinearElement& e, BilinearState& st, double theta, double h, double w_free, char* hold,
                               double* fixed, double* w0) {
  st.next = st.phase;
  st.event = std::numeric_limits<double>::quiet_NaN();
  if (st.phase == YieldPhase::elastic) {
    *hold = 1;
    *fixed = 0.0;
    *w0 = w_free + st.q / (theta * e.k * h) + (1.0 - theta) / theta * st.w;
  } else {
    *hold = 0;
    *fixed = theta * e.limit * sign_of(st.phase);
  }
}

// The elastic force at the step's end for the end velocity w1 (before any yield).
inline double bilinear_elastic_end(const BilinearElement& e, const BilinearState& st, double theta, double h, double w1) {
  return st.q + e.k * h * ((1.0 - theta) * st.w + theta * w1);
}

// The force at the end of a trial step (as phased), within the yield surface.
inline double bilinear_trial_force(const BilinearElement& e, const BilinearState& st, double theta, double h, double w1) {
  if (st.phase != YieldPhase::elastic) return e.limit * sign_of(st.phase);
  const double q1 = bilinear_elastic_end(e, st, theta, h, w1);
  return q1 > e.limit ? e.limit : (q1 < -e.limit ? -e.limit : q1);
}

// Where q(tau) = q_n + k_h h (tau w_n + tau^2 (w1 - w_n) / 2) (w linear through the step)
// reaches `target`, in (0, 1].
inline double bilinear_yield_fraction(const BilinearElement& e, const BilinearState& st, double h, double w1, double target) {
  const double a = 0.5 * e.k * h * (w1 - st.w), b = e.k * h * st.w, c = st.q - target;
  double best = std::numeric_limits<double>::quiet_NaN();
  auto consider = [&](double x) {
    if (std::isfinite(x) && x >= 0.0 && x <= 1.0 && !(x >= best)) best = x;
  };
  if (std::abs(a) > 1e-14 * (std::abs(b) + std::abs(c))) {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      const double q = -0.5 * (b + (b >= 0.0 ? r : -r));  // the stable quadratic formula
      if (q != 0.0) consider(c / q);
      consider(q / a);
    }
  } else if (b != 0.0) {
    consider(-c / b);
  }
  return std::isfinite(best) ? best : 1.0;
}

// The decision from the trial step's end velocity w1: yields or unloads inside the step (the
// new fixed step force), or goes on as phased. True when it changed.
inline bool bilinear_decide(const BilinearElement& e, BilinearState& st, double theta, double h, double w1, char* hold, double* fixed) {
  if (st.phase == YieldPhase::elastic) {
    const double q1 = bilinear_elastic_end(e, st, theta, h, w1);
    if (std::abs(q1) <= e.limit) return false;
    const double s = q1 > 0.0 ? 1.0 : -1.0, f = s * e.limit;
    const double tau = bilinear_yield_fraction(e, st, h, w1, f);
    // The trapezoid of q up to tau, F_h after (backward Euler: the end force).
    const double mean = theta < 1.0 ? tau * 0.5 * (st.q + f) + (1.0 - tau) * f : f;
    *hold = 0;
    *fixed = mean - (1.0 - theta) * st.q;
    st.next = s > 0.0 ? YieldPhase::plastic_positive : YieldPhase::plastic_negative;
    st.event = tau;
    st.yielded = true;
    return true;
  }
  const double s = sign_of(st.phase), f = s * e.limit;
  if (w1 * s >= 0.0) return false;
  const double tau = st.prev_same ? locate_onset(0.0, true, st.w_prev, st.w, w1, 0.0)
                                  : (st.w != w1 ? std::clamp(st.w / (st.w - w1), 0.0, 1.0) : 1.0);
  // F_h up to tau, then elastic from w = 0: q_n+1 = F_h + k_h (1 - tau) h theta w1.
  const double q1 = f + e.k * (1.0 - tau) * h * theta * w1;
  const double mean = theta < 1.0 ? tau * f + (1.0 - tau) * 0.5 * (f + q1) : q1;
  *hold = 0;
  *fixed = mean - (1.0 - theta) * f;
  st.next = YieldPhase::elastic;
  st.event = tau;
  st.yielded = false;
  return true;
}

// The step's end from the element's final end velocity w1: its force and phase at t_n+1.
inline void bilinear_end(const BilinearElement& e, BilinearState& st, double theta, double h, double w1) {
  double q1 = 0.0;
  if (st.next == YieldPhase::elastic) {
    q1 = std::isnan(st.event) ? bilinear_elastic_end(e, st, theta, h, w1)
                              : e.limit * sign_of(st.phase) + e.k * (1.0 - st.event) * h * theta * w1;
    if (std::abs(q1) > e.limit) {  // (the dampers' final decisions moved it past yield: at the end)
      st.next = q1 > 0.0 ? YieldPhase::plastic_positive : YieldPhase::plastic_negative;
      st.event = 1.0;
      st.yielded = true;
    }
  }
  if (st.next != YieldPhase::elastic) q1 = e.limit * sign_of(st.next);
  st.prev_same = st.phase == st.next && st.phase != YieldPhase::elastic;
  st.phase = st.next;
  st.q = q1;
  st.w_prev = st.w;
  st.w = w1;
}

}  // namespace adjoin::detail
