#pragma once
// Suites of records: the statistics of their elastic spectra, and scaling a suite to a target
// spectrum over a period band (ASCE 7-16 §16.2.3 style).
//
// Statistics (of PSA, per damping and period, over the n >= 2 records of the suite):
//   mean         the geometric mean exp(m),      m = (1/n) sum_k ln PSA_k
//   median       the sample median of PSA (the mean of the two middle values when n is even)
//   minus1sigma  exp(m - s),  plus1sigma  exp(m + s),  s = the sample standard deviation of
//                ln PSA (divisor n - 1)
// Every PSA must be > 0 (a record of zeros has none): InputError naming the record otherwise.
// One record is refused: its s is undefined (0/0), and a suite of one is just its spectrum.
//
// Scaling (scale_suite). Band: [band_low T1, band_high T1] (0.2 T1 ... 2 T1), or a band given
// directly in seconds [band_from, band_to] (two buildings: 0.2 of the shorter fundamental
// period ... 2 of the longer, as ASCE 7-16 §16.2.3 takes its band over both principal
// directions; adjoin spectrum --band), checked at the spectra's periods inside it (suite_periods adds the band's ends to a period list, so the
// ends are always checked). One factor per record, f_k = c a_k:
//   SuiteScaling::fit      a_k = exp(mean over the band of ln(target / PSA_k)): record k alone
//                          matched to the target in the least-squares sense of ln PSA;
//   SuiteScaling::uniform  a_k = 1 (every record keeps its level relative to the others);
// then one common multiplier c, chosen so that the scaled suite's mean (the geometric mean
// above, of f_k PSA_k) divided by the target has its minimum over the band exactly equal to
// min_ratio (0.9): the suite is at or above 90 % of the target everywhere in the band and no
// higher than it needs to be. The geometric mean is never above the arithmetic mean ASCE 7
// averages, so the code's check on the arithmetic mean holds too.
// Scaling a record by f scales its whole elastic spectrum (sd ... psa) by exactly f (the
// oscillator is linear), so the scaled spectra are f_k times the spectra given.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/post/spectrum.hpp"

namespace adjoin {

struct SuiteStatistics {
  std::vector<double> periods;   // s, as in the spectra
  std::vector<double> dampings;  // ratios
  // damping-major, values[d * periods.size() + i], PSA in g
  std::vector<double> mean, median, minus1sigma, plus1sigma;
};

// The statistics of spectra computed at the same periods and dampings. `names` (one per
// spectrum, or empty: "record k") name the records in messages. `factors` (one per spectrum,
// or empty: all 1) scale each spectrum first. InputError on fewer than two spectra, differing
// periods or dampings, or a PSA that is not > 0.
SuiteStatistics suite_statistics(std::span<const ResponseSpectrum> spectra, std::span<const std::string> names = {},
                                 std::span<const double> factors = {});

// SuiteScaling (fit, uniform): core/enum_names.hpp.

struct SuiteScalingOptions {
  double t1 = 0.0;          // s, the structure's fundamental period, > 0 (or 0 with a band below)
  double band_low = 0.2;    // band [band_low t1, band_high t1], 0 < band_low < band_high
  double band_high = 2.0;
  // Or the band itself [s], 0 < band_from < band_to <= 1e4, with t1 = 0 (one of the two).
  double band_from = 0.0, band_to = 0.0;
  double min_ratio = 0.9;   // the scaled mean's lowest ratio to the target over the band, > 0
  SuiteScaling rule = SuiteScaling::fit;
  std::size_t damping_index = 0;  // the spectra's damping the target is for

  // Checks the values above; names the offending field and what is expected.
  bool IsValid(std::string* error) const;
  // The band [s]: [band_low t1, band_high t1], or [band_from, band_to].
  double band_min() const { return t1 > 0.0 ? band_low * t1 : band_from; }
  double band_max() const { return t1 > 0.0 ? band_high * t1 : band_to; }
};

struct SuiteScale {
  std::vector<double> factors;  // f_k = common * fit_k, one per record
  std::vector<double> fit;      // a_k (all 1 for SuiteScaling::uniform)
  double common = 1.0;          // c
  double band_min = 0.0, band_max = 0.0;  // s
  std::size_t band_periods = 0;           // spectra periods inside the band
  double min_ratio_period = 0.0;          // s, where the scaled mean / target is lowest
  double max_ratio = 0.0;                 // the scaled mean / target at its highest in the band
  double max_ratio_period = 0.0;          // s
};

// Periods for a scaled suite: `periods` with band_low t1 and band_high t1 added (sorted, no
// repeats), so that the band's ends are among the periods checked.
std::vector<double> suite_periods(std::vector<double> periods, const SuiteScalingOptions& options);

// The factors (see the header comment). InputError on invalid options, fewer than two
// spectra, a band not inside the spectra's periods or holding fewer than two of them, a target
// that does not cover the band, or a PSA that is not > 0 in the band.
SuiteScale scale_suite(std::span<const ResponseSpectrum> spectra, const TargetSpectrum& target,
                       const SuiteScalingOptions& options, std::span<const std::string> names = {});

}  // namespace adjoin
