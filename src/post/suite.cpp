// Suites of records: log statistics of their spectra and scaling to a target (see suite.hpp).
#include "adjoin/post/suite.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "adjoin/core/errors.hpp"

namespace adjoin {
namespace {

std::string name_of(std::span<const std::string> names, std::size_t k) {
  return k < names.size() ? names[k] : "record " + std::to_string(k + 1);
}

// The spectra must share periods and dampings: the statistics are taken period by period.
void check_suite(std::span<const ResponseSpectrum> spectra, std::span<const std::string> names,
                 std::span<const double> factors) {
  if (spectra.size() < 2)
    throw InputError("a suite needs at least two records (the standard deviation of one is undefined), got " +
                     std::to_string(spectra.size()));
  if (!names.empty() && names.size() != spectra.size())
    throw InputError("suite: " + std::to_string(names.size()) + " names for " + std::to_string(spectra.size()) + " spectra");
  if (!factors.empty() && factors.size() != spectra.size())
    throw InputError("suite: " + std::to_string(factors.size()) + " factors for " + std::to_string(spectra.size()) +
                     " spectra");
  for (double f : factors)
    if (!(f > 0.0) || !std::isfinite(f)) throw InputError("suite: scale factors must be positive and finite");
  for (std::size_t k = 1; k < spectra.size(); ++k)
    if (spectra[k].periods != spectra[0].periods || spectra[k].dampings != spectra[0].dampings)
      throw InputError("suite: " + name_of(names, k) + " has other periods or dampings than " + name_of(names, 0));
}

// ln PSA, refusing the PSA <= 0 that a log cannot take (a record of zeros, a rigid oscillator
// on a record with no motion).
double log_psa(const ResponseSpectrum& s, std::size_t d, std::size_t i, std::span<const std::string> names,
               std::size_t k) {
  const SpectralValues& v = s.at(d, i);
  if (!(v.psa > 0.0) || !std::isfinite(v.psa)) {
    std::ostringstream out;
    out << name_of(names, k) << ": PSA is " << v.psa << " g at T = " << v.period << " s, damping " << v.damping
        << ": the suite's statistics are taken in log and need PSA > 0 (is the record all zeros?)";
    throw InputError(out.str());
  }
  return std::log(v.psa);
}

void require_finite(double value, const char* what, double period) {
  if (std::isfinite(value)) return;
  std::ostringstream out;
  out << "suite: the " << what << " at T = " << period << " s is " << value
      << " (the spectra's values overflow; check the records' units)";
  throw NumericalError(out.str(), 0.0);
}

}  // namespace

SuiteStatistics suite_statistics(std::span<const ResponseSpectrum> spectra, std::span<const std::string> names,
                                 std::span<const double> factors) {
  check_suite(spectra, names, factors);
  SuiteStatistics out;
  out.periods = spectra[0].periods;
  out.dampings = spectra[0].dampings;
  const std::size_t n = spectra.size(), np = out.periods.size(), total = np * out.dampings.size();
  out.mean.resize(total);
  out.median.resize(total);
  out.minus1sigma.resize(total);
  out.plus1sigma.resize(total);
  std::vector<double> logs(n), values(n);
  for (std::size_t d = 0; d < out.dampings.size(); ++d)
    for (std::size_t i = 0; i < np; ++i) {
      double sum = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        const double f = factors.empty() ? 1.0 : factors[k];
        logs[k] = log_psa(spectra[k], d, i, names, k) + std::log(f);
        values[k] = f * spectra[k].at(d, i).psa;
        sum += logs[k];
      }
      const double m = sum / static_cast<double>(n);
      double squares = 0.0;  // two passes: no cancellation when the spread is small
      for (double x : logs) squares += (x - m) * (x - m);
      const double s = std::sqrt(squares / static_cast<double>(n - 1));
      std::sort(values.begin(), values.end());
      const double median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
      const std::size_t at = d * np + i;
      out.mean[at] = std::exp(m);
      out.median[at] = median;
      out.minus1sigma[at] = std::exp(m - s);
      out.plus1sigma[at] = std::exp(m + s);
      for (double v : {out.mean[at], median, out.minus1sigma[at], out.plus1sigma[at]})
        require_finite(v, "suite statistics", out.periods[i]);
    }
  return out;
}

bool SuiteScalingOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  const bool band = band_from != 0.0 || band_to != 0.0;
  if (band && t1 != 0.0) return fail("t1, band_from, band_to: give the fundamental period t1 or the band, not both");
  if (band && !(band_from > 0.0 && band_from < band_to && band_to <= 1e4))
    return fail("band_from, band_to: expected a band of periods in s, 0 < band_from < band_to <= 1e4");
  if (band) return min_ratio > 0.0 && std::isfinite(min_ratio) ? true : fail("min_ratio: expected a ratio > 0, e.g. 0.9");
  if (!(t1 > 0.0 && t1 <= 1e4)) return fail("t1: expected the fundamental period in s, 0 < T1 <= 1e4");
  if (!(band_low > 0.0 && band_low < band_high && std::isfinite(band_high)))
    return fail("band_low, band_high: expected 0 < band_low < band_high (multiples of T1, e.g. 0.2 and 2)");
  if (!(min_ratio > 0.0 && std::isfinite(min_ratio))) return fail("min_ratio: expected a ratio > 0, e.g. 0.9");
  return true;
}

std::vector<double> suite_periods(std::vector<double> periods, const SuiteScalingOptions& options) {
  std::string error;
  if (!options.IsValid(&error) || periods.empty()) return periods;
  const auto [lo, hi] = std::minmax_element(periods.begin(), periods.end());
  const double first = *lo, last = *hi;
  // Only inside the periods asked for: a band outside them is an error for scale_suite to
  // report, not a reason to compute periods nobody asked for.
  for (double end : {options.band_min(), options.band_max()})
    if (end >= first && end <= last && std::find(periods.begin(), periods.end(), end) == periods.end())
      periods.push_back(end);
  std::sort(periods.begin(), periods.end());
  periods.erase(std::unique(periods.begin(), periods.end()), periods.end());
  return periods;
}

SuiteScale scale_suite(std::span<const ResponseSpectrum> spectra, const TargetSpectrum& target,
                       const SuiteScalingOptions& options, std::span<const std::string> names) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError("suite scaling: " + error);
  check_suite(spectra, names, {});
  const ResponseSpectrum& first = spectra[0];
  if (options.damping_index >= first.dampings.size()) throw InputError("suite scaling: damping_index out of range");
  SuiteScale out;
  out.band_min = options.band_min();
  out.band_max = options.band_max();
  std::ostringstream band;
  if (options.t1 > 0.0) band << options.band_low << " T1 ... " << options.band_high << " T1 = ";
  band << out.band_min << " ... " << out.band_max << " s";
  const auto [lo, hi] = std::minmax_element(first.periods.begin(), first.periods.end());
  if (out.band_min < *lo || out.band_max > *hi) {
    std::ostringstream m;
    m << "the band " << band.str() << " is not inside the periods computed (" << *lo << " ... " << *hi << " s)";
    throw InputError(m.str());
  }
  if (out.band_min < target.min_period() || out.band_max > target.max_period()) {
    std::ostringstream m;
    m << "the target " << target.name << " covers " << target.min_period() << " ... " << target.max_period()
      << " s, not the band " << band.str();
    throw InputError(m.str());
  }
  std::vector<std::size_t> in_band;
  for (std::size_t i = 0; i < first.periods.size(); ++i)
    if (first.periods[i] >= out.band_min && first.periods[i] <= out.band_max) in_band.push_back(i);
  out.band_periods = in_band.size();
  if (in_band.size() < 2)
    throw InputError("the band " + band.str() + " holds " + std::to_string(in_band.size()) +
                     " of the periods computed (at least 2 are needed: give more periods)");

  const std::size_t d = options.damping_index, n = spectra.size();
  const double zeta = first.dampings[d];
  std::vector<double> log_target;
  for (std::size_t i : in_band) log_target.push_back(std::log(target.psa_at(first.periods[i], zeta)));

  // a_k: the mean log misfit of record k over the band (its least-squares level in ln PSA).
  std::vector<double> log_fit(n, 0.0);
  if (options.rule == SuiteScaling::fit)
    for (std::size_t k = 0; k < n; ++k) {
      double sum = 0.0;
      for (std::size_t j = 0; j < in_band.size(); ++j)
        sum += log_target[j] - log_psa(spectra[k], d, in_band[j], names, k);
      log_fit[k] = sum / static_cast<double>(in_band.size());
    }
  // ln(mean / target) of the suite scaled by a_k, per band period; c lifts its minimum to
  // min_ratio. Scaling every record by c scales the geometric mean by exactly c.
  std::vector<double> log_ratio(in_band.size());
  for (std::size_t j = 0; j < in_band.size(); ++j) {
    double sum = 0.0;
    for (std::size_t k = 0; k < n; ++k) sum += log_fit[k] + log_psa(spectra[k], d, in_band[j], names, k);
    log_ratio[j] = sum / static_cast<double>(n) - log_target[j];
  }
  const auto low = std::min_element(log_ratio.begin(), log_ratio.end());
  const auto high = std::max_element(log_ratio.begin(), log_ratio.end());
  const double log_common = std::log(options.min_ratio) - *low;
  out.common = std::exp(log_common);
  out.min_ratio_period = first.periods[in_band[static_cast<std::size_t>(low - log_ratio.begin())]];
  out.max_ratio_period = first.periods[in_band[static_cast<std::size_t>(high - log_ratio.begin())]];
  out.max_ratio = std::exp(*high + log_common);
  for (std::size_t k = 0; k < n; ++k) {
    out.fit.push_back(std::exp(log_fit[k]));
    out.factors.push_back(std::exp(log_common + log_fit[k]));
    require_finite(out.factors.back(), "scale factor", out.min_ratio_period);
  }
  require_finite(out.max_ratio, "scaled mean / target", out.max_ratio_period);
  return out;
}

}  // namespace adjoin
