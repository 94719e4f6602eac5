#pragma once
// Intensity measures of a recorded accelerogram (Record: accelerations in m/s^2, uniform dt).
//
//  - PGA: max |a|, reported in g (g = 9.80665 m/s^2) and m/s^2, with its time.
//  - PGV, PGD: max |v|, max |d| with v, d the cumulative trapezoid integrals of a and v from
//    rest (v(0) = d(0) = 0). No baseline correction is applied here: process the record first
//    (remove_baseline, a high-pass filter) if its integrals drift.
//  - Arias intensity Ia = pi / (2 g) * integral a^2 dt [m/s], trapezoid rule.
//  - CAV = integral |a| dt [m/s], exact for the piecewise-linear record (a step whose ends have
//    opposite signs is split at its zero crossing).
//  - Husid curve H(t) = cumulative Arias / total (trapezoid); significant duration D5-95 =
//    t(H = 0.95) - t(H = 0.05), the crossing times interpolated linearly between samples.
//  - Fourier amplitude spectrum |A(f)| = dt |sum_n a_n e^{-2 pi i f n dt}| [m/s] at
//    f_k = k / (n dt), k = 0 .. n/2 (FFTW, no padding, no window).
//  - Predominant period: 1 / f at the largest Fourier amplitude with f > 0 [s] (resolution:
//    neighbouring frequencies are 1/(n dt) apart).
//  - Spectrum intensities, from the 5 % response spectrum with exact peaks (post/spectrum.hpp),
//    integrated over the period by composite Simpson's rule on periods 0.005 s apart:
//    Housner's SI = int_{0.1 s}^{2.5 s} PSV dT [m], Von Thun's ASI = int_{0.1 s}^{0.5 s} PSA dT
//    [g s]. Computed only by spectrum_intensity (about 500 oscillators, so not part of
//    intensity_measures).
//  - Konno-Ohmachi smoothing (Konno & Ohmachi 1998) of an amplitude spectrum at centre
//    frequencies fc > 0:  S(fc) = sum_k W_k A_k / sum_k W_k  over the spectrum's f_k > 0, with
//    W_k = [sin(b log10(f_k/fc)) / (b log10(f_k/fc))]^4 (1 at f_k = fc): a window of constant
//    width in log frequency whose first zeros are at fc 10^(+-pi/b); b = 40 is the usual
//    bandwidth, larger is narrower. Summed over every frequency (no truncated window), so the
//    cost is centres x frequencies.
#include <cstddef>
#include <span>
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

struct IntensityMeasures {
  std::size_t npts = 0;
  double dt = 0.0;                  // s
  double duration = 0.0;            // s, (npts - 1) dt
  double pga = 0.0;                 // g
  double pga_m_s2 = 0.0;            // m/s^2
  double t_pga = 0.0;               // s
  double pgv = 0.0;                 // m/s
  double pgd = 0.0;                 // m
  double arias = 0.0;               // m/s
  double cav = 0.0;                 // m/s
  double t5 = 0.0, t95 = 0.0;       // s, Husid 5 % and 95 % times
  double d5_95 = 0.0;               // s
  double predominant_period = 0.0;  // s
};

IntensityMeasures intensity_measures(const Record& record);

// Cumulative trapezoid integral of y sampled at dt, starting from 0 (same length as y).
std::vector<double> cumulative_trapezoid(const std::vector<double>& y, double dt);

double arias_intensity(const Record& record);
double cumulative_absolute_velocity(const Record& record);
// Normalised cumulative Arias intensity at each sample (all zeros for a zero record).
std::vector<double> husid_curve(const Record& record);

struct SignificantDuration {
  double t_start = 0.0, t_end = 0.0, duration = 0.0;  // s
};
// Time between the Husid curve reaching `from` and `to` (fractions, 0 <= from < to <= 1).
SignificantDuration significant_duration(const Record& record, double from = 0.05, double to = 0.95);

struct SpectrumIntensity {
  double housner = 0.0;  // m
  double asi = 0.0;      // g s
};
SpectrumIntensity spectrum_intensity(const Record& record);

struct FourierSpectrum {
  std::vector<double> frequency;  // Hz
  std::vector<double> amplitude;  // m/s
};
FourierSpectrum fourier_amplitude_spectrum(const Record& record);
// Throws InputError for bandwidth <= 0, a centre that is not a finite number > 0, or a
// spectrum without a frequency > 0.
std::vector<double> konno_ohmachi(const FourierSpectrum& spectrum, std::span<const double> centres,
                                  double bandwidth = 40.0);
double predominant_period(const Record& record);

}  // namespace adjoin
