// Intensity measures of recorded accelerograms (see intensity.hpp for the definitions).
#include "adjoin/post/intensity.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <mutex>

#include "../detail/fftw_planner.hpp"
#include <numbers>
#include <sstream>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"

namespace adjoin {
namespace {

void check(const Record& record) {
  if (!(record.dt > 0.0) || !std::isfinite(record.dt))
    throw InputError(record.source + ": the record's dt must be positive (got " + std::to_string(record.dt) + ")");
}

// FFTW's planner is not thread-safe; executing a plan is.

// Time at which the cumulative curve h (non-decreasing) first reaches level, interpolated.
double crossing_time(const std::vector<double>& h, double level, double dt) {
  const auto it = std::lower_bound(h.begin(), h.end(), level);
  if (it == h.end()) return dt * static_cast<double>(h.size() - 1);
  const auto i = static_cast<std::size_t>(it - h.begin());
  if (i == 0) return 0.0;
  const double below = h[i - 1], above = h[i];
  const double fraction = above > below ? (level - below) / (above - below) : 0.0;
  return dt * (static_cast<double>(i - 1) + fraction);
}

}  // namespace

std::vector<double> cumulative_trapezoid(const std::vector<double>& y, double dt) {
  std::vector<double> out(y.size(), 0.0);
  for (std::size_t i = 1; i < y.size(); ++i) out[i] = out[i - 1] + 0.5 * dt * (y[i - 1] + y[i]);
  return out;
}

double arias_intensity(const Record& record) {
  check(record);
  double sum = 0.0;
  const auto& a = record.accel;
  for (std::size_t i = 1; i < a.size(); ++i) sum += 0.5 * (a[i - 1] * a[i - 1] + a[i] * a[i]);
  return std::numbers::pi / (2.0 * kStandardGravity) * sum * record.dt;
}

double cumulative_absolute_velocity(const Record& record) {
  check(record);
  double sum = 0.0;
  const auto& a = record.accel;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const double p = a[i - 1], q = a[i];
    if ((p >= 0.0) == (q >= 0.0) || p == 0.0 || q == 0.0)
      sum += 0.5 * std::abs(p + q);
    else  // the line crosses zero inside the step: two triangles
      sum += 0.5 * (p * p + q * q) / (std::abs(p) + std::abs(q));
  }
  return sum * record.dt;
}

std::vector<double> husid_curve(const Record& record) {
  check(record);
  const auto& a = record.accel;
  std::vector<double> h(a.size(), 0.0);
  for (std::size_t i = 1; i < a.size(); ++i) h[i] = h[i - 1] + 0.5 * (a[i - 1] * a[i - 1] + a[i] * a[i]);
  const double total = h.empty() ? 0.0 : h.back();
  if (total > 0.0)
    for (double& v : h) v /= total;
  return h;
}

SignificantDuration significant_duration(const Record& record, double from, double to) {
  if (!(from >= 0.0 && from < to && to <= 1.0))
    throw InputError("significant duration: expected 0 <= from < to <= 1 (got " + std::to_string(from) + ", " + std::to_string(to) + ")");
  const std::vector<double> h = husid_curve(record);
  SignificantDuration d;
  if (h.size() < 2 || !(h.back() > 0.0)) return d;
  d.t_start = crossing_time(h, from, record.dt);
  d.t_end = crossing_time(h, to, record.dt);
  d.duration = d.t_end - d.t_start;
  return d;
}

FourierSpectrum fourier_amplitude_spectrum(const Record& record) {
  check(record);
  const std::size_t n = record.accel.size();
  FourierSpectrum s;
  if (n == 0) return s;
  const std::size_t m = n / 2 + 1;
  struct Free {
    void operator()(void* p) const { fftw_free(p); }
  };
  std::unique_ptr<double, Free> in(fftw_alloc_real(n));
  std::unique_ptr<fftw_complex, Free> out(fftw_alloc_complex(m));
  if (!in || !out) throw std::bad_alloc();
  fftw_plan plan;
  {
    std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), in.get(), out.get(), FFTW_ESTIMATE);
  }
  std::copy(record.accel.begin(), record.accel.end(), in.get());
  fftw_execute(plan);
  {
    std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    fftw_destroy_plan(plan);
  }
  s.frequency.resize(m);
  s.amplitude.resize(m);
  const double df = 1.0 / (static_cast<double>(n) * record.dt);
  for (std::size_t k = 0; k < m; ++k) {
    s.frequency[k] = df * static_cast<double>(k);
    s.amplitude[k] = record.dt * std::hypot(out.get()[k][0], out.get()[k][1]);
  }
  return s;
}

std::vector<double> konno_ohmachi(const FourierSpectrum& spectrum, std::span<const double> centres,
                                  double bandwidth) {
  if (!(bandwidth > 0.0) || !std::isfinite(bandwidth)) {
    std::ostringstream out;
    out << "Konno-Ohmachi smoothing: the bandwidth b must be a finite number > 0 (40 is usual), got " << bandwidth;
    throw InputError(out.str());
  }
  // log10 of the positive frequencies, once.
  std::vector<double> log_f, amplitude;
  for (std::size_t k = 0; k < spectrum.frequency.size(); ++k)
    if (spectrum.frequency[k] > 0.0) {
      log_f.push_back(std::log10(spectrum.frequency[k]));
      amplitude.push_back(spectrum.amplitude[k]);
    }
  if (log_f.empty()) throw InputError("Konno-Ohmachi smoothing: the spectrum has no frequency > 0");
  std::vector<double> smoothed(centres.size());
  for (std::size_t c = 0; c < centres.size(); ++c) {
    const double fc = centres[c];
    if (!(fc > 0.0) || !std::isfinite(fc)) {
      std::ostringstream out;
      out << "Konno-Ohmachi smoothing: centre frequencies must be finite numbers > 0 Hz, got " << fc;
      throw InputError(out.str());
    }
    const double log_fc = std::log10(fc);
    double weighted = 0.0, total = 0.0;
    for (std::size_t k = 0; k < log_f.size(); ++k) {
      const double x = bandwidth * (log_f[k] - log_fc);
      double w = 1.0;
      if (x != 0.0) {
        const double r = std::sin(x) / x;
        w = (r * r) * (r * r);
      }
      weighted += w * amplitude[k];
      total += w;
    }
    smoothed[c] = weighted / total;
  }
  return smoothed;
}

double predominant_period(const Record& record) {
  const FourierSpectrum s = fourier_amplitude_spectrum(record);
  if (s.frequency.size() < 2) return 0.0;
  const auto peak = std::max_element(s.amplitude.begin() + 1, s.amplitude.end());
  if (!(*peak > 0.0)) return 0.0;
  return 1.0 / s.frequency[static_cast<std::size_t>(peak - s.amplitude.begin())];
}

SpectrumIntensity spectrum_intensity(const Record& record) {
  check(record);
  // One spectrum over 0.1 .. 2.5 s in steps of 0.005 s (480 intervals: even, as Simpson needs);
  // ASI uses its first 80 intervals.
  constexpr std::size_t kIntervals = 480, kAsiIntervals = 80;
  constexpr double kFirst = 0.1, kStep = 0.005;
  SpectrumOptions options;
  options.periods.resize(kIntervals + 1);
  for (std::size_t i = 0; i <= kIntervals; ++i) options.periods[i] = kFirst + kStep * static_cast<double>(i);
  const ResponseSpectrum spectrum = response_spectrum(record, options);
  auto simpson = [&](std::size_t intervals, auto value) {
    double sum = value(0) + value(intervals);
    for (std::size_t i = 1; i < intervals; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * value(i);
    return sum * kStep / 3.0;
  };
  SpectrumIntensity si;
  si.housner = simpson(kIntervals, [&](std::size_t i) { return spectrum.at(0, i).psv; });
  si.asi = simpson(kAsiIntervals, [&](std::size_t i) { return spectrum.at(0, i).psa; });
  return si;
}

IntensityMeasures intensity_measures(const Record& record) {
  check(record);
  IntensityMeasures m;
  const auto& a = record.accel;
  m.npts = a.size();
  m.dt = record.dt;
  m.duration = record.duration();
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i]) > m.pga_m_s2) {
      m.pga_m_s2 = std::abs(a[i]);
      m.t_pga = record.dt * static_cast<double>(i);
    }
  m.pga = m.pga_m_s2 / kStandardGravity;
  const std::vector<double> v = cumulative_trapezoid(a, record.dt);
  const std::vector<double> d = cumulative_trapezoid(v, record.dt);
  for (double x : v) m.pgv = std::max(m.pgv, std::abs(x));
  for (double x : d) m.pgd = std::max(m.pgd, std::abs(x));
  m.arias = arias_intensity(record);
  m.cav = cumulative_absolute_velocity(record);
  const SignificantDuration sd = significant_duration(record);
  m.t5 = sd.t_start;
  m.t95 = sd.t_end;
  m.d5_95 = sd.duration;
  m.predominant_period = predominant_period(record);
  return m;
}

}  // namespace adjoin
