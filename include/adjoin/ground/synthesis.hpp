#pragma once
// Synthetic ground motion: filtered white noise (the `filtered-noise` source, SPEC §2).
//
//     SynthesisOptions o;                       // Clough-Penzien, JHT envelope, 20 s at 0.005 s
//     o.target_pga = 0.3;                       // g (or o.s0 = ... m^2/s^3)
//     o.seed = 7;
//     Record r = synthesize(o);                 // accelerations in m/s^2
//
// Power spectral density (PSD) convention. S(omega) is the TWO-SIDED density of the stationary
// acceleration process over angular frequency omega in (-inf, inf) [rad/s], in m^2/s^3:
//
//     variance = integral_{-inf}^{inf} S(omega) d omega = 2 integral_0^inf S(omega) d omega.
//
// S0 is the two-sided density of the white noise at bedrock, so
//
//     Kanai-Tajimi    S(w) = S0 (wg^4 + 4 zg^2 wg^2 w^2) / ((wg^2 - w^2)^2 + 4 zg^2 wg^2 w^2)
//     Clough-Penzien  S(w) = S_KT(w) * w^4 / ((wf^2 - w^2)^2 + 4 zf^2 wf^2 w^2)
//
// (S_KT(0) = S0; S_KT(wg) = S0 (1 + 4 zg^2) / (4 zg^2); the Kanai-Tajimi variance is
// pi S0 wg (1 + 4 zg^2) / (2 zg); the Clough-Penzien high-pass removes the KT process's
// non-zero density at omega = 0 that makes velocities and displacements grow without bound.)
//
// Construction (frequency domain). n = floor(duration / dt) + 1 samples (the duration is
// rounded down to whole steps); the process is built on an FFT grid of M >= n points, M the
// smallest even number of the form 2^a 3^b 5^c 7^d >= n (synthesis_fft_length), with
// frequencies omega_k = k dw, dw = 2 pi / (M dt), k = 1 .. M/2 - 1 (the mean, k = 0, and the
// Nyquist term are set to zero). For each k, in increasing order, two uniforms
// u = ((x >> 11) + 0.5) 2^-53 in (0, 1) are drawn from std::mt19937_64 seeded with `seed`
// (u1 first), and Box-Muller gives a complex Gaussian  z = sqrt(-2 ln u1) e^{i 2 pi u2}
// (Rayleigh amplitude, uniform phase, E|z|^2 = 2). Then
//
//     x(t_n) = sum_k sqrt(2 S(omega_k) dw) Re[z_k e^{i omega_k t_n}],   t_n = n dt,
//
// evaluated by one inverse real FFT (FFTW, plans cached per length). Each term has variance
// 2 S(omega_k) dw, so Var x = sum_k 2 S(omega_k) dw (discrete_variance) -> integral of S over
// (-pi/dt, pi/dt): the process is Gaussian, stationary (periodic with period M dt), and its
// periodogram (dt / (2 pi M)) |DFT_M(x)|^2 at omega_k has expectation exactly S(omega_k).
// The first n samples are multiplied by the envelope e(t), then (if target_pga is set) scaled
// so that max |a| = target_pga g exactly.
//
// Reproducibility: the integer stream of mt19937_64 and the uniforms above are fixed by the
// C++ standard (no std::normal_distribution, whose algorithm differs between libraries), and
// FFTW is used with FFTW_ESTIMATE plans on fftw_malloc-aligned arrays, so the same seed and
// options give bit-for-bit the same record on a given build; on another platform only the last
// bits of log/sin/cos and of the FFT may differ.
//
// Envelopes (e(t), peak value 1):
//  - jennings_housner_tsai (1968): (t/t1)^2 for t < t1, 1 on [t1, t2], exp(-decay (t - t2))
//    after t2. Defaults from the duration D: t1 = 0.1 D, t2 = 0.5 D, decay = ln(20) / (D - t2)
//    (so e(D) = 0.05).
//  - saragoni_hart (1974, in Boore's 2003 form): e(t) = (e/eps)^b (t/t_n)^b exp(-c t/t_n)
//    with b = -eps ln(eta) / (1 + eps (ln eps - 1)), c = b / eps: its peak, 1, is at
//    t = eps t_n, and e(t_n) = eta. Defaults: eps = 0.2, eta = 0.05, t_n = D.
//  - none: e = 1 (the stationary process).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

// SpectrumModel and EnvelopeKind, with their names: core/enum_names.hpp.
// "kanai-tajimi" (also "kt"), "clough-penzien" ("cp"); "none", "jennings-housner-tsai"
// ("jht"), "saragoni-hart" ("sh"). Underscores are accepted for hyphens. False if unknown.
bool parse_spectrum_model(const std::string& name, SpectrumModel* model);
bool parse_envelope_kind(const std::string& name, EnvelopeKind* kind);

struct Envelope {
  EnvelopeKind kind = EnvelopeKind::jennings_housner_tsai;
  // Jennings-Housner-Tsai [s, s, 1/s]; absent: defaults from the duration (see above).
  std::optional<double> t1, t2, decay;
  // Saragoni-Hart: eps (peak time / t_n), eta (e(t_n)), t_n [s]; absent: defaults.
  std::optional<double> eps, eta, t_n;
};

// The envelope with every absent parameter replaced by its default for this duration [s].
Envelope resolve_envelope(const Envelope& envelope, double duration);
// e(t) of a resolved envelope (every parameter of its kind present).
double envelope_value(const Envelope& resolved, double t);

struct SynthesisOptions {
  SpectrumModel spectrum = SpectrumModel::clough_penzien;  // ground.spectrum
  double omega_g = 15.6;  // rad/s, ground filter frequency          ground.omega_g
  double zeta_g = 0.6;    // ground filter damping                   ground.zeta_g
  double omega_f = 1.5;   // rad/s, Clough-Penzien high-pass         ground.omega_f
  double zeta_f = 0.6;    // Clough-Penzien high-pass damping        ground.zeta_f
  // Intensity: exactly one of the two.
  std::optional<double> s0;          // m^2/s^3, two-sided bedrock density   ground.s0
  std::optional<double> target_pga;  // g, max |a| after the envelope       ground.target_pga
  Envelope envelope;                 // ground.envelope, .t1, .t2, .decay, .eps, .eta, .t_n
  double duration = 20.0;            // s                                    ground.duration
  double dt = 0.005;                 // s                                    ground.dt
  std::uint64_t seed = 1;            //                                      ground.seed

  // Checks the values; on failure writes a message naming the scene key (ground.omega_g, ...)
  // and what is expected, and returns false. Requires omega_g, zeta_g (and for Clough-Penzien
  // omega_f, zeta_f) positive and finite, omega_g (and omega_f) below the Nyquist frequency
  // pi/dt, exactly one of s0 > 0 and target_pga > 0, dt > 0, duration >= dt, at most 2^26
  // samples, and valid envelope parameters (0 <= t1 <= t2, decay > 0; 0 < eps < 1,
  // 0 < eta < 1, t_n > 0).
  bool IsValid(std::string* error) const;
};

// Two-sided PSD S(omega) [m^2/s^3] of the options' spectrum, with S0 = s0 (1 if absent).
double ground_psd(const SynthesisOptions& options, double omega);
double kanai_tajimi_psd(double omega, double omega_g, double zeta_g, double s0);
// The Clough-Penzien high-pass factor w^4 / ((wf^2 - w^2)^2 + 4 zf^2 wf^2 w^2).
double clough_penzien_factor(double omega, double omega_f, double zeta_f);
// integral of the Kanai-Tajimi S over the real line: pi S0 wg (1 + 4 zg^2) / (2 zg).
double kanai_tajimi_variance(double omega_g, double zeta_g, double s0);

// Samples n = floor(duration / dt + 1e-9) + 1, and the FFT length M >= n used for them.
std::size_t synthesis_samples(double duration, double dt);
std::size_t synthesis_fft_length(std::size_t n);
// Variance of the synthesized stationary process, sum_k 2 S(omega_k) dw (S0 = s0, or 1).
double discrete_variance(const SynthesisOptions& options);

// The record (m/s^2, n samples at dt). InputError (message from IsValid) on invalid options.
Record synthesize(const SynthesisOptions& options);

}  // namespace adjoin
