#pragma once
// Elastic response spectra of a uniformly sampled acceleration history.
//
// The oscillator is  u'' + 2 zeta omega u' + omega^2 u = -a_g(t),  u(0) = u'(0) = 0,  with
// omega = 2 pi / T, u the displacement relative to the base and a_g the ground (or floor)
// acceleration. a_g is taken piecewise linear between samples, and the oscillator is advanced
// by the exact solution for such an excitation (Nigam & Jennings 1969): a 2x2 recursion whose
// coefficients come from the exponential of the augmented system matrix, so they are exact to
// rounding for every period and damping (no cancellation at long periods).
//
// Peaks: the recursion is exact at any instant, so the only error left is where the peaks are
// looked for. Each record interval is split into n = ceil(points_per_period dt / T) sub-steps
// (at most max_substeps), and where a response quantity turns inside a sub-step close to its
// running peak, the turning point is located exactly (Newton on the Taylor series of the exact
// solution, which for a linear excitation is entire and summed to rounding). Peaks are thus the
// peaks of the exact response to the piecewise-linear excitation, not of a sampled version.
//
// Cost: linear in samples x periods (about 3-4 ns per sample and period at 5 %, one core).
// Oscillators with equal sub-step counts are advanced four or eight at a time in vector
// lanes; every lane computes what one oscillator alone computes, in the same order and
// without fused multiply-adds, so the numbers do not depend on the grouping, the thread
// count or the processor.
//
// Outputs (SpectralValues): sd = max|u| [m], sv = max|u'| [m/s] (true relative velocity),
// sa = max|u'' + a_g| [g] (true absolute acceleration), psv = omega sd [m/s],
// psa = omega^2 sd [g]. A period of 0 is the rigid oscillator: sd = sv = psv = 0, sa = psa = PGA.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

struct SpectrumOptions {
  // Periods [s], each >= 0 (0 is the rigid oscillator). Empty: default_spectrum_periods().
  std::vector<double> periods;
  // Damping ratios, each in [0, 1).
  std::vector<double> dampings{0.05};
  // Sub-step rule: sub-steps h <= T / points_per_period (>= 4). With the exact turning-point
  // search this only sets the Taylor-series length and the search's cost, not the accuracy.
  double points_per_period = 10.0;
  // Cap on sub-steps per record interval (>= 1). Reached only for T < points_per_period dt /
  // max_substeps, where the oscillator follows the excitation quasi-statically and the turning
  // point search is skipped (omega h > 1.6); peaks are then taken at the sub-step points.
  int max_substeps = 100;
  // Locate peaks between sub-step points exactly (true) or take them at the points (false).
  bool refine_peaks = true;
  // Also scan the free vibration for one damped period after the record ends (the peak may
  // come after the excitation at long periods). Off by default: peaks over the record only.
  bool free_vibration = false;
  // Worker threads over (period, damping) pairs. 0: std::thread::hardware_concurrency().
  unsigned threads = 0;

  // Checks the values above; names the offending field and what is expected.
  bool IsValid(std::string* error) const;
};

// PeriodSpacing (linear, log): core/enum_names.hpp.

// `count` periods from `first` to `last` inclusive [s]. Log spacing needs first > 0.
// Throws InputError on first > last, count == 0, or count == 1 with first != last.
std::vector<double> period_range(double first, double last, std::size_t count, PeriodSpacing spacing);
// The default set: 100 log-spaced periods from 0.01 s to 10 s.
std::vector<double> default_spectrum_periods();

struct SpectralValues {
  double period = 0.0;   // s
  double damping = 0.0;  // ratio
  double sd = 0.0;       // m
  double sv = 0.0;       // m/s
  double sa = 0.0;       // g
  double psv = 0.0;      // m/s
  double psa = 0.0;      // g
};

struct ResponseSpectrum {
  std::vector<double> periods;         // s
  std::vector<double> dampings;        // ratios
  std::vector<SpectralValues> values;  // damping-major: values[d * periods.size() + i]

  const SpectralValues& at(std::size_t damping_index, std::size_t period_index) const {
    return values[damping_index * periods.size() + period_index];
  }
};

// The spectrum of accel [m/s^2] sampled at step dt [s] (accel[i] at t = i dt). Throws
// InputError on invalid options, dt <= 0, an empty history or a non-finite sample.
ResponseSpectrum response_spectrum(double dt, std::span<const double> accel,
                                   const SpectrumOptions& options = {});
ResponseSpectrum response_spectrum(const Record& record, const SpectrumOptions& options = {});

// One oscillator (period, damping); options supply the sub-step and peak settings.
SpectralValues spectral_values(double dt, std::span<const double> accel, double period,
                               double damping, const SpectrumOptions& options = {});

// Sub-steps per record interval that spectral_values uses for this period.
std::size_t spectrum_substeps(double dt, double period, const SpectrumOptions& options = {});

// The oscillator's response at the samples: u [m], v = u' [m/s], a_abs = u'' + a_g [m/s^2].
struct OscillatorHistory {
  std::vector<double> u, v, a_abs;
};
// Requires period > 0 and 0 <= damping < 1 (InputError otherwise).
OscillatorHistory oscillator_response(double dt, std::span<const double> accel, double period,
                                      double damping);

// The exact one-step recursion over a step h for u'' + 2 zeta omega u' + omega^2 u = p(t) with
// p linear from p0 to p1:  u1 = a_uu u0 + a_uv v0 + b_u0 p0 + b_u1 p1,  v1 likewise.
struct StepCoefficients {
  double a_uu, a_uv, b_u0, b_u1;
  double a_vu, a_vv, b_v0, b_v1;
};
StepCoefficients step_coefficients(double omega, double damping, double h);

}  // namespace adjoin
