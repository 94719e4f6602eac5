#pragma once
// Fragility curves from incremental dynamic analysis or multiple stripes (SPEC §9): the
// lognormal P(event | IM = x) = Phi(ln(x / theta) / beta) fitted to runs that each say whether
// the event (pounding, a drift limit, a damper's stroke) happened at the record's intensity.
//
//  - Maximum likelihood (Baker 2015): the runs are grouped by IM level; at level j, k_j of n_j
//    runs had the event, and the likelihood is the product of binomial probabilities
//    C(n_j, k_j) p_j^k_j (1 - p_j)^(n_j - k_j), p_j = Phi(ln(x_j / theta) / beta). Maximised
//    over (ln theta, ln beta) by GSL's BFGS from the moments of ln IM under the observed
//    fractions (or a coarse grid's best point, when better), then Newton's method, until the
//    gradient of ln L is below 1e-9 per run; where that fails (a maximum at a very large beta)
//    by Newton's method in the probit coordinates (-ln theta / beta, 1 / beta), where ln L is
//    concave (docs/explanation/fragility.md).
//  - Degenerate data has no maximum: no event at any level, the event at every level, or a
//    perfect separation (no event below some level, the event in every run above it, at most
//    one level in between with a mixed count) drives beta to 0; and fractions that do not
//    grow with IM drive beta to infinity. Such data is reported (fitted = false, problem says
//    which), never given a theta.
//  - Bootstrap (resampling records, each record's runs at every level kept together): the
//    5 % and 95 % percentiles of theta and beta over the resamples that can be fitted.
//  - IM at first event (Vamvatsikos & Cornell 2002; Baker 2015, eq. 2), for IDA traces where
//    each record has its own levels: IM_i = the lowest IM at which record i had the event;
//    theta = exp(mean ln IM_i), beta = the sample standard deviation of ln IM_i (n - 1).
//    A record without the event at any of its levels is censored: left out of the moments
//    and counted (its first event is above its highest level, so theta is then biased low).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace adjoin {

// One run: its record, its intensity (> 0) and whether the event happened.
struct FragilityRun {
  std::string record;
  double im = 0.0;
  bool event = false;
};

// The runs at one IM level.
struct FragilityLevel {
  double im = 0.0;
  std::size_t n = 0, events = 0;
};

// Runs grouped by IM level (equal values; levels within a relative 1e-9 of each other are
// one level), in increasing IM.
std::vector<FragilityLevel> fragility_levels(const std::vector<FragilityRun>& runs);

// True when the records do not share one set of IM levels (IDA traces, hunt and fill).
bool fragility_is_trace(const std::vector<FragilityRun>& runs);

struct FragilityFit {
  bool fitted = false;
  std::string problem;  // why not fitted (fitted = false)
  double theta = std::numeric_limits<double>::quiet_NaN();
  double beta = std::numeric_limits<double>::quiet_NaN();
  double log_likelihood = std::numeric_limits<double>::quiet_NaN();  // with the binomial coefficients
  std::size_t iterations = 0;
};

// Phi(ln(x / theta) / beta).
double fragility_probability(double theta, double beta, double x);
// ln L(theta, beta) of the counts, binomial coefficients included.
double fragility_log_likelihood(const std::vector<FragilityLevel>& levels, double theta, double beta);
// "" when the counts have a maximum-likelihood fit, otherwise why not (see above).
std::string fragility_degeneracy(const std::vector<FragilityLevel>& levels);
// The maximum-likelihood fit; NumericalError if the optimiser fails on data that has a fit.
// `start` (theta, beta): where to start (a bootstrap resample starts at the estimate); without
// it, or if the optimiser fails from there, the start described above.
FragilityFit fit_fragility_mle(const std::vector<FragilityLevel>& levels,
                               std::optional<std::pair<double, double>> start = std::nullopt);

struct FragilityBounds {
  std::size_t samples = 0;     // resamples drawn
  std::size_t degenerate = 0;  // of them, without a fit (left out of the percentiles)
  std::uint64_t seed = 0;
  double theta_low = std::numeric_limits<double>::quiet_NaN(), theta_high = theta_low;  // 5 %, 95 %
  double beta_low = theta_low, beta_high = theta_low;
};
// `samples` resamples of the records (with replacement; GSL's mt19937 seeded with `seed`,
// so the same seed gives the same bounds on every machine). Percentiles interpolate the
// sorted fits linearly (gsl_stats_quantile_from_sorted_data); NaN when fewer than two
// resamples could be fitted.
FragilityBounds bootstrap_fragility(const std::vector<FragilityRun>& runs, std::size_t samples, std::uint64_t seed);

struct FirstEventFit {
  bool fitted = false;
  std::string problem;
  double theta = std::numeric_limits<double>::quiet_NaN();
  double beta = std::numeric_limits<double>::quiet_NaN();
  std::size_t records = 0;   // with an event (in the moments)
  std::size_t censored = 0;  // without one (left out)
  std::vector<std::string> censored_records;
};
// Needs two records with an event and two different first-event IMs.
FirstEventFit fit_first_event(const std::vector<FragilityRun>& runs);

}  // namespace adjoin
