#pragma once
// Inelastic response spectra of a uniformly sampled acceleration history: constant-ductility
// spectra (the yield strength a target ductility needs) and their constant-strength inverse
// (the ductility a given strength gives).
//
// The oscillator: u'' + 2 zeta omega u' + f_s(u)/m = -a_g(t), u(0) = u'(0) = 0, omega = 2 pi / T
// the initial (elastic) frequency, the damping term on the initial stiffness throughout. The
// spring f_s/m = omega^2 (alpha u + (1 - alpha) z), with z the elastic part, |z| <= u_y:
// elastic-perfectly-plastic (alpha = 0) or bilinear with kinematic hardening (alpha = the
// post-yield stiffness ratio, "hardening"). Yield strength f_y/m = omega^2 u_y.
//
// Exactness: a_g is linear between samples (as for the elastic spectra), and on each branch
// (elastic: stiffness omega^2; yielding: alpha omega^2, with a constant force) the oscillator
// is linear, so it is advanced by the exact recursion for that branch (the coefficients from
// the exponential of the branch's system matrix). A branch switch inside a step -- yield when
// |z| reaches u_y, unloading when the velocity reaches zero -- is located exactly (Newton on
// the Taylor series of the branch's exact solution, which is entire and summed to rounding),
// the state carried there, and the rest of the step taken on the new branch. Peaks of |u|
// between steps are located the same way. Sub-steps h <= T / points_per_period only keep the
// Taylor series short; the results do not depend on them beyond rounding.
//
// Ductility mu = max|u| / u_y. Constant ductility: with the elastic strength demand
// f_e/m = omega^2 SD (SD the elastic peak), the strength ratio eta = f_y / f_e is scanned down
// from 1 until mu(eta) reaches the target, each step sized by how far mu is below the target
// (ln(target / mu) / 10 in log eta, from 0.5 % to 10 % in strength); in the first bracket where
// it does, an Illinois (regula falsi) iteration on log mu against log eta finds mu = target to
// the tolerance. So when several strengths give the target, the largest is reported (common
// practice); it can be missed only where mu varies faster than |d log mu / d log eta| = 10 or
// exceeds the target over a band of strengths narrower than 0.5 % (src/post/inelastic.cpp).
// If no eta down to 1e-4 reaches the target, the smallest is
// reported with its ductility: ductility_reached says what was reached in every case.
// Reported: cy = f_y / (m g), u_y [m], R = f_e / f_y = 1 / eta.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "adjoin/core/enum_names.hpp"

namespace adjoin {

// Hysteresis (elastic_perfectly_plastic "epp", bilinear): core/enum_names.hpp.

struct InelasticOptions {
  // Periods [s], each in [1e-4, 1e4]. Empty: default_spectrum_periods() without 0.
  std::vector<double> periods;
  // Damping ratios in [0, 1).
  std::vector<double> dampings{0.05};
  // Target ductilities, each in [1, 100].
  std::vector<double> ductilities{1.0, 1.5, 2.0, 3.0, 4.0, 6.0};
  Hysteresis hysteresis = Hysteresis::elastic_perfectly_plastic;
  // Post-yield stiffness ratio alpha: 0 for elastic-perfectly-plastic, in [0, 1) for bilinear.
  double hardening = 0.0;
  // Sub-steps h <= T / points_per_period (>= 8).
  double points_per_period = 10.0;
  // Relative tolerance on the ductility reached, in [1e-8, 0.1].
  double tolerance = 1e-4;
  // Worker threads over (period, damping). 0: std::thread::hardware_concurrency().
  unsigned threads = 0;

  // Checks the values above; names the offending field and what is expected.
  bool IsValid(std::string* error) const;
};

struct InelasticValues {
  double period = 0.0;             // s
  double damping = 0.0;            // ratio
  double ductility = 0.0;          // the target
  double cy = 0.0;                 // f_y / (m g)
  double uy = 0.0;                 // m
  double R = 1.0;                  // f_e / f_y
  double ductility_reached = 0.0;  // max|u| / u_y at that strength
  double peak_displacement = 0.0;  // m, max|u|
};

struct InelasticSpectrum {
  std::vector<double> periods, dampings, ductilities;
  // values[(d * periods.size() + i) * ductilities.size() + k]
  std::vector<InelasticValues> values;
  const InelasticValues& at(std::size_t damping_index, std::size_t period_index, std::size_t ductility_index) const {
    return values[(damping_index * periods.size() + period_index) * ductilities.size() + ductility_index];
  }
};

// Constant-ductility spectra of accel [m/s^2] at step dt [s]. Throws InputError on invalid
// options, dt <= 0, an empty history or a non-finite sample.
InelasticSpectrum constant_ductility_spectrum(double dt, std::span<const double> accel,
                                              const InelasticOptions& options = {});

// The constant-strength inverse: the ductility demand of an oscillator of given strength,
// stated as the strength reduction factor R = f_e / f_y (> 0) or the yield strength coefficient
// cy = f_y / (m g) (> 0). options.ductilities is not used. values[(d * periods + i) *
// strengths + k], with ductility = ductility_reached = the demand.
enum class StrengthMeasure { reduction_factor, yield_coefficient };
InelasticSpectrum constant_strength_spectrum(double dt, std::span<const double> accel,
                                             const std::vector<double>& strengths, StrengthMeasure measure,
                                             const InelasticOptions& options = {});

// One oscillator: max|u| [m] for the yield displacement uy [m] (> 0; infinity: elastic).
double inelastic_peak_displacement(double dt, std::span<const double> accel, double period, double damping,
                                   double uy, const InelasticOptions& options = {});

}  // namespace adjoin
