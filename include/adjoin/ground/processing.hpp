#pragma once
// Processing of recorded accelerograms: each function takes a Record and returns a new one
// (accelerations in m/s^2, time origin at the first sample), appending what was done to the
// description. Invalid parameters are an InputError naming the parameter.
//
//  - remove_baseline: subtracts the least-squares polynomial of degree `order` in t (0: the
//    mean; 1: a straight line; ...), fitted in a Legendre basis on [0, duration] (QR).
//  - butterworth: zero-phase Butterworth low-, high- or band-pass. Design: analog prototype
//    of the given order, frequency transformation at corners prewarped by the bilinear
//    transform (2/dt) tan(pi f dt), bilinear transform, second-order sections normalised to
//    unit gain in the passband (DC for low-pass, Nyquist for high-pass, the geometric centre
//    for band-pass; a band-pass of order n has 2n poles). Applied with zero phase and magnitude
//    |H|^2 (what a forward-backward pass gives), so the gain at each corner is exactly 1/2: in
//    the frequency domain (FFTW), which is exact at every order, where the recursive cascade
//    loses its precision once poles crowd z = 1 (high orders, corners far below the sampling
//    rate). The record is extended at both ends by odd reflection over its whole length and
//    its mean passed at the DC gain, then zero-padded: no wrap-around. sosfiltfilt (the
//    recursive pass, as scipy.signal.sosfiltfilt) stays for comparison.
//  - resample: band-limited interpolation with a Kaiser-windowed sinc (beta 8.6, 32 zero
//    crossings each side) whose cut-off is 0.9 of the lower of the old and new Nyquist
//    frequencies, so downsampling is anti-aliased in the same step. Samples outside the
//    record count as zero; the kernel is normalised to unit DC gain. Passband (up to ~0.8 of
//    that Nyquist) flat within ~1e-4. The new record covers [0, duration] on the new grid.
//  - scale_to_pga: multiplies so that max |a| equals the target exactly.
//  - cut_window: keeps the samples with t0 <= t <= t1 (a sample within 1e-9 dt of a bound
//    counts as inside); the first kept sample becomes t = 0.
//  - pad_zeros: round(before/dt) zeros in front, round(after/dt) at the end.
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

Record remove_baseline(const Record& record, int order = 0);

struct ButterworthFilter {
  using Type = FilterType;  // lowpass, highpass, bandpass (core/enum_names.hpp)
  Type type = Type::bandpass;
  double f_low = 0.0;   // Hz: high-pass corner, or band-pass lower corner
  double f_high = 0.0;  // Hz: low-pass corner, or band-pass upper corner
  int order = 4;        // of the analog prototype, 1..20 (per pass)
};

// One second-order section, a0 = 1: H(z) = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2).
struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
};

std::vector<Biquad> butterworth_sections(const ButterworthFilter& filter, double dt);
// Frequency response of one pass of the cascade at f [Hz].
std::complex<double> frequency_response(const std::vector<Biquad>& sections, double f, double dt);
// One causal pass (direct form II transposed), from rest.
std::vector<double> sosfilt(const std::vector<Biquad>& sections, const std::vector<double>& x);
// Zero-phase forward-backward pass with odd-reflection padding (see above).
std::vector<double> sosfiltfilt(const std::vector<Biquad>& sections, const std::vector<double>& x);

Record butterworth(const Record& record, const ButterworthFilter& filter);
Record resample(const Record& record, double dt);
Record scale_to_pga(const Record& record, double pga_m_s2);
Record cut_window(const Record& record, double t0, double t1);
Record pad_zeros(const Record& record, double before_s, double after_s);

// Everything a scene can ask for, applied in this order: window, baseline, padding, filter,
// resampling, scaling (scaling last, so the target PGA holds for what the solver sees).
struct Processing {
  std::optional<double> window_t0, window_t1;  // s; either may be absent (record start / end)
  std::optional<int> baseline_order;
  double pad_before = 0.0, pad_after = 0.0;  // s
  std::optional<ButterworthFilter> filter;
  std::optional<double> dt;              // s, resample to this step
  std::optional<double> target_pga;      // m/s^2
};
Record process(const Record& record, const Processing& processing);

// The values of a Processing a caller may name its own way (a command-line option, a scene key).
enum class ProcessingField { window_start, window_end, baseline, pad_before, pad_after, filter_order, f_low, f_high, resample_dt, scale_pga };
struct ProcessingProblem {
  ProcessingField field;
  std::string message;  // what is wrong and the range that works, without the field's name
};
// One validation for every caller (record process, scenes): each value finite and in its
// range for this record (corners between 1 / (10 x duration) and the Nyquist frequency, orders
// 1..20, steps and PGA positive), and the samples it would make within `memory_bytes` (0: not
// checked). The first problem found, or none.
std::optional<ProcessingProblem> check_processing(const Processing& processing, const Record& record, double memory_bytes = 0.0);

}  // namespace adjoin
