#pragma once
// Orientation-independent response spectra of a pair of horizontal components (RotDnn,
// Boore 2010; GMRotI50, Boore, Watson-Lamprey & Abrahamson 2006).
//
// For each period and damping the two oscillators (one per component, the same period and
// damping) are advanced by the exact piecewise-linear recursion of post/spectrum.hpp, with the
// same sub-steps. The oscillator is linear, so the response to the component rotated by an
// angle theta (from the first component's direction towards the second's),
// a(theta) = a1 cos(theta) + a2 sin(theta), is u(theta) = u1 cos(theta) + u2 sin(theta). For
// each of the angles theta = 0, s, 2 s, ... < 180 degrees (s = angle_step, 1 degree by default
// as in Boore 2010) the peak of |u(theta)| over time is found exactly, as for a single
// component: the largest value at the sub-step points, and where the rotated velocity changes
// sign inside a sub-step close to that peak, the turning point located exactly (Newton on the
// Taylor series of the exact solution). Only the points and sub-steps that can hold a peak
// are rotated: a point with |(u1, u2)| below the smallest peak over the angles found so far
// cannot set any angle's peak, and that bound is found first from the points near the largest
// responses, so the rotations cost a small fraction of the two oscillators.
//
// From the peaks D(theta) [m]: PSA(theta) = omega^2 D(theta) / g; RotD00 and RotD100 are the
// smallest and largest over the angles, with their angles (the first one on ties); RotDnn is
// the nn-th percentile, linear between the sorted values at position nn/100 (n - 1) (RotD50
// with 180 angles is the mean of the 90th and 91st sorted values, the median).
// GMRotI50: GM(theta, T) = sqrt(PSA(theta) PSA(theta + 90)) for theta in [0, 90); GMRotD50(T)
// its median over theta; the single angle theta* minimising the mean over the periods of
// (GM(theta, T) / GMRotD50(T) - 1)^2 (Boore et al. 2006, eq. 2; every period > 0 of the
// spectrum with GMRotD50 > 0 takes part); GMRotI50(T) = GM(theta*, T).
// A period of 0 is the rigid oscillator: the rotated peak ground acceleration at the samples.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

struct RotDOptions {
  // Periods [s], 0 (the PGA) or in [1e-4, 1e4]. Empty: default_spectrum_periods().
  std::vector<double> periods;
  // Damping ratios in [0, 1).
  std::vector<double> dampings{0.05};
  // Percentiles (0..100) reported besides RotD00, RotD50 and RotD100 (RotDValues::extra).
  std::vector<double> percentiles;
  // Angle step [degrees]; 90 / angle_step must be a whole number from 1 to 900.
  double angle_step = 1.0;
  // Sub-steps and exact peaks, as in SpectrumOptions.
  double points_per_period = 10.0;
  int max_substeps = 100;
  bool refine_peaks = true;
  // Worker threads over (period, damping). 0: std::thread::hardware_concurrency().
  unsigned threads = 0;

  // Checks the values above; names the offending field and what is expected.
  bool IsValid(std::string* error) const;
};

struct RotDValues {
  double period = 0.0;    // s
  double damping = 0.0;   // ratio
  double rotd00 = 0.0;    // g (PSA)
  double rotd50 = 0.0;    // g
  double rotd100 = 0.0;   // g
  double angle00 = 0.0;   // degrees from the first component, in [0, 180)
  double angle100 = 0.0;  // degrees
  double gmroti50 = 0.0;  // g
  double psa1 = 0.0;      // g, the first component alone (angle 0)
  double psa2 = 0.0;      // g, the second component alone (angle 90)
  std::vector<double> extra;     // g, at RotDOptions::percentiles
  std::vector<double> by_angle;  // g, PSA at each angle k * angle_step
};

struct RotDSpectrum {
  std::vector<double> periods;           // s
  std::vector<double> dampings;          // ratios
  std::vector<double> percentiles;       // the extra percentiles
  double angle_step = 1.0;               // degrees
  std::vector<double> gmroti50_angle;    // degrees, one per damping
  std::vector<RotDValues> values;        // damping-major: values[d * periods.size() + i]

  const RotDValues& at(std::size_t damping_index, std::size_t period_index) const {
    return values[damping_index * periods.size() + period_index];
  }
};

// The pair a1, a2 [m/s^2], both sampled at dt [s] from t = 0 and of the same length. Throws
// InputError on invalid options, dt <= 0, empty or unequal histories, non-finite samples.
RotDSpectrum rotd_spectrum(double dt, std::span<const double> a1, std::span<const double> a2,
                           const RotDOptions& options = {});
// Records must have the same dt (relative difference at most 1e-9) and length (InputError).
RotDSpectrum rotd_spectrum(const Record& first, const Record& second, const RotDOptions& options = {});

// Rotated peaks of a pair of histories at their samples (PGA, PGV, PGD of a pair): the same
// angles and percentile rule as above, values in the histories' unit.
struct RotatedPeaks {
  double rotd00 = 0.0, rotd50 = 0.0, rotd100 = 0.0;
  double angle00 = 0.0, angle100 = 0.0;  // degrees
};
RotatedPeaks rotated_peaks(std::span<const double> x1, std::span<const double> x2, double angle_step = 1.0);

// The p-th percentile (0..100) of values, linear between sorted values (numpy's default).
double percentile_linear(std::vector<double> values, double p);

}  // namespace adjoin
