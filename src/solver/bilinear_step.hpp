#pragma once
// Bilinear elements in the structure step (SPEC §7; internal to the solver): a storey's own
// bilinear law or a bilinear storey device, force = b k d + (1 - b) k z: the spring b k in
// parallel with the spring k_h = (1 - b) k in series with a Coulomb slider of slip force
// F_h = (1 - b) F_y. The whole initial stiffness k stays in K0 and K_eff (the step matrix is
// never refactorised); the series element's force is q = k_h (d - u_p), u_p the slider's slip
// (the plastic deformation), which enters the step as a constant offset -k_h u_p (as a Zener
// element's history does) while the element is elastic. While it slips, its force is held at
// +-F_h by a step force U beside the friction dampers' in their box QP (box_qp.hpp): the
// correction c = +-F_h - k_h (d - u_p,n) of what the spring alone would give, affine in the
// element's end velocity w_n+1, a held row of the QP with the compliance -1 / (theta^2 k_h h)
// on its diagonal (theta the step's mechanics weight: 1/2 trapezoidal, 1 backward Euler):
//
//  - elastic through the step: not an unknown (U = 0): the steps of an elastic structure cost
//    what they did;
//  - plastic through the step: held, U = theta c_n+1 (c_n = 0);
//  - yield inside the step: the elastic trial's force passes +-F_h; the instant tau where q(t)
//    reaches it (w linear through the step) is located and U is the trapezoid of c over
//    [tau, 1], c_n+1 from the trial (its own error is O(h^3));
//  - unloading inside the step: the plastic rate w reverses at the located tau (the root of w
//    through its last grid values, as a friction damper's slip ends), u_p freezes there and U
//    is the trapezoid of c, constant after tau.
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
  int i = -1, j = -1;       // its floors (dofs; -1 the ground): d = x_i - x_j
  int storey = -1;          // the storey it stands in (A's first)
  bool storey_law = false;  // the storey spring's own law (its z is the channel X.hystN), or a device
  double k = 0.0;           // k_h = (1 - b) k [N/m]
  double limit = 0.0;       // F_h = (1 - b) F_y [N]
};

enum class YieldPhase : char { elastic, plastic_positive, plastic_negative };

// The element's state (per run): at t_n, and what the step decided. (Its force q at t_n is
// kept beside the others', in BilinearStates (bilinear_lanes.hpp): every step writes it.)
struct BilinearState {
  YieldPhase phase = YieldPhase::elastic;
  double up = 0.0;         // the slider's slip u_p at t_n [m]
  double d = 0.0;          // deformation at t_n [m]
  double w = 0.0;          // relative velocity at t_n (while elastic: set as it leaves the range)
  double w_prev = 0.0;     // ... at t_n-1
  bool prev_same = false;  // t_n-1 was in the same plastic excursion (for the unloading's parabola)
  // this step
  YieldPhase next = YieldPhase::elastic;
  double event = std::numeric_limits<double>::quiet_NaN();  // fraction of the step where it yielded or unloaded
  bool yielded = false;                                     // the event is a yield (else an unloading)
  double up_next = 0.0;                                     // an unloading's frozen slip
  // The force the element adds to its spring's k_h d: -k_h u_p (the step's offset at t_n).
  double offset(const BilinearElement& e) const { return -e.k * up; }
};

inline double sign_of(YieldPhase p) { return p == YieldPhase::plastic_positive ? 1.0 : -1.0; }

// The element as phased at t_n, for the QP: elastic, not an unknown (fixed 0); plastic, held
// (its row's right-hand side w0; the matrix has its compliance).
inline void bilinear_as_phased(BilinearState& st, double theta, double w_free, char* hold, double* fixed, double* w0) {
  st.next = st.phase;
  st.event = std::numeric_limits<double>::quiet_NaN();
  *fixed = 0.0;
  *hold = st.phase != YieldPhase::elastic;
  // U = alpha + beta w1, beta = -theta^2 k_h h, alpha = -theta (1 - theta) k_h h w_n.
  if (*hold) *w0 = w_free + (1.0 - theta) / theta * st.w;
}

// The force at the end of a trial step whose end deformation is d1 (as phased), within the
// yield surface.
inline double bilinear_trial_force(const BilinearElement& e, const BilinearState& st, double d1) {
  if (st.phase != YieldPhase::elastic) return e.limit * sign_of(st.phase);
  return std::clamp(e.k * (d1 - st.up), -e.limit, e.limit);
}

// Where q(tau) = q_n + k_h h (tau w_n + tau^2 (w1 - w_n) / 2) (w linear through the step)
// reaches `target`, in [0, 1] (q_n the force at t_n).
inline double bilinear_yield_fraction(const BilinearElement& e, const BilinearState& st, double q_n, double h, double w1,
                                      double target) {
  const double a = 0.5 * e.k * h * (w1 - st.w), b = e.k * h * st.w, c = q_n - target;
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

// The decision from the trial step's end (deformation d1, velocity w1; q_n the force at t_n):
// yields or unloads inside the step (its fixed step force), or goes on as phased. (Its first
// test, |k_h (d1 - u_p)| <= F_h for an element elastic at t_n, is the step's pass over all
// elements, bilinear_lanes.hpp: it decides nothing.)
inline void bilinear_decide(const BilinearElement& e, BilinearState& st, double q_n, double theta, double h, double d1, double w1,
                            char* hold, double* fixed) {
  if (st.phase == YieldPhase::elastic) {
    const double q1 = e.k * (d1 - st.up);
    if (std::abs(q1) <= e.limit) return;
    const double s = q1 > 0.0 ? 1.0 : -1.0, f = s * e.limit;
    const double tau = bilinear_yield_fraction(e, st, q_n, h, w1, f);
    const double c1 = f - q1;  // the correction at the end: 0 up to tau, linear after
    *hold = 0;
    *fixed = theta < 1.0 ? 0.5 * (1.0 - tau) * c1 : c1;
    st.next = s > 0.0 ? YieldPhase::plastic_positive : YieldPhase::plastic_negative;
    st.event = tau;
    st.yielded = true;
    return;
  }
  const double s = sign_of(st.phase), f = s * e.limit;
  if (w1 * s >= 0.0) return;
  const double tau = st.prev_same ? locate_onset(0.0, true, st.w_prev, st.w, w1, 0.0)
                                  : (st.w != w1 ? std::clamp(st.w / (st.w - w1), 0.0, 1.0) : 1.0);
  // The slip freezes at tau: u_p = d(tau) - F_h / k_h, the correction c(tau) constant after.
  const double d_tau = st.d + h * (tau * st.w + 0.5 * tau * tau * (w1 - st.w));
  st.up_next = d_tau - f / e.k;
  const double c_tau = -e.k * (st.up_next - st.up);
  *hold = 0;
  *fixed = theta < 1.0 ? 0.5 * tau * c_tau + (1.0 - tau) * c_tau : c_tau;
  st.next = YieldPhase::elastic;
  st.event = tau;
  st.yielded = false;
}

// The step's end from the element's final end deformation d1 and velocity w1: its slip,
// force q and phase at t_n+1. (An element elastic through the step, no event located in it,
// that ends within the yield surface — the most, in a building — is ended by the step's pass
// over all elements instead, bilinear_lanes.hpp: only its force changes, as here. It was
// elastic at t_n, so its phase stays and prev_same is false already; its d, w and w_prev are
// read only while it slips or as it leaves the elastic range, when the step takes w_n from the
// grid velocities: bilinear_decide's caller.)
inline void bilinear_end(const BilinearElement& e, BilinearState& st, double& q, double d1, double w1) {
  if (st.next == YieldPhase::elastic && !std::isnan(st.event)) st.up = st.up_next;  // unloaded inside the step
  double q1 = e.k * (d1 - st.up);
  if (st.next == YieldPhase::elastic && std::abs(q1) > e.limit) {  // (the dampers' final decisions moved it past yield)
    st.next = q1 > 0.0 ? YieldPhase::plastic_positive : YieldPhase::plastic_negative;
    st.event = 1.0;
    st.yielded = true;
  }
  if (st.next != YieldPhase::elastic) {
    q1 = e.limit * sign_of(st.next);
    st.up = d1 - q1 / e.k;
  }
  st.prev_same = st.phase == st.next && st.phase != YieldPhase::elastic;
  st.phase = st.next;
  q = q1;
  st.d = d1;
  st.w_prev = st.w;
  st.w = w1;
}

}  // namespace adjoin::detail
