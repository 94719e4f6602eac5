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

// sum_{m < terms} c[m] s^m / m!  (Horner).
inline double taylor(const double* c, int terms, double s) {
  double r = c[terms - 1];
  for (int m = terms - 1; m >= 1; --m) r = c[m - 1] + r * s / static_cast<double>(m);
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

// One oscillator, advanced over sub-steps of length h with p = -a_g linear on each.
class Oscillator {
 public:
  Oscillator(double omega, double zeta, double h, bool refine)
      : k_(step_coefficients(omega, zeta, h)),
        h_(h),
        c_(2.0 * zeta * omega),
        w2_(omega * omega),
        terms_(taylor_terms(omega * h)),
        refine_(refine && omega * h <= kMaxRefineTheta) {}

  // Advance one sub-step from p0 to p1 and update the peaks.
  inline void step(double p0, double p1) {
    const double u1 = k_.a_uu * u_ + k_.a_uv * v_ + k_.b_u0 * p0 + k_.b_u1 * p1;
    const double v1 = k_.a_vu * u_ + k_.a_vv * v_ + k_.b_v0 * p0 + k_.b_v1 * p1;
    const double a1 = -(c_ * v1 + w2_ * u1);  // absolute acceleration u'' + a_g
    if (refine_) {
      // Turning points: u turns where v changes sign, v where u'' = p + a_abs does, and
      // a_abs where its derivative -(c u'' + w2 v) does. Searched only when the turn could
      // beat the running peak: overshoot over the end values <= h^2/8 max|q''| (x2 margin).
      const double r0 = p0 + a_, r1 = p1 + a1;  // relative accelerations u''
      if (v_ * v1 < 0.0) {
        const double bound = 0.25 * h_ * h_ * std::max(std::abs(r0), std::abs(r1));
        if (std::max(std::abs(u_), std::abs(u1)) + bound >= peaks_.u) refine(p0, p1, 0, v_, v1);
      }
      if (r0 * r1 < 0.0) {
        const double slope = (p1 - p0) / h_;
        const double j0 = slope - c_ * r0 - w2_ * v_, j1 = slope - c_ * r1 - w2_ * v1;
        const double bound = 0.25 * h_ * h_ * std::max(std::abs(j0), std::abs(j1));
        if (std::max(std::abs(v_), std::abs(v1)) + bound >= peaks_.v) refine(p0, p1, 1, r0, r1);
      }
      const double g0 = -(c_ * r0 + w2_ * v_), g1 = -(c_ * r1 + w2_ * v1);
      if (g0 * g1 < 0.0) {
        const double slope = (p1 - p0) / h_;
        const double j0 = slope - c_ * r0 - w2_ * v_, j1 = slope - c_ * r1 - w2_ * v1;
        const double q0 = -(c_ * j0 + w2_ * r0), q1 = -(c_ * j1 + w2_ * r1);
        const double bound = 0.25 * h_ * h_ * std::max(std::abs(q0), std::abs(q1));
        if (std::max(std::abs(a_), std::abs(a1)) + bound >= peaks_.a) refine(p0, p1, 2, g0, g1);
      }
    }
    u_ = u1;
    v_ = v1;
    a_ = a1;
    peaks_.u = std::max(peaks_.u, std::abs(u1));
    peaks_.v = std::max(peaks_.v, std::abs(v1));
    peaks_.a = std::max(peaks_.a, std::abs(a1));
  }

  const Peaks& peaks() const { return peaks_; }
  double u() const { return u_; }
  double v() const { return v_; }
  double a_abs() const { return a_; }

 private:
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

  StepCoefficients k_;
  double h_, c_, w2_;
  int terms_;
  bool refine_;
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

SpectralValues compute(double dt, std::span<const double> accel, double period, double damping,
                       const SpectrumOptions& options) {
  SpectralValues out;
  out.period = period;
  out.damping = damping;
  if (period == 0.0) {  // rigid: moves with the ground
    double pga = 0.0;
    for (double a : accel) pga = std::max(pga, std::abs(a));
    out.sa = out.psa = pga / kStandardGravity;
    return out;
  }
  const double omega = kTwoPi / period;
  const std::size_t n = spectrum_substeps(dt, period, options);
  const double h = dt / static_cast<double>(n);
  Oscillator oscillator(omega, damping, h, options.refine_peaks);
  if (n == 1) {
    for (std::size_t i = 0; i + 1 < accel.size(); ++i) oscillator.step(-accel[i], -accel[i + 1]);
  } else {
    const double inv_n = 1.0 / static_cast<double>(n);
    for (std::size_t i = 0; i + 1 < accel.size(); ++i) {
      const double p0 = -accel[i];
      const double dp = (-accel[i + 1] - p0) * inv_n;
      double pa = p0;
      for (std::size_t k = 1; k <= n; ++k) {
        const double pb = k == n ? -accel[i + 1] : p0 + dp * static_cast<double>(k);
        oscillator.step(pa, pb);
        pa = pb;
      }
    }
  }
  if (options.free_vibration) {
    // Extremes of a damped free vibration shrink, so one damped period holds its largest.
    const double damped_period = period / std::sqrt(1.0 - damping * damping);
    const auto steps = static_cast<std::size_t>(std::ceil(damped_period / h)) + 1;
    for (std::size_t k = 0; k < steps; ++k) oscillator.step(0.0, 0.0);
  }
  const Peaks& peaks = oscillator.peaks();
  out.sd = peaks.u;
  out.sv = peaks.v;
  out.sa = peaks.a / kStandardGravity;
  out.psv = omega * peaks.u;
  out.psa = omega * omega * peaks.u / kStandardGravity;
  return out;
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
  return compute(dt, accel, period, damping, options);
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

  // Largest cost first, so the last tasks handed out are short ones.
  std::vector<std::size_t> order(total);
  for (std::size_t k = 0; k < total; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return spectrum_substeps(dt, spectrum.periods[x % np], options) >
           spectrum_substeps(dt, spectrum.periods[y % np], options);
  });
  std::atomic<std::size_t> next{0};
  auto work = [&]() {
    for (std::size_t i = next.fetch_add(1); i < total; i = next.fetch_add(1)) {
      const std::size_t k = order[i];
      spectrum.values[k] = compute(dt, accel, spectrum.periods[k % np], spectrum.dampings[k / np], options);
    }
  };
  unsigned threads = options.threads != 0 ? options.threads : std::thread::hardware_concurrency();
  threads = static_cast<unsigned>(std::min<std::size_t>(std::max(threads, 1u), total));
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
  Oscillator oscillator(omega, damping, dt, false);
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
