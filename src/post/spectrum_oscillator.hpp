#pragma once
// One response-spectrum oscillator: the exact piecewise-linear step and the exact location of
// peaks between sub-step points (used by spectrum.cpp only; the method is described in
// adjoin/post/spectrum.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <thread>
#include <vector>

#include "adjoin/post/spectrum.hpp"

namespace adjoin::spectrum_detail {

// Above this omega h the turning-point search is skipped (only reached through max_substeps,
// where the oscillator follows the excitation quasi-statically).
constexpr double kMaxRefineTheta = 1.6;
constexpr int kMaxTerms = 40;

constexpr std::array<double, kMaxTerms + 4> inverse_factorials() {
  std::array<double, kMaxTerms + 4> f{};
  double x = 1.0;
  for (std::size_t m = 0; m < f.size(); ++m) {
    if (m > 0) x /= static_cast<double>(m);
    f[m] = x;
  }
  return f;
}
inline constexpr std::array<double, kMaxTerms + 4> kInverseFactorial = inverse_factorials();

// sum_{m < terms} c[m] s^m / m!  (Horner, multiplications only).
inline double taylor(const double* c, int terms, double s) {
  double r = c[terms - 1] * kInverseFactorial[static_cast<std::size_t>(terms - 1)];
  for (int m = terms - 2; m >= 0; --m) r = r * s + c[m] * kInverseFactorial[static_cast<std::size_t>(m)];
  return r;
}

// Number of Taylor terms for which (theta)^M / M! is below rounding (at least 6).
inline int taylor_terms(double theta) {
  double term = 1.0;
  int m = 0;
  while ((term > 1e-17 || m < 6) && m < kMaxTerms - 4) {
    ++m;
    term *= theta / static_cast<double>(m);
  }
  return m + 1;
}

// |q| at the turning point of q on (0, h), where q'(0) = f0 and q'(h) = f1 differ in sign;
// c[m] = q^(m)(0) for m < terms + 2.
inline double turning_value(const double* c, int terms, double h, double f0, double f1) {
  double lo = 0.0;
  double hi = h;
  double s = h * f0 / (f0 - f1);
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double f = taylor(c + 1, terms, s);
    if (f == 0.0) break;
    if ((f > 0.0) == (f0 > 0.0)) lo = s; else hi = s;
    const double fp = taylor(c + 2, terms, s);
    double next = fp != 0.0 ? s - f / fp : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double change = std::abs(next - s);
    s = next;
    if (change <= 1e-15 * h) break;
  }
  return std::abs(taylor(c, terms, s));
}

struct Peaks {
  double u = 0.0;
  double v = 0.0;
  double a = 0.0;
};

// Bounds on the excitation p = -a_g over the record, for the turning-point filter.
struct ExcitationBounds {
  double p = 0.0;      // max |p|
  double slope = 0.0;  // max |dp/dt|
};

inline ExcitationBounds excitation_bounds(double dt, std::span<const double> accel) {
  ExcitationBounds b;
  for (std::size_t i = 0; i < accel.size(); ++i) {
    b.p = std::max(b.p, std::abs(accel[i]));
    if (i > 0) b.slope = std::max(b.slope, std::abs(accel[i] - accel[i - 1]) / dt);
  }
  return b;
}

// One oscillator, advanced over sub-steps of length h with p = -a_g linear on each.
//
// Peaks between sub-step points: a quantity q (u, v or a_abs) can exceed its end values inside
// a sub-step only where q' changes sign, and then by at most h^2/8 max|q''|. Every step checks,
// branch-free and cheaply, whether an end value comes within a margin m_q = h^2/4 B_q of the
// running peak, where B_q bounds |q''| from the excitation bounds and the running peaks
// (u'' = p + a_abs, v'' = p' - c u'' - w2 v, a_abs'' = -(c v'' + w2 u'')). Only then does the
// slow path look for sign changes, tighten the bound with the end values and locate the
// turning point exactly. A first, cheaper pass at the samples (step_sampled) gives lower
// bounds of the peaks (the floor), so the slow path is not taken at every step while the
// response is still growing: a turn below the floor cannot be the peak.
class Oscillator {
 public:
  Oscillator() = default;
  Oscillator(double omega, double zeta, double h, bool refine, const ExcitationBounds& bounds)
      : k_(step_coefficients(omega, zeta, h)),
        h_(h),
        c_(2.0 * zeta * omega),
        w2_(omega * omega),
        terms_(taylor_terms(omega * h)),
        refine_(refine && omega * h <= kMaxRefineTheta),
        bounds_(bounds) {
    update_thresholds();
  }

  // Advance one sub-step from p0 to p1 and update the peaks.
  [[gnu::always_inline]] inline void step(double p0, double p1) {
    const double u1 = k_.a_uu * u_ + k_.a_uv * v_ + k_.b_u0 * p0 + k_.b_u1 * p1;
    const double v1 = k_.a_vu * u_ + k_.a_vv * v_ + k_.b_v0 * p0 + k_.b_v1 * p1;
    const double a1 = -(c_ * v1 + w2_ * u1);  // absolute acceleration u'' + a_g
    // One test for the three quantities (no short-circuit branches).
    const int near = int{std::max(std::abs(u_), std::abs(u1)) >= threshold_u_} |
                     int{std::max(std::abs(v_), std::abs(v1)) >= threshold_v_} |
                     int{std::max(std::abs(a_), std::abs(a1)) >= threshold_a_};
    if (near != 0) near_peak(p0, p1, u1, v1, a1);
    u_ = u1;
    v_ = v1;
    a_ = a1;
  }

  // Advance one sub-step, peaks at the end points only (branch-free).
  [[gnu::always_inline]] inline void step_sampled(double p0, double p1) {
    const double u1 = k_.a_uu * u_ + k_.a_uv * v_ + k_.b_u0 * p0 + k_.b_u1 * p1;
    const double v1 = k_.a_vu * u_ + k_.a_vv * v_ + k_.b_v0 * p0 + k_.b_v1 * p1;
    const double a1 = -(c_ * v1 + w2_ * u1);
    peaks_.u = std::max(peaks_.u, std::abs(u1));
    peaks_.v = std::max(peaks_.v, std::abs(v1));
    peaks_.a = std::max(peaks_.a, std::abs(a1));
    u_ = u1;
    v_ = v1;
    a_ = a1;
  }

  // Lower bounds of the final peaks (from a sampled pass over the same record).
  void set_floor(const Peaks& floor) {
    floor_ = floor;
    update_thresholds();
  }

  const Peaks& peaks() const { return peaks_; }
  double u() const { return u_; }
  double v() const { return v_; }
  double a_abs() const { return a_; }

  // Hooks for the lane kernels below, which step several oscillators at once in vector
  // registers and come back here for the rare steps near a peak.
  const StepCoefficients& coefficients() const { return k_; }
  double damping_term() const { return c_; }
  double stiffness_term() const { return w2_; }
  double threshold_u() const { return threshold_u_; }
  double threshold_v() const { return threshold_v_; }
  double threshold_a() const { return threshold_a_; }
  void set_state(double u, double v, double a) {
    u_ = u;
    v_ = v;
    a_ = a;
  }
  void set_peaks(const Peaks& peaks) { peaks_ = peaks; }
  // The step from the current state to (u1, v1, a1) under p0 -> p1 came near a peak.
  void step_near_peak(double p0, double p1, double u1, double v1, double a1) {
    near_peak(p0, p1, u1, v1, a1);
    set_state(u1, v1, a1);
  }

 private:
  void update_thresholds() {
    if (!refine_) {  // peaks at the sub-step points only
      threshold_u_ = peaks_.u;
      threshold_v_ = peaks_.v;
      threshold_a_ = peaks_.a;
      return;
    }
    // Below max(peak, floor) an end value neither sets the peak nor bounds a turn that could.
    // Any end value that skips the slow path is below it, so these bound |q''| there.
    const double hh = 0.25 * h_ * h_;
    const double eu = std::max(peaks_.u, floor_.u), ev = std::max(peaks_.v, floor_.v),
                 ea = std::max(peaks_.a, floor_.a);
    const double b_u = bounds_.p + ea;                         // |u''|
    const double b_v = bounds_.slope + c_ * b_u + w2_ * ev;    // |u'''|
    const double b_a = c_ * b_v + w2_ * b_u;                   // |a_abs''|
    threshold_u_ = eu - hh * b_u;
    threshold_v_ = ev - hh * b_v;
    threshold_a_ = ea - hh * b_a;
  }

  // An end value is near its running peak: look for turning points, update peaks and margins.
  [[gnu::noinline]] void near_peak(double p0, double p1, double u1, double v1, double a1) {
    if (refine_) {
      const double hh = 0.25 * h_ * h_;
      const double slope = (p1 - p0) / h_;
      const double r0 = p0 + a_, r1 = p1 + a1;                                        // u''
      const double j0 = slope - c_ * r0 - w2_ * v_, j1 = slope - c_ * r1 - w2_ * v1;  // u'''
      const double g0 = -(c_ * r0 + w2_ * v_), g1 = -(c_ * r1 + w2_ * v1);            // a_abs'
      if (v_ * v1 < 0.0 && std::max(std::abs(u_), std::abs(u1)) + hh * std::max(std::abs(r0), std::abs(r1)) >=
                               std::max(peaks_.u, floor_.u))
        refine(p0, p1, 0, v_, v1);
      if (r0 * r1 < 0.0 && std::max(std::abs(v_), std::abs(v1)) + hh * std::max(std::abs(j0), std::abs(j1)) >=
                               std::max(peaks_.v, floor_.v))
        refine(p0, p1, 1, r0, r1);
      if (g0 * g1 < 0.0) {
        const double q0 = -(c_ * j0 + w2_ * r0), q1 = -(c_ * j1 + w2_ * r1);
        if (std::max(std::abs(a_), std::abs(a1)) + hh * std::max(std::abs(q0), std::abs(q1)) >=
            std::max(peaks_.a, floor_.a))
          refine(p0, p1, 2, g0, g1);
      }
    }
    peaks_.u = std::max(peaks_.u, std::abs(u1));
    peaks_.v = std::max(peaks_.v, std::abs(v1));
    peaks_.a = std::max(peaks_.a, std::abs(a1));
    update_thresholds();
  }

  // Exact turning value of quantity `which` (0: u, 1: v, 2: a_abs) inside the current sub-step.
  void refine(double p0, double p1, int which, double f0, double f1) {
    // Derivatives of u at the start of the sub-step, from the equation of motion; p'' = 0.
    std::array<double, kMaxTerms + 4> d{};
    const int n = terms_ + 3;
    d[0] = u_;
    d[1] = v_;
    d[2] = p0 - c_ * v_ - w2_ * u_;
    d[3] = (p1 - p0) / h_ - c_ * d[2] - w2_ * d[1];
    for (int m = 4; m < n; ++m)
      d[static_cast<std::size_t>(m)] = -c_ * d[static_cast<std::size_t>(m - 1)] - w2_ * d[static_cast<std::size_t>(m - 2)];
    double value = 0.0;
    if (which == 0) {
      value = turning_value(d.data(), terms_, h_, f0, f1);
      peaks_.u = std::max(peaks_.u, value);
    } else if (which == 1) {
      value = turning_value(d.data() + 1, terms_, h_, f0, f1);
      peaks_.v = std::max(peaks_.v, value);
    } else {
      std::array<double, kMaxTerms + 4> e{};
      // a_abs = -(c u' + w2 u); its derivatives follow from those of u.
      for (int m = 0; m + 1 < n; ++m)
        e[static_cast<std::size_t>(m)] = -(c_ * d[static_cast<std::size_t>(m + 1)] + w2_ * d[static_cast<std::size_t>(m)]);
      value = turning_value(e.data(), terms_, h_, f0, f1);
      peaks_.a = std::max(peaks_.a, value);
    }
  }

  StepCoefficients k_{};
  double h_ = 0.0, c_ = 0.0, w2_ = 0.0;
  int terms_ = 0;
  bool refine_ = false;
  ExcitationBounds bounds_;
  Peaks floor_;
  double threshold_u_ = 0.0, threshold_v_ = 0.0, threshold_a_ = 0.0;
  double u_ = 0.0, v_ = 0.0, a_ = 0.0;
  Peaks peaks_;
};

// The exact step over h of u'' + 2 zeta omega u' + kappa omega^2 u = p(t), p linear (kappa = 1
// the elastic oscillator, step_coefficients; kappa = alpha < 1 a yielded bilinear branch, 0 a
// perfectly plastic one), in the time scale of omega. In spectrum.cpp.
StepCoefficients branch_step_coefficients(double omega, double damping, double kappa, double h);

// Feeds `step(p_start, p_end)` the excitation p = -accel over every sub-step: each record
// interval cut into n equal sub-steps, p linear inside it (the sub-step ends computed the same
// way everywhere, so every oscillator sees the same numbers). The vector-lane kernels
// (spectrum_lanes.hpp) keep their own copy of this loop: they are compiled as AVX2 clones,
// into which a call to this template is not inlined (the spectrum ran 6x slower).
template <typename Step>
void for_each_substep(const double* accel, std::size_t samples, std::size_t n, Step&& step) {
  const double inv_n = 1.0 / static_cast<double>(n);
  for (std::size_t i = 0; i + 1 < samples; ++i) {
    const double p0 = -accel[i], p1 = -accel[i + 1];
    if (n == 1) {
      step(p0, p1);
      continue;
    }
    const double dp = (p1 - p0) * inv_n;
    double p = p0;
    for (std::size_t j = 1; j <= n; ++j) {
      const double next = j == n ? p1 : p0 + dp * static_cast<double>(j);
      step(p, next);
      p = next;
    }
  }
}

// Runs `work` (which takes tasks until none are left) on min(wanted, tasks) threads, the
// calling thread included; wanted 0 means std::thread::hardware_concurrency().
template <typename Work>
void run_workers(unsigned wanted, std::size_t tasks, const Work& work) {
  unsigned threads = wanted != 0 ? wanted : std::thread::hardware_concurrency();
  threads = static_cast<unsigned>(std::min<std::size_t>(std::max(threads, 1u), std::max<std::size_t>(tasks, 1)));
  if (threads <= 1) {
    work();
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
}

}  // namespace adjoin::spectrum_detail
