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

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "../detail/simd_clones.hpp"
#include "spectrum_lanes.hpp"

namespace adjoin {

namespace {

using namespace spectrum_detail;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

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
    if (!(t == 0.0 || (t >= 1e-4 && t <= 1e4))) {
      std::ostringstream out;
      out << "spectrum periods must be 0 (the PGA) or from 1e-4 s to 1e4 s, got " << t;
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
  return spectrum_detail::branch_step_coefficients(omega, damping, 1.0, h);
}

StepCoefficients spectrum_detail::branch_step_coefficients(double omega, double damping, double kappa, double h) {
  // Dimensionless time tau = omega t, state [u, du/dtau, P, dP/dtau] with P = p / omega^2
  // linear in tau: u_tautau + 2 zeta u_tau + kappa u = P. Its exponential over theta = omega h
  // gives the exact step; nothing cancels for small theta.
  const double theta = omega * h;
  Mat4 a{0.0, 1.0, 0.0, 0.0,                  //
         -kappa, -2.0 * damping, 1.0, 0.0,    //
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
  spectrum_detail::run_workers(options.threads, groups.size(), work);
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
