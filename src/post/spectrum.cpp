// Response spectra by the exact piecewise-linear recursion (Nigam & Jennings 1969), with
// sub-steps at short periods and exact location of peaks between sub-step points.
#include "adjoin/post/spectrum.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <sstream>
#include <thread>

#include "adjoin/errors.hpp"
#include "adjoin/model/units.hpp"
#include "../detail/simd_clones.hpp"

namespace adjoin {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Above this omega h the turning-point search is skipped (only reached through max_substeps,
// where the oscillator follows the excitation quasi-statically).
constexpr double kMaxRefineTheta = 1.6;
constexpr int kMaxTerms = 40;

using Mat4 = std::array<double, 16>;  // row-major

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 c{};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) {
      const double aik = a[static_cast<std::size_t>(4 * i + k)];
      for (int j = 0; j < 4; ++j)
        c[static_cast<std::size_t>(4 * i + j)] += aik * b[static_cast<std::size_t>(4 * k + j)];
    }
  return c;
}

// exp(A) by scaling and squaring with a Taylor series summed to rounding (||A / 2^s|| <= 1/2).
Mat4 expm(Mat4 a) {
  double norm = 0.0;
  for (int i = 0; i < 4; ++i) {
    double row = 0.0;
    for (int j = 0; j < 4; ++j) row += std::abs(a[static_cast<std::size_t>(4 * i + j)]);
    norm = std::max(norm, row);
  }
  int squarings = 0;
  if (norm > 0.5) squarings = static_cast<int>(std::ceil(std::log2(norm / 0.5)));
  const double scale = std::ldexp(1.0, -squarings);
  for (double& x : a) x *= scale;

  Mat4 result{};
  for (int i = 0; i < 4; ++i) result[static_cast<std::size_t>(5 * i)] = 1.0;
  Mat4 term = result;
  for (int k = 1; k <= 30; ++k) {
    term = multiply(term, a);
    double term_norm = 0.0;
    for (double& x : term) {
      x /= static_cast<double>(k);
      term_norm = std::max(term_norm, std::abs(x));
    }
    for (std::size_t i = 0; i < 16; ++i) result[i] += term[i];
    if (term_norm < 1e-18) break;
  }
  for (int s = 0; s < squarings; ++s) result = multiply(result, result);
  return result;
}

constexpr std::array<double, kMaxTerms + 4> inverse_factorials() {
  std::array<double, kMaxTerms + 4> f{};
  double x = 1.0;
  for (std::size_t m = 0; m < f.size(); ++m) {
    if (m > 0) x /= static_cast<double>(m);
    f[m] = x;
  }
  return f;
}
constexpr std::array<double, kMaxTerms + 4> kInverseFactorial = inverse_factorials();

// sum_{m < terms} c[m] s^m / m!  (Horner, multiplications only).
inline double taylor(const double* c, int terms, double s) {
  double r = c[terms - 1] * kInverseFactorial[static_cast<std::size_t>(terms - 1)];
  for (int m = terms - 2; m >= 0; --m) r = r * s + c[m] * kInverseFactorial[static_cast<std::size_t>(m)];
  return r;
}

// Number of Taylor terms for which (theta)^M / M! is below rounding (at least 6).
int taylor_terms(double theta) {
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
double turning_value(const double* c, int terms, double h, double f0, double f1) {
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

ExcitationBounds excitation_bounds(double dt, std::span<const double> accel) {
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

void check_history(double dt, std::span<const double> accel) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream out;
    out << "response spectrum: the time step must be a positive number, got dt = " << dt;
    throw InputError(out.str());
  }
  if (accel.empty()) throw InputError("response spectrum: the acceleration history is empty");
  for (std::size_t i = 0; i < accel.size(); ++i)
    if (!std::isfinite(accel[i])) {
      std::ostringstream out;
      out << "response spectrum: acceleration sample " << i << " (t = " << static_cast<double>(i) * dt
          << " s) is not a finite number";
      throw InputError(out.str());
    }
}

void check_oscillator(double period, double damping) {
  if (!(period >= 0.0) || !std::isfinite(period)) {
    std::ostringstream out;
    out << "response spectrum: period must be a finite number >= 0 s, got " << period;
    throw InputError(out.str());
  }
  if (!(damping >= 0.0 && damping < 1.0)) {
    std::ostringstream out;
    out << "response spectrum: damping ratio must be in [0, 1), got " << damping;
    throw InputError(out.str());
  }
}

struct Task {
  double period;
  double damping;
  std::size_t index;  // into the output
};

SpectralValues rigid(std::span<const double> accel, double damping) {
  SpectralValues out;
  out.damping = damping;
  double pga = 0.0;
  for (double a : accel) pga = std::max(pga, std::abs(a));
  out.sa = out.psa = pga / kStandardGravity;
  return out;
}

// ---- Lane kernels -------------------------------------------------------------------------
//
// Oscillators sharing a sub-step count see the same excitation values, so four of them are
// advanced together, one per lane of a vector register (GCC vector extensions: AVX2 registers
// in the x86-64-v3 clone, pairs of SSE2 registers otherwise), and a group of eight uses two
// registers so that the processor overlaps two independent recursions. Each lane computes
// exactly what Oscillator::step computes, in the same order, so results do not depend on the
// grouping. The near-peak test is done for all lanes at once; the rare lanes that pass it go
// through the scalar Oscillator code and their thresholds are reloaded.
//
// GCC warns that passing these vectors by value has another ABI with and without AVX; they
// only pass between inlined helpers in this file, and the warning is given at the end of the
// file, so it is turned off for the whole file.
#pragma GCC diagnostic ignored "-Wpsabi"

using Vec = double __attribute__((vector_size(32)));
using Mask = long long __attribute__((vector_size(32)));
constexpr int kLanes = 4;

[[gnu::always_inline]] inline Vec vabs(Vec x) { return reinterpret_cast<Vec>(reinterpret_cast<Mask>(x) & 0x7fffffffffffffffLL); }
[[gnu::always_inline]] inline Vec vmax(Vec a, Vec b) { return a > b ? a : b; }
[[gnu::always_inline]] inline bool any(Mask m) { return ((m[0] | m[1]) | (m[2] | m[3])) != 0; }

template <int V>
struct Lanes {
  Vec a_uu[V], a_uv[V], b_u0[V], b_u1[V], a_vu[V], a_vv[V], b_v0[V], b_v1[V], c[V], w2[V];
  Vec u[V], v[V], a[V];

  explicit Lanes(const Oscillator* osc) {
    for (int r = 0; r < V; ++r)
      for (int l = 0; l < kLanes; ++l) {
        const Oscillator& o = osc[r * kLanes + l];
        const StepCoefficients& k = o.coefficients();
        a_uu[r][l] = k.a_uu, a_uv[r][l] = k.a_uv, b_u0[r][l] = k.b_u0, b_u1[r][l] = k.b_u1;
        a_vu[r][l] = k.a_vu, a_vv[r][l] = k.a_vv, b_v0[r][l] = k.b_v0, b_v1[r][l] = k.b_v1;
        c[r][l] = o.damping_term(), w2[r][l] = o.stiffness_term();
        u[r][l] = o.u(), v[r][l] = o.v(), a[r][l] = o.a_abs();
      }
  }
  void store_state(Oscillator* osc) const {
    for (int r = 0; r < V; ++r)
      for (int l = 0; l < kLanes; ++l) osc[r * kLanes + l].set_state(u[r][l], v[r][l], a[r][l]);
  }
};

// Advances the lanes over the record. Refine: peaks located exactly between sub-step points
// (Oscillator::step, four lanes at a time); otherwise peaks at the sub-step points only
// (Oscillator::step_sampled).
template <int V, bool Refine>
[[gnu::always_inline]] inline void advance_lanes(Oscillator* osc, const double* accel, std::size_t samples,
                                                 std::size_t n) {
  Lanes<V> s(osc);
  Vec pu[V], pv[V], pa[V];  // sampled: running peaks
  Vec tu[V], tv[V], ta[V];  // refined: thresholds of the near-peak test
  Vec au[V], av[V], aa[V];  // refined: |u|, |v|, |a_abs| at the start of the sub-step
  auto load_thresholds = [&](int r, int l) {
    const Oscillator& o = osc[r * kLanes + l];
    tu[r][l] = o.threshold_u(), tv[r][l] = o.threshold_v(), ta[r][l] = o.threshold_a();
  };
  for (int r = 0; r < V; ++r) {
    for (int l = 0; l < kLanes; ++l) {
      const Peaks& p = osc[r * kLanes + l].peaks();
      pu[r][l] = p.u, pv[r][l] = p.v, pa[r][l] = p.a;
      load_thresholds(r, l);
    }
    au[r] = vabs(s.u[r]), av[r] = vabs(s.v[r]), aa[r] = vabs(s.a[r]);
  }
  auto step = [&](double p0, double p1) {
    for (int r = 0; r < V; ++r) {
      const Vec u1 = s.a_uu[r] * s.u[r] + s.a_uv[r] * s.v[r] + s.b_u0[r] * p0 + s.b_u1[r] * p1;
      const Vec v1 = s.a_vu[r] * s.u[r] + s.a_vv[r] * s.v[r] + s.b_v0[r] * p0 + s.b_v1[r] * p1;
      const Vec a1 = -(s.c[r] * v1 + s.w2[r] * u1);
      const Vec au1 = vabs(u1), av1 = vabs(v1), aa1 = vabs(a1);
      if constexpr (Refine) {
        const Mask near = (vmax(au[r], au1) >= tu[r]) | (vmax(av[r], av1) >= tv[r]) | (vmax(aa[r], aa1) >= ta[r]);
        if (any(near)) [[unlikely]] {
          for (int l = 0; l < kLanes; ++l) {
            if (!near[l]) continue;
            Oscillator& o = osc[r * kLanes + l];
            o.set_state(s.u[r][l], s.v[r][l], s.a[r][l]);
            o.step_near_peak(p0, p1, u1[l], v1[l], a1[l]);
            load_thresholds(r, l);
          }
        }
        au[r] = au1, av[r] = av1, aa[r] = aa1;
      } else {
        pu[r] = vmax(pu[r], au1);
        pv[r] = vmax(pv[r], av1);
        pa[r] = vmax(pa[r], aa1);
      }
      s.u[r] = u1, s.v[r] = v1, s.a[r] = a1;
    }
  };
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
  s.store_state(osc);
  if constexpr (!Refine)
    for (int r = 0; r < V; ++r)
      for (int l = 0; l < kLanes; ++l) osc[r * kLanes + l].set_peaks(Peaks{pu[r][l], pv[r][l], pa[r][l]});
}

// The entry points, compiled twice where the toolchain can (detail/simd_clones.hpp).

ADJOIN_SIMD_CLONES void sampled_4(Oscillator* o, const double* a, std::size_t m, std::size_t n) { advance_lanes<1, false>(o, a, m, n); }
ADJOIN_SIMD_CLONES void sampled_8(Oscillator* o, const double* a, std::size_t m, std::size_t n) { advance_lanes<2, false>(o, a, m, n); }
ADJOIN_SIMD_CLONES void refined_4(Oscillator* o, const double* a, std::size_t m, std::size_t n) { advance_lanes<1, true>(o, a, m, n); }
ADJOIN_SIMD_CLONES void refined_8(Oscillator* o, const double* a, std::size_t m, std::size_t n) { advance_lanes<2, true>(o, a, m, n); }

constexpr std::size_t kMaxGroup = 2 * kLanes;

// Up to eight oscillators (periods > 0) sharing one sub-step count n. Unused lanes repeat the
// first oscillator and are discarded.
void compute_group(double dt, std::span<const double> accel, const Task* tasks, std::size_t count, std::size_t n,
                   const SpectrumOptions& options, SpectralValues* out) {
  const double h = dt / static_cast<double>(n);
  const ExcitationBounds bounds = excitation_bounds(dt, accel);
  const bool wide = count > static_cast<std::size_t>(kLanes);
  const std::size_t lanes = wide ? kMaxGroup : static_cast<std::size_t>(kLanes);
  auto task = [&](std::size_t k) -> const Task& { return tasks[k < count ? k : 0]; };
  std::array<Oscillator, kMaxGroup> oscillators;
  for (std::size_t k = 0; k < lanes; ++k)
    oscillators[k] = Oscillator(kTwoPi / task(k).period, task(k).damping, h, options.refine_peaks, bounds);
  auto sampled = wide ? sampled_8 : sampled_4;
  if (options.refine_peaks) {
    // Floors: peaks at the samples, one step per record interval.
    std::array<Oscillator, kMaxGroup> coarse;
    for (std::size_t k = 0; k < lanes; ++k)
      coarse[k] = Oscillator(kTwoPi / task(k).period, task(k).damping, dt, false, bounds);
    sampled(coarse.data(), accel.data(), accel.size(), 1);
    for (std::size_t k = 0; k < lanes; ++k) oscillators[k].set_floor(coarse[k].peaks());
    (wide ? refined_8 : refined_4)(oscillators.data(), accel.data(), accel.size(), n);
  } else {
    sampled(oscillators.data(), accel.data(), accel.size(), n);
  }
  for (std::size_t k = 0; k < count; ++k) {
    Oscillator& oscillator = oscillators[k];
    const double period = tasks[k].period, damping = tasks[k].damping;
    if (options.free_vibration) {
      // Extremes of a damped free vibration shrink, so one damped period holds its largest.
      const double damped_period = period / std::sqrt(1.0 - damping * damping);
      const auto steps = static_cast<std::size_t>(std::ceil(damped_period / h)) + 1;
      for (std::size_t j = 0; j < steps; ++j) oscillator.step(0.0, 0.0);
    }
    const double omega = kTwoPi / period;
    const Peaks& peaks = oscillator.peaks();
    SpectralValues& v = out[tasks[k].index];
    v.period = period;
    v.damping = damping;
    v.sd = peaks.u;
    v.sv = peaks.v;
    v.sa = peaks.a / kStandardGravity;
    v.psv = omega * peaks.u;
    v.psa = omega * omega * peaks.u / kStandardGravity;
  }
}

}  // namespace

bool SpectrumOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  for (double t : periods)
    if (!(t >= 0.0) || !std::isfinite(t)) {
      std::ostringstream out;
      out << "spectrum periods must be finite numbers >= 0 s, got " << t;
      return fail(out.str());
    }
  if (dampings.empty()) return fail("spectrum dampings: at least one damping ratio is needed");
  for (double z : dampings)
    if (!(z >= 0.0 && z < 1.0)) {
      std::ostringstream out;
      out << "spectrum damping ratios must be in [0, 1) (0.05 is 5 %), got " << z;
      return fail(out.str());
    }
  if (!(points_per_period >= 4.0) || !std::isfinite(points_per_period)) {
    std::ostringstream out;
    out << "spectrum points_per_period must be a finite number >= 4, got " << points_per_period;
    return fail(out.str());
  }
  if (max_substeps < 1) {
    std::ostringstream out;
    out << "spectrum max_substeps must be >= 1, got " << max_substeps;
    return fail(out.str());
  }
  return true;
}

std::vector<double> period_range(double first, double last, std::size_t count, PeriodSpacing spacing) {
  std::ostringstream out;
  if (!std::isfinite(first) || !std::isfinite(last) || first < 0.0 || first > last) {
    out << "period range: need 0 <= first <= last, got " << first << " to " << last;
    throw InputError(out.str());
  }
  if (count == 0 || (count == 1 && first != last)) {
    out << "period range: need at least 2 periods from " << first << " to " << last << ", got " << count;
    throw InputError(out.str());
  }
  if (spacing == PeriodSpacing::log && first <= 0.0) {
    out << "period range: log spacing needs a first period > 0, got " << first;
    throw InputError(out.str());
  }
  std::vector<double> periods(count, first);
  if (count == 1) return periods;
  const double steps = static_cast<double>(count - 1);
  for (std::size_t i = 1; i + 1 < count; ++i) {
    const double f = static_cast<double>(i) / steps;
    periods[i] = spacing == PeriodSpacing::linear
                     ? first + (last - first) * f
                     : std::exp(std::log(first) + (std::log(last) - std::log(first)) * f);
  }
  periods.back() = last;
  return periods;
}

std::vector<double> default_spectrum_periods() { return period_range(0.01, 10.0, 100, PeriodSpacing::log); }

std::size_t spectrum_substeps(double dt, double period, const SpectrumOptions& options) {
  if (!(period > 0.0)) return 1;
  const double wanted = std::ceil(options.points_per_period * dt / period);
  const double capped = std::min(wanted, static_cast<double>(std::max(options.max_substeps, 1)));
  return static_cast<std::size_t>(std::max(capped, 1.0));
}

StepCoefficients step_coefficients(double omega, double damping, double h) {
  // Dimensionless time tau = omega t, state [u, du/dtau, P, dP/dtau] with P = p / omega^2
  // linear in tau: u_tautau + 2 zeta u_tau + u = P. Its exponential over theta = omega h gives
  // the exact step; nothing cancels for small theta.
  const double theta = omega * h;
  Mat4 a{0.0, 1.0, 0.0, 0.0,                  //
         -1.0, -2.0 * damping, 1.0, 0.0,      //
         0.0, 0.0, 0.0, 1.0,                  //
         0.0, 0.0, 0.0, 0.0};
  for (double& x : a) x *= theta;
  const Mat4 e = expm(a);
  const double w2 = omega * omega;
  StepCoefficients k{};
  k.a_uu = e[0];
  k.a_uv = e[1] / omega;
  k.b_u0 = (e[2] - e[3] / theta) / w2;
  k.b_u1 = e[3] / theta / w2;
  k.a_vu = omega * e[4];
  k.a_vv = e[5];
  k.b_v0 = (e[6] - e[7] / theta) / omega;
  k.b_v1 = e[7] / theta / omega;
  return k;
}

SpectralValues spectral_values(double dt, std::span<const double> accel, double period,
                               double damping, const SpectrumOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  check_history(dt, accel);
  check_oscillator(period, damping);
  if (period == 0.0) return rigid(accel, damping);
  SpectralValues out;
  const Task task{period, damping, 0};
  compute_group(dt, accel, &task, 1, spectrum_substeps(dt, period, options), options, &out);
  return out;
}

ResponseSpectrum response_spectrum(double dt, std::span<const double> accel,
                                   const SpectrumOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  check_history(dt, accel);
  ResponseSpectrum spectrum;
  spectrum.periods = options.periods.empty() ? default_spectrum_periods() : options.periods;
  spectrum.dampings = options.dampings;
  const std::size_t np = spectrum.periods.size();
  const std::size_t total = np * spectrum.dampings.size();
  spectrum.values.resize(total);

  // Oscillators grouped by sub-step count, K at a time; largest cost first, so the last
  // groups handed out are short ones.
  std::vector<Task> tasks;
  tasks.reserve(total);
  for (std::size_t k = 0; k < total; ++k) {
    const double period = spectrum.periods[k % np], damping = spectrum.dampings[k / np];
    if (period == 0.0) {
      spectrum.values[k] = rigid(accel, damping);
      spectrum.values[k].period = 0.0;
    } else {
      tasks.push_back(Task{period, damping, k});
    }
  }
  std::vector<std::size_t> substeps(tasks.size());
  std::vector<std::size_t> order(tasks.size());
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    substeps[k] = spectrum_substeps(dt, tasks[k].period, options);
    order[k] = k;
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return substeps[x] > substeps[y]; });
  std::vector<Task> sorted(tasks.size());
  for (std::size_t k = 0; k < tasks.size(); ++k) sorted[k] = tasks[order[k]];
  struct Group {
    std::size_t first, count, n;
  };
  std::vector<Group> groups;
  for (std::size_t k = 0; k < sorted.size();) {
    const std::size_t n = substeps[order[k]];
    std::size_t count = 1;
    while (count < kMaxGroup && k + count < sorted.size() && substeps[order[k + count]] == n) ++count;
    groups.push_back(Group{k, count, n});
    k += count;
  }
  std::atomic<std::size_t> next{0};
  auto work = [&]() {
    for (std::size_t g = next.fetch_add(1); g < groups.size(); g = next.fetch_add(1))
      compute_group(dt, accel, sorted.data() + groups[g].first, groups[g].count, groups[g].n, options,
                    spectrum.values.data());
  };
  unsigned threads = options.threads != 0 ? options.threads : std::thread::hardware_concurrency();
  threads = static_cast<unsigned>(std::min<std::size_t>(std::max(threads, 1u), std::max<std::size_t>(groups.size(), 1)));
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& thread : pool) thread.join();
  }
  return spectrum;
}

ResponseSpectrum response_spectrum(const Record& record, const SpectrumOptions& options) {
  return response_spectrum(record.dt, record.accel, options);
}

OscillatorHistory oscillator_response(double dt, std::span<const double> accel, double period,
                                      double damping) {
  check_history(dt, accel);
  check_oscillator(period, damping);
  if (period == 0.0) throw InputError("oscillator response: period must be > 0 s");
  const double omega = kTwoPi / period;
  Oscillator oscillator(omega, damping, dt, false, excitation_bounds(dt, accel));
  OscillatorHistory history;
  history.u.reserve(accel.size());
  history.v.reserve(accel.size());
  history.a_abs.reserve(accel.size());
  history.u.push_back(0.0);
  history.v.push_back(0.0);
  history.a_abs.push_back(0.0);
  for (std::size_t i = 0; i + 1 < accel.size(); ++i) {
    oscillator.step(-accel[i], -accel[i + 1]);
    history.u.push_back(oscillator.u());
    history.v.push_back(oscillator.v());
    history.a_abs.push_back(oscillator.a_abs());
  }
  return history;
}

}  // namespace adjoin
