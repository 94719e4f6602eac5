// RotDnn and GMRotI50 spectra of a pair of horizontal components (the method is described in
// adjoin/post/rotd.hpp).
#include "adjoin/post/rotd.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <thread>

#include "adjoin/errors.hpp"
#include "adjoin/model/units.hpp"
#include "adjoin/post/spectrum.hpp"
#include "spectrum_oscillator.hpp"

// The angle loops use GCC vector extensions (two angles a register); the vectors only pass
// between inlined helpers of this file.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace adjoin {

namespace {

using spectrum_detail::kMaxRefineTheta;
using spectrum_detail::kMaxTerms;
using spectrum_detail::taylor_terms;
using spectrum_detail::turning_value;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Two angles a register (SSE2, which every x86-64 has; the 256-bit form without AVX went
// through the stack).
using Vec = double __attribute__((vector_size(16)));
using Mask = long long __attribute__((vector_size(16)));
constexpr std::size_t kLanes = 2;

inline Vec vmax(Vec a, Vec b) { return a > b ? a : b; }
inline Vec vabs(Vec x) { return vmax(x, -x); }
inline Vec splat(double x) { return Vec{x, x}; }

// The angles k * step, k = 0 .. count - 1, with cos and sin padded to whole vectors (the
// padding repeats angle 0, and its peaks are never read).
struct Angles {
  std::size_t count = 0;
  std::size_t blocks = 0;
  double step = 1.0;
  std::vector<Vec> cos, sin;

  explicit Angles(double step_degrees) : step(step_degrees) {
    count = static_cast<std::size_t>(std::llround(180.0 / step_degrees));
    blocks = (count + kLanes - 1) / kLanes;
    cos.assign(blocks, splat(1.0));
    sin.assign(blocks, splat(0.0));
    for (std::size_t k = 0; k < count; ++k) {
      // Exact at the multiples of 90 degrees.
      const double degrees = static_cast<double>(k) * step_degrees;
      double c = std::cos(degrees * std::numbers::pi / 180.0), s = std::sin(degrees * std::numbers::pi / 180.0);
      if (std::abs(degrees - 90.0) < 1e-9) c = 0.0, s = 1.0;
      if (degrees == 0.0) c = 1.0, s = 0.0;
      cos[k / kLanes][k % kLanes] = c;
      sin[k / kLanes][k % kLanes] = s;
    }
  }
  double cos_of(std::size_t k) const { return cos[k / kLanes][k % kLanes]; }
  double sin_of(std::size_t k) const { return sin[k / kLanes][k % kLanes]; }
};

double smallest(const std::vector<Vec>& peaks, std::size_t count) {
  double m = peaks[0][0];
  for (std::size_t k = 1; k < count; ++k) m = std::min(m, peaks[k / kLanes][k % kLanes]);
  return m;
}

// Sampled peaks of |x1 cos + x2 sin| over all points, rotating only the points that can hold
// one. The points farthest out in four directions (0, 45, 90, 135 degrees) give, rotated to
// every angle, a lower bound L of the smallest peak over the angles (RotD00); a point with
// |(x1, x2)| < L is below every angle's peak, so only the points with |(x1, x2)| >= L (a few
// per cent of a record) are rotated.
void sampled_peaks(const double* x1, const double* x2, const double* r2, std::size_t n, const Angles& angles,
                   std::vector<Vec>& peaks) {
  std::array<double, 4> best{};
  std::array<std::size_t, 4> at{};
  for (std::size_t k = 0; k < n; ++k) {
    const double d[4] = {std::abs(x1[k]), std::abs(x1[k] + x2[k]), std::abs(x2[k]), std::abs(x1[k] - x2[k])};
    for (std::size_t j = 0; j < 4; ++j)
      if (d[j] > best[j]) best[j] = d[j], at[j] = k;
  }
  auto rotate = [&](std::size_t k) {
    const Vec a = splat(x1[k]), b = splat(x2[k]);
    for (std::size_t j = 0; j < angles.blocks; ++j)
      peaks[j] = vmax(peaks[j], vabs(a * angles.cos[j] + b * angles.sin[j]));
  };
  for (std::size_t k : at) rotate(k);
  const double floor = smallest(peaks, angles.count), floor2 = floor * floor;
  for (std::size_t k = 0; k < n; ++k)
    if (r2[k] >= floor2) rotate(k);
}

struct Workspace {
  std::vector<double> u1, u2, v1, v2, r2;
  std::vector<Vec> peaks;
};

// The excitation p = -a at sub-step point k (n sub-steps a record interval), as the stepping
// loop computes it.
inline double excitation_at(std::span<const double> a, std::size_t k, std::size_t n, double inv_n) {
  const std::size_t i = k / n, j = k % n;
  if (j == 0) return -a[i];
  const double p0 = -a[i], p1 = -a[i + 1];
  return p0 + (p1 - p0) * inv_n * static_cast<double>(j);
}

// Largest |H| on [0, h] of the cubic Hermite interpolant of (y0, y0') and (y1, y1').
inline double hermite_max(double y0, double d0, double y1, double d1, double h) {
  // H(s) = y0 + d0 s + c2 s^2 + c3 s^3.
  const double delta = (y1 - y0) / h;
  const double c2 = (3.0 * delta - 2.0 * d0 - d1) / h;
  const double c3 = (d0 + d1 - 2.0 * delta) / (h * h);
  double best = std::max(std::abs(y0), std::abs(y1));
  auto consider = [&](double s) {
    if (s > 0.0 && s < h) best = std::max(best, std::abs(y0 + s * (d0 + s * (c2 + s * c3))));
  };
  // H'(s) = d0 + 2 c2 s + 3 c3 s^2.
  const double qa = 3.0 * c3, qb = 2.0 * c2, qc = d0;
  if (std::abs(qa) * h < 1e-12 * (std::abs(qb) + std::abs(qc) / h)) {
    if (qb != 0.0) consider(-qc / qb);
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double root = std::sqrt(disc);
      const double q = -0.5 * (qb + (qb >= 0.0 ? root : -root));
      if (q != 0.0) consider(q / qa), consider(qc / q);
    }
  }
  return best;
}

// Peaks D(theta) [m] of the pair's oscillators (period > 0) at every angle.
void pair_peaks(double dt, std::span<const double> a1, std::span<const double> a2, double period, double zeta,
                const RotDOptions& options, const Angles& angles, const spectrum_detail::ExcitationBounds& bounds,
                Workspace& w) {
  SpectrumOptions so;
  so.points_per_period = options.points_per_period;
  so.max_substeps = options.max_substeps;
  const std::size_t n = spectrum_substeps(dt, period, so);
  const double h = dt / static_cast<double>(n), inv_n = 1.0 / static_cast<double>(n);
  const double omega = kTwoPi / period, c = 2.0 * zeta * omega, w2 = omega * omega;
  const StepCoefficients k = step_coefficients(omega, zeta, h);
  const std::size_t samples = a1.size();
  const std::size_t points = (samples - 1) * n + 1;
  w.u1.resize(points), w.u2.resize(points), w.v1.resize(points), w.v2.resize(points), w.r2.resize(points);
  double* u1 = w.u1.data();
  double* u2 = w.u2.data();
  double* v1 = w.v1.data();
  double* v2 = w.v2.data();
  double* r2 = w.r2.data();
  u1[0] = u2[0] = v1[0] = v2[0] = r2[0] = 0.0;
  // The two oscillators, exactly as Oscillator::step advances one (same operations, so
  // angle 0 reproduces the single component's spectrum).
  double x = 0.0, y = 0.0, vx = 0.0, vy = 0.0;
  std::size_t at = 1;
  for (std::size_t i = 0; i + 1 < samples; ++i) {
    const double p0 = -a1[i], p1 = -a1[i + 1], q0 = -a2[i], q1 = -a2[i + 1];
    const double dp = (p1 - p0) * inv_n, dq = (q1 - q0) * inv_n;
    double p = p0, q = q0;
    for (std::size_t j = 1; j <= n; ++j) {
      const double pn = j == n ? p1 : p0 + dp * static_cast<double>(j);
      const double qn = j == n ? q1 : q0 + dq * static_cast<double>(j);
      const double x1 = k.a_uu * x + k.a_uv * vx + k.b_u0 * p + k.b_u1 * pn;
      const double vx1 = k.a_vu * x + k.a_vv * vx + k.b_v0 * p + k.b_v1 * pn;
      const double y1 = k.a_uu * y + k.a_uv * vy + k.b_u0 * q + k.b_u1 * qn;
      const double vy1 = k.a_vu * y + k.a_vv * vy + k.b_v0 * q + k.b_v1 * qn;
      x = x1, vx = vx1, y = y1, vy = vy1;
      u1[at] = x, v1[at] = vx, u2[at] = y, v2[at] = vy, r2[at] = x * x + y * y;
      ++at;
      p = pn, q = qn;
    }
  }

  w.peaks.assign(angles.blocks, splat(0.0));
  sampled_peaks(u1, u2, r2, points, angles, w.peaks);
  if (!options.refine_peaks || omega * h > kMaxRefineTheta || points < 2) return;

  // Peaks between sub-step points. |u''|, |u'''|, |u''''| of the displacement vector are
  // bounded from the largest excitation, velocity and displacement (p'' = 0 inside a
  // sub-step), with a factor 2 for the sub-steps' interiors.
  const double pmax = bounds.p, slope = bounds.slope;
  double vmax2 = 0.0, rmax2 = 0.0;
  for (std::size_t i = 0; i < points; ++i) {
    vmax2 = std::max(vmax2, v1[i] * v1[i] + v2[i] * v2[i]);
    rmax2 = std::max(rmax2, r2[i]);
  }
  const double b2 = 2.0 * (pmax + c * std::sqrt(vmax2) + w2 * std::sqrt(rmax2));
  const double b3 = 2.0 * (slope + c * b2 + w2 * std::sqrt(vmax2));
  const double b4 = 2.0 * (c * b3 + w2 * b2);
  const double margin2 = 0.125 * h * h * b2;           // max - end values, quadratic bound
  const double margin4 = h * h * h * h / 384.0 * b4;   // cubic Hermite interpolation error
  const int terms = taylor_terms(omega * h);
  std::array<double, kMaxTerms + 4> d{};
  double m = smallest(w.peaks, angles.count);
  // A turning point of the rotated response inside sub-step s at angle index j (lane of the
  // peaks' vector): exact value where it can beat the angle's peak.
  auto consider = [&](std::size_t s, std::size_t j, double r0, double r1, double w0, double w1) {
    // (A copy, written back below: clang binds no reference to a vector-extension element.)
    const double peak = w.peaks[j / kLanes][j % kLanes];
    if (!(w0 * w1 < 0.0) || std::max(std::abs(r0), std::abs(r1)) + margin2 < peak) return false;
    if (hermite_max(r0, w0, r1, w1, h) + margin4 < peak) return false;
    // The exact turning point of the rotated response (as Oscillator::refine).
    const double cl = angles.cos_of(j), sl = angles.sin_of(j);
    const double e0 = excitation_at(a1, s, n, inv_n) * cl + excitation_at(a2, s, n, inv_n) * sl;
    const double e1 = excitation_at(a1, s + 1, n, inv_n) * cl + excitation_at(a2, s + 1, n, inv_n) * sl;
    d[0] = r0;
    d[1] = w0;
    d[2] = e0 - c * d[1] - w2 * d[0];
    d[3] = (e1 - e0) / h - c * d[2] - w2 * d[1];
    for (int q = 4; q < terms + 3; ++q)
      d[static_cast<std::size_t>(q)] = -c * d[static_cast<std::size_t>(q - 1)] - w2 * d[static_cast<std::size_t>(q - 2)];
    const double value = turning_value(d.data(), terms, h, w0, w1);
    if (!(value > peak)) return false;
    w.peaks[j / kLanes][j % kLanes] = value;
    return true;
  };
  constexpr double kDegree = std::numbers::pi / 180.0;
  const auto count = static_cast<std::ptrdiff_t>(angles.count);
  for (std::size_t s = 0; s + 1 < points; ++s) {
    const double reach = std::sqrt(std::max(r2[s], r2[s + 1])) + margin2;
    if (reach < m) continue;
    bool changed = false;
    // The rotated velocity v . e(theta) changes sign inside the sub-step exactly for the angles
    // between the normals to the velocity at its ends: an arc as wide as the velocity turns.
    const double dot = v1[s] * v1[s + 1] + v2[s] * v2[s + 1], cross = v1[s] * v2[s + 1] - v2[s] * v1[s + 1];
    if (dot > 0.0 && std::abs(cross) < 0.25 * dot) {  // turns by less than 14 degrees: the arc only
      const double normal = std::atan2(v2[s], v1[s]) / kDegree + 90.0;
      const double turn = std::atan2(cross, dot) / kDegree;
      const auto first = static_cast<std::ptrdiff_t>(std::floor((normal + std::min(turn, 0.0)) / angles.step)) - 1;
      const auto last = static_cast<std::ptrdiff_t>(std::ceil((normal + std::max(turn, 0.0)) / angles.step)) + 1;
      for (std::ptrdiff_t index = first; index <= last; ++index) {
        const auto j = static_cast<std::size_t>(((index % count) + count) % count);
        const double cs = angles.cos_of(j), sn = angles.sin_of(j);
        changed |= consider(s, j, u1[s] * cs + u2[s] * sn, u1[s + 1] * cs + u2[s + 1] * sn, v1[s] * cs + v2[s] * sn,
                            v1[s + 1] * cs + v2[s + 1] * sn);
      }
    } else {
      const Vec x0 = splat(u1[s]), y0 = splat(u2[s]), x1 = splat(u1[s + 1]), y1 = splat(u2[s + 1]);
      const Vec vx0 = splat(v1[s]), vy0 = splat(v2[s]), vx1 = splat(v1[s + 1]), vy1 = splat(v2[s + 1]);
      for (std::size_t j = 0; j < angles.blocks; ++j) {
        const Vec cs = angles.cos[j], sn = angles.sin[j];
        const Vec r0 = x0 * cs + y0 * sn, r1 = x1 * cs + y1 * sn;
        const Vec w0 = vx0 * cs + vy0 * sn, w1 = vx1 * cs + vy1 * sn;
        const Mask near = (w0 * w1 < 0.0) & (vmax(vabs(r0), vabs(r1)) + margin2 >= w.peaks[j]);
        if ((near[0] | near[1]) == 0) continue;
        for (std::size_t l = 0; l < kLanes; ++l)
          if (near[l] && j * kLanes + l < angles.count) changed |= consider(s, j * kLanes + l, r0[l], r1[l], w0[l], w1[l]);
      }
    }
    if (changed) m = smallest(w.peaks, angles.count);
  }
}

void check_pair(double dt, std::span<const double> a1, std::span<const double> a2) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream out;
    out << "RotD spectrum: the time step must be a positive number, got dt = " << dt;
    throw InputError(out.str());
  }
  if (a1.empty() || a2.empty()) throw InputError("RotD spectrum: a component's acceleration history is empty");
  if (a1.size() != a2.size()) {
    std::ostringstream out;
    out << "RotD spectrum: the two components must have the same number of samples, got " << a1.size() << " and "
        << a2.size() << " (pad the shorter with zeros)";
    throw InputError(out.str());
  }
  for (int comp = 0; comp < 2; ++comp) {
    const std::span<const double> a = comp == 0 ? a1 : a2;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!std::isfinite(a[i])) {
        std::ostringstream out;
        out << "RotD spectrum: component " << comp + 1 << ", acceleration sample " << i << " (t = "
            << static_cast<double>(i) * dt << " s) is not a finite number";
        throw InputError(out.str());
      }
  }
}

}  // namespace

double percentile_linear(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double position = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double f = position - static_cast<double>(below);
  return values[below] + f * (values[above] - values[below]);
}

bool RotDOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  SpectrumOptions so;
  so.periods = periods;
  so.dampings = dampings;
  so.points_per_period = points_per_period;
  so.max_substeps = max_substeps;
  if (!so.IsValid(error)) return false;
  for (double p : percentiles)
    if (!(p >= 0.0 && p <= 100.0)) {
      std::ostringstream out;
      out << "RotD percentiles must be from 0 to 100, got " << p;
      return fail(out.str());
    }
  const double quarter = std::isfinite(angle_step) && angle_step > 0.0 ? 90.0 / angle_step : 0.0;
  if (!(quarter >= 1.0 && quarter <= 900.0) || std::abs(quarter - std::round(quarter)) > 1e-9 * quarter) {
    std::ostringstream out;
    out << "RotD angle step must divide 90 degrees into 1 to 900 equal parts (1 is usual), got " << angle_step;
    return fail(out.str());
  }
  return true;
}

RotatedPeaks rotated_peaks(std::span<const double> x1, std::span<const double> x2, double angle_step) {
  RotDOptions check;
  check.angle_step = angle_step;
  std::string error;
  if (!check.IsValid(&error)) throw InputError(error);
  if (x1.size() != x2.size()) throw InputError("rotated peaks: the two histories must have the same length");
  const Angles angles(angle_step);
  std::vector<double> r2(x1.size());
  for (std::size_t k = 0; k < x1.size(); ++k) r2[k] = x1[k] * x1[k] + x2[k] * x2[k];
  std::vector<Vec> peaks(angles.blocks, splat(0.0));
  sampled_peaks(x1.data(), x2.data(), r2.data(), x1.size(), angles, peaks);
  std::vector<double> values(angles.count);
  for (std::size_t k = 0; k < angles.count; ++k) values[k] = peaks[k / kLanes][k % kLanes];
  RotatedPeaks out;
  const auto lo = std::min_element(values.begin(), values.end()), hi = std::max_element(values.begin(), values.end());
  out.rotd00 = *lo;
  out.rotd100 = *hi;
  out.angle00 = static_cast<double>(lo - values.begin()) * angle_step;
  out.angle100 = static_cast<double>(hi - values.begin()) * angle_step;
  out.rotd50 = percentile_linear(values, 50.0);
  return out;
}

RotDSpectrum rotd_spectrum(double dt, std::span<const double> a1, std::span<const double> a2,
                           const RotDOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  check_pair(dt, a1, a2);
  RotDSpectrum out;
  out.periods = options.periods.empty() ? default_spectrum_periods() : options.periods;
  out.dampings = options.dampings;
  out.percentiles = options.percentiles;
  out.angle_step = options.angle_step;
  const Angles angles(options.angle_step);
  // Bounds of |(p1, p2)| and of its slope over the record, for the peak search's margins.
  spectrum_detail::ExcitationBounds bounds;
  for (std::size_t i = 0; i < a1.size(); ++i) {
    bounds.p = std::max(bounds.p, std::sqrt(a1[i] * a1[i] + a2[i] * a2[i]));
    if (i > 0) {
      const double d1 = a1[i] - a1[i - 1], d2 = a2[i] - a2[i - 1];
      bounds.slope = std::max(bounds.slope, std::sqrt(d1 * d1 + d2 * d2) / dt);
    }
  }
  const std::size_t np = out.periods.size(), total = np * out.dampings.size();
  out.values.resize(total);

  // Peaks at every angle, one (period, damping) a task, longest first.
  std::vector<std::size_t> order(total);
  for (std::size_t t = 0; t < total; ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return out.periods[x % np] < out.periods[y % np]; });
  std::atomic<std::size_t> next{0};
  auto work = [&]() {
    Workspace w;
    for (std::size_t t = next.fetch_add(1); t < total; t = next.fetch_add(1)) {
      const std::size_t task = order[t];
      const double period = out.periods[task % np], zeta = out.dampings[task / np];
      RotDValues& v = out.values[task];
      v.period = period;
      v.damping = zeta;
      v.by_angle.resize(angles.count);
      if (period == 0.0) {
        std::vector<double> r2(a1.size());
        for (std::size_t k = 0; k < a1.size(); ++k) r2[k] = a1[k] * a1[k] + a2[k] * a2[k];
        w.peaks.assign(angles.blocks, splat(0.0));
        sampled_peaks(a1.data(), a2.data(), r2.data(), a1.size(), angles, w.peaks);
        for (std::size_t k = 0; k < angles.count; ++k) v.by_angle[k] = w.peaks[k / kLanes][k % kLanes] / kStandardGravity;
      } else {
        pair_peaks(dt, a1, a2, period, zeta, options, angles, bounds, w);
        const double scale = (kTwoPi / period) * (kTwoPi / period) / kStandardGravity;
        for (std::size_t k = 0; k < angles.count; ++k) v.by_angle[k] = w.peaks[k / kLanes][k % kLanes] * scale;
      }
    }
  };
  spectrum_detail::run_workers(options.threads, total, work);

  // Percentiles and angles.
  const std::size_t quarter = angles.count / 2;  // the angle index of 90 degrees
  for (RotDValues& v : out.values) {
    const auto lo = std::min_element(v.by_angle.begin(), v.by_angle.end());
    const auto hi = std::max_element(v.by_angle.begin(), v.by_angle.end());
    v.rotd00 = *lo;
    v.rotd100 = *hi;
    v.angle00 = static_cast<double>(lo - v.by_angle.begin()) * angles.step;
    v.angle100 = static_cast<double>(hi - v.by_angle.begin()) * angles.step;
    v.rotd50 = percentile_linear(v.by_angle, 50.0);
    for (double p : options.percentiles) v.extra.push_back(percentile_linear(v.by_angle, p));
    v.psa1 = v.by_angle[0];
    v.psa2 = v.by_angle[quarter];
  }

  // GMRotI50, per damping.
  out.gmroti50_angle.assign(out.dampings.size(), 0.0);
  for (std::size_t d = 0; d < out.dampings.size(); ++d) {
    std::vector<double> penalty(quarter, 0.0);
    std::vector<double> gm(quarter);
    std::size_t used = 0;
    for (std::size_t i = 0; i < np; ++i) {
      const RotDValues& v = out.values[d * np + i];
      if (!(v.period > 0.0)) continue;
      for (std::size_t j = 0; j < quarter; ++j) gm[j] = std::sqrt(v.by_angle[j] * v.by_angle[j + quarter]);
      const double median = percentile_linear(gm, 50.0);
      if (!(median > 0.0)) continue;
      for (std::size_t j = 0; j < quarter; ++j) {
        const double r = gm[j] / median - 1.0;
        penalty[j] += r * r;
      }
      ++used;
    }
    const std::size_t best =
        used == 0 ? 0 : static_cast<std::size_t>(std::min_element(penalty.begin(), penalty.end()) - penalty.begin());
    out.gmroti50_angle[d] = static_cast<double>(best) * angles.step;
    for (std::size_t i = 0; i < np; ++i) {
      RotDValues& v = out.values[d * np + i];
      v.gmroti50 = std::sqrt(v.by_angle[best] * v.by_angle[best + quarter]);
    }
  }
  return out;
}

RotDSpectrum rotd_spectrum(const Record& first, const Record& second, const RotDOptions& options) {
  if (!(std::abs(first.dt - second.dt) <= 1e-9 * std::max(first.dt, second.dt))) {
    std::ostringstream out;
    out << "RotD spectrum: the two components must have the same time step, got dt = " << first.dt << " s ("
        << first.source << ") and " << second.dt << " s (" << second.source << ")";
    throw InputError(out.str());
  }
  return rotd_spectrum(first.dt, first.accel, second.accel, options);
}

}  // namespace adjoin
