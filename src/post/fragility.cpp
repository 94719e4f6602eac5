// Lognormal fragility curves: maximum likelihood on counts per IM level, the bootstrap over
// records, and the IM-at-first-event moments (post/fragility.hpp).
#include "adjoin/post/fragility.hpp"

#include <gsl/gsl_multimin.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sf_erf.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "adjoin/core/errors.hpp"

namespace adjoin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Gradient of ln L (per run) at which the optimiser stops: the estimate is then exact to
// about 1e-9 in ln theta and ln beta (the curvature is of the order of the run count).
constexpr double kGradientTolerance = 1e-9;
// Where BFGS hands over to Newton's method (see fit_fragility_mle).
constexpr double kBfgsTolerance = 1e-5;

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// ln Phi(z), accurate far in both tails.
double log_phi_cdf(double z) { return gsl_sf_log_erfc(-z / M_SQRT2) - M_LN2; }
// phi(z) / Phi(z) (the inverse Mills ratio), without overflow for z far below 0.
double mills(double z) { return std::exp(-0.5 * z * z - 0.5 * std::log(2.0 * M_PI) - log_phi_cdf(z)); }

double log_binomial(std::size_t n, std::size_t k) {
  return std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0);
}

// -ln L (without the binomial coefficients) and its gradient in x = (ln theta, ln beta).
double negative_log_likelihood(const std::vector<FragilityLevel>& levels, double u, double v, double* du, double* dv) {
  const double beta = std::exp(v);
  double f = 0.0, gu = 0.0, gv = 0.0;
  for (const FragilityLevel& l : levels) {
    const double z = (std::log(l.im) - u) / beta;
    const double k = static_cast<double>(l.events), m = static_cast<double>(l.n - l.events);
    if (k > 0) f -= k * log_phi_cdf(z);
    if (m > 0) f -= m * log_phi_cdf(-z);
    // d(ln L)/dz, then dz/du = -1/beta and dz/dv = -z.
    const double dl_dz = (k > 0 ? k * mills(z) : 0.0) - (m > 0 ? m * mills(-z) : 0.0);
    gu += dl_dz / beta;
    gv += dl_dz * z;
  }
  if (du) *du = gu;  // d(-ln L)/du = -dl_dz * (-1/beta)
  if (dv) *dv = gv;
  return f;
}

const std::vector<FragilityLevel>& levels_of(void* params) { return *static_cast<const std::vector<FragilityLevel>*>(params); }

double gsl_f(const gsl_vector* x, void* params) {
  return negative_log_likelihood(levels_of(params), gsl_vector_get(x, 0), gsl_vector_get(x, 1), nullptr, nullptr);
}
void gsl_df(const gsl_vector* x, void* params, gsl_vector* g) {
  double du = 0.0, dv = 0.0;
  negative_log_likelihood(levels_of(params), gsl_vector_get(x, 0), gsl_vector_get(x, 1), &du, &dv);
  gsl_vector_set(g, 0, du);
  gsl_vector_set(g, 1, dv);
}
void gsl_fdf(const gsl_vector* x, void* params, double* f, gsl_vector* g) {
  double du = 0.0, dv = 0.0;
  *f = negative_log_likelihood(levels_of(params), gsl_vector_get(x, 0), gsl_vector_get(x, 1), &du, &dv);
  gsl_vector_set(g, 0, du);
  gsl_vector_set(g, 1, dv);
}

// The start: the observed fractions, made non-decreasing, read as a distribution function of
// ln IM over the levels (the rest of the probability at the highest level); its mean and
// standard deviation (at least 0.1, so the start is never a step). With few runs per level
// (IDA traces: one) that can be far off, so the best point of a coarse grid over the levels'
// range and beta in [0.05, 3] is taken instead when its likelihood is higher: BFGS from a far
// start can take a first step into the flat region beta -> infinity and stall there.
std::pair<double, double> start_point(const std::vector<FragilityLevel>& levels) {
  double previous = 0.0, mean = 0.0, square = 0.0;
  for (std::size_t j = 0; j < levels.size(); ++j) {
    const double p = j + 1 == levels.size() ? 1.0 : std::max(previous, double(levels[j].events) / double(levels[j].n));
    const double w = p - previous, x = std::log(levels[j].im);
    mean += w * x;
    square += w * x * x;
    previous = p;
  }
  std::pair<double, double> best{mean, std::log(std::max(std::sqrt(std::max(0.0, square - mean * mean)), 0.1))};
  double best_f = negative_log_likelihood(levels, best.first, best.second, nullptr, nullptr);
  const double lo = std::log(levels.front().im) - 0.5, hi = std::log(levels.back().im) + 0.5;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 14; ++j) {
      const double u = lo + (hi - lo) * i / 20.0, v = std::log(0.05) + (std::log(3.0) - std::log(0.05)) * j / 14.0;
      const double f = negative_log_likelihood(levels, u, v, nullptr, nullptr);
      if (f < best_f) {
        best_f = f;
        best = {u, v};
      }
    }
  return best;
}

// Newton's method on the gradient of -ln L, with its Hessian by central differences of the
// analytic gradient: from BFGS's end point, where the Hessian is positive definite, it
// converges quadratically. True when |gradient| < tolerance.
bool newton_polish(const std::vector<FragilityLevel>& levels, double tolerance, double& u, double& v, std::size_t& iterations) {
  for (int i = 0; i < 20; ++i) {
    double gu = 0.0, gv = 0.0;
    negative_log_likelihood(levels, u, v, &gu, &gv);
    if (std::hypot(gu, gv) < tolerance) return true;
    ++iterations;
    constexpr double h = 1e-5;
    double a[2], b[2], c[2], d[2];
    negative_log_likelihood(levels, u + h, v, &a[0], &a[1]);
    negative_log_likelihood(levels, u - h, v, &b[0], &b[1]);
    negative_log_likelihood(levels, u, v + h, &c[0], &c[1]);
    negative_log_likelihood(levels, u, v - h, &d[0], &d[1]);
    const double huu = (a[0] - b[0]) / (2 * h), hvv = (c[1] - d[1]) / (2 * h);
    const double huv = 0.5 * ((a[1] - b[1]) / (2 * h) + (c[0] - d[0]) / (2 * h));
    const double det = huu * hvv - huv * huv;
    if (!(huu > 0.0 && det > 0.0)) return false;
    u -= (hvv * gu - huv * gv) / det;
    v -= (huu * gv - huv * gu) / det;
  }
  double gu = 0.0, gv = 0.0;
  negative_log_likelihood(levels, u, v, &gu, &gv);
  return std::hypot(gu, gv) < tolerance;
}

struct Minimizer {
  gsl_multimin_fdfminimizer* s;
  explicit Minimizer(std::size_t n) : s(gsl_multimin_fdfminimizer_alloc(gsl_multimin_fdfminimizer_vector_bfgs2, n)) {}
  ~Minimizer() { gsl_multimin_fdfminimizer_free(s); }
  Minimizer(const Minimizer&) = delete;
  Minimizer& operator=(const Minimizer&) = delete;
};

}  // namespace

std::vector<FragilityLevel> fragility_levels(const std::vector<FragilityRun>& runs) {
  std::vector<FragilityRun> sorted = runs;
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.im < b.im; });
  std::vector<FragilityLevel> levels;
  for (const FragilityRun& r : sorted) {
    if (levels.empty() || r.im > levels.back().im * (1.0 + 1e-9)) levels.push_back({r.im, 0, 0});
    ++levels.back().n;
    levels.back().events += r.event ? 1 : 0;
  }
  return levels;
}

bool fragility_is_trace(const std::vector<FragilityRun>& runs) {
  const std::vector<FragilityLevel> levels = fragility_levels(runs);
  const auto level_of = [&](double im) {
    return std::lower_bound(levels.begin(), levels.end(), im,
                            [](const FragilityLevel& l, double x) { return l.im * (1.0 + 1e-9) < x; }) - levels.begin();
  };
  std::map<std::string, std::vector<long>> per_record;
  for (const FragilityRun& r : runs) per_record[r.record].push_back(level_of(r.im));
  const std::vector<long>* first = nullptr;
  for (auto& [record, set] : per_record) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    if (first && set != *first) return true;
    first = &set;
  }
  return false;
}

double fragility_probability(double theta, double beta, double x) {
  return 0.5 * std::erfc(-std::log(x / theta) / (beta * M_SQRT2));
}

double fragility_log_likelihood(const std::vector<FragilityLevel>& levels, double theta, double beta) {
  double constant = 0.0;
  for (const FragilityLevel& l : levels) constant += log_binomial(l.n, l.events);
  return constant - negative_log_likelihood(levels, std::log(theta), std::log(beta), nullptr, nullptr);
}

std::string fragility_degeneracy(const std::vector<FragilityLevel>& levels) {
  if (levels.empty()) return "no runs";
  std::size_t n = 0, k = 0;
  for (const FragilityLevel& l : levels) {
    n += l.n;
    k += l.events;
  }
  const std::string runs = std::to_string(k) + " of " + std::to_string(n) + " runs at " + std::to_string(levels.size()) +
                           " IM level" + (levels.size() == 1 ? "" : "s");
  if (k == 0)
    return "no run had the event (" + runs + "): theta is above the highest level, " + number(levels.back().im) +
           ", and no fit can say where; add higher levels";
  if (k == n)
    return "every run had the event (" + runs + "): theta is below the lowest level, " + number(levels.front().im) +
           ", and no fit can say where; add lower levels";
  // The first level with an event and the last without one in every run: when no level lies
  // strictly between them on the wrong side, a step function at theta fits every count
  // (a mixed level, if any, at theta itself), and the likelihood grows as beta -> 0.
  std::size_t first_event = 0, last_miss = 0;
  while (levels[first_event].events == 0) ++first_event;
  for (std::size_t j = 0; j < levels.size(); ++j)
    if (levels[j].events < levels[j].n) last_miss = j;
  if (last_miss <= first_event) {
    const std::string where = last_miss == first_event
                                  ? "only the level " + number(levels[first_event].im) + " has runs with and without it"
                                  : "none up to " + number(levels[last_miss].im) + ", every run from " + number(levels[first_event].im);
    return "the levels separate the runs perfectly (" + runs + "; " + where +
           "): the likelihood grows without bound as beta -> 0, so no dispersion can be estimated; add levels "
           "between, or records";
  }
  // Along beta -> infinity (a constant probability, the overall fraction) ln L grows with
  // 1/beta iff the events are positively correlated with ln IM; otherwise its supremum is there.
  const double fraction = double(k) / double(n);
  double covariance = 0.0;
  for (const FragilityLevel& l : levels) covariance += (double(l.events) - double(l.n) * fraction) * std::log(l.im);
  if (covariance <= 0.0)
    return "the fraction of runs with the event does not grow with IM (" + runs +
           "): no increasing lognormal curve fits better than a constant probability";
  return "";
}

namespace {

// BFGS (GSL) from (u, v), then Newton: true with fit->theta, beta when the gradient of ln L
// went below the tolerance.
bool maximise(const std::vector<FragilityLevel>& levels, double u0, double v0, FragilityFit* fit) {
  std::size_t runs = 0;
  for (const FragilityLevel& l : levels) runs += l.n;
  gsl_multimin_function_fdf function{&gsl_f, &gsl_df, &gsl_fdf, 2, const_cast<std::vector<FragilityLevel>*>(&levels)};
  std::unique_ptr<gsl_vector, decltype(&gsl_vector_free)> x(gsl_vector_alloc(2), &gsl_vector_free);
  gsl_vector_set(x.get(), 0, u0);
  gsl_vector_set(x.get(), 1, v0);
  Minimizer m(2);
  // BFGS brings the gradient down to what its line search on ln L can resolve (about
  // sqrt(machine epsilon) relative), restarted from where it stops when it stalls; Newton's
  // method on the gradient then takes it to the tolerance.
  int status = GSL_CONTINUE;
  for (int restart = 0; restart < 5 && status != GSL_SUCCESS; ++restart) {
    gsl_multimin_fdfminimizer_set(m.s, &function, x.get(), 0.1, 0.1);
    for (int iteration = 0; iteration < 500; ++iteration) {
      ++fit->iterations;
      const int step = gsl_multimin_fdfminimizer_iterate(m.s);
      status = gsl_multimin_test_gradient(m.s->gradient, kBfgsTolerance * double(runs));
      if (status == GSL_SUCCESS || step != GSL_SUCCESS) break;
    }
    gsl_vector_memcpy(x.get(), m.s->x);
  }
  double u = gsl_vector_get(x.get(), 0), v = gsl_vector_get(x.get(), 1);
  const bool converged = newton_polish(levels, kGradientTolerance * double(runs), u, v, fit->iterations);
  fit->theta = std::exp(u);
  fit->beta = std::exp(v);
  return converged && std::isfinite(fit->theta) && fit->theta > 0.0 && std::isfinite(fit->beta) && fit->beta > 0.0;
}

}  // namespace

namespace {

// The fallback: Newton's method with a backtracking line search in the probit coordinates
// (a, b) = (-ln theta / beta, 1 / beta), p_j = Phi(a + b ln x_j), where ln L is concave, so it
// converges from any start on data that has a maximum. Used where the maximum lies at a beta so
// large (the fraction hardly grows with IM) that (ln theta, ln beta) are badly scaled. The
// result is (ln theta, ln beta) = (-a / b, -ln b); false if it did not converge.
bool maximise_probit(const std::vector<FragilityLevel>& levels, double u0, double v0, double* u, double* v,
                     std::size_t* iterations) {
  std::size_t runs = 0;
  for (const FragilityLevel& l : levels) runs += l.n;
  const auto log_likelihood = [&](double a, double b) {
    double sum = 0.0;
    for (const FragilityLevel& l : levels) {
      const double z = a + b * std::log(l.im);
      sum += (l.events ? double(l.events) * log_phi_cdf(z) : 0.0) + (l.n > l.events ? double(l.n - l.events) * log_phi_cdf(-z) : 0.0);
    }
    return sum;
  };
  double b = std::exp(-v0), a = -u0 * b;
  for (int i = 0; i < 200; ++i) {
    double g[2] = {0.0, 0.0}, h[3] = {0.0, 0.0, 0.0};  // gradient; Hessian aa, ab, bb
    for (const FragilityLevel& l : levels) {
      const double s = std::log(l.im), z = a + b * s;
      const double k = double(l.events), m = double(l.n - l.events);
      const double up = k > 0 ? mills(z) : 0.0, down = m > 0 ? mills(-z) : 0.0;
      const double dz = k * up - m * down;                           // d ln L / dz
      const double d2z = -k * up * (z + up) - m * down * (down - z);  // d2 ln L / dz2 (< 0)
      g[0] += dz;
      g[1] += dz * s;
      h[0] += d2z;
      h[1] += d2z * s;
      h[2] += d2z * s * s;
    }
    if (std::hypot(g[0], g[1]) < kGradientTolerance * double(runs) && b > 0.0) {
      *u = -a / b;
      *v = -std::log(b);
      return std::isfinite(*u) && std::isfinite(*v);
    }
    ++*iterations;
    const double det = h[0] * h[2] - h[1] * h[1];
    if (!(h[0] < 0.0 && det > 0.0)) return false;
    const double da = -(h[2] * g[0] - h[1] * g[1]) / det, db = -(h[0] * g[1] - h[1] * g[0]) / det;
    const double before = log_likelihood(a, b);
    double step = 1.0;
    while (step > 1e-12 && !(b + step * db > 0.0 && log_likelihood(a + step * da, b + step * db) >= before)) step *= 0.5;
    if (step <= 1e-12) return false;
    a += step * da;
    b += step * db;
  }
  return false;
}

}  // namespace

FragilityFit fit_fragility_mle(const std::vector<FragilityLevel>& levels, std::optional<std::pair<double, double>> start) {
  FragilityFit fit;
  fit.problem = fragility_degeneracy(levels);
  if (!fit.problem.empty()) return fit;
  bool done = start && maximise(levels, std::log(start->first), std::log(start->second), &fit);
  const auto [u0, v0] = start_point(levels);
  if (!done) done = maximise(levels, u0, v0, &fit);
  if (!done) {
    double u = 0.0, v = 0.0;
    done = maximise_probit(levels, u0, v0, &u, &v, &fit.iterations);
    if (done && std::abs(u) > 700.0) {
      // The maximum exists but theta = e^u is beyond double range: as good as no curve.
      fit.problem = "the fraction of runs with the event hardly grows with IM: the likelihood's maximum is at beta = " +
                    number(std::exp(v)) + " and ln theta = " + number(u) + ", a nearly flat curve that says nothing";
      return fit;
    }
    fit.theta = std::exp(u);
    fit.beta = std::exp(v);
  }
  if (!done)
    throw NumericalError("fragility fit: the likelihood's maximiser stopped after " + std::to_string(fit.iterations) +
                         " iterations with a gradient of ln L above " + number(kGradientTolerance) + " per run (at theta = " +
                         number(fit.theta) + ", beta = " + number(fit.beta) + ")", 0.0);
  fit.fitted = true;
  fit.log_likelihood = fragility_log_likelihood(levels, fit.theta, fit.beta);
  return fit;
}

FragilityBounds bootstrap_fragility(const std::vector<FragilityRun>& runs, std::size_t samples, std::uint64_t seed) {
  FragilityBounds bounds;
  bounds.samples = samples;
  bounds.seed = seed;
  const std::vector<FragilityLevel> levels = fragility_levels(runs);
  // Each record's counts at the common levels: a resample adds up whole records.
  std::map<std::string, std::size_t> index;
  std::vector<std::vector<FragilityLevel>> records;
  for (const FragilityRun& r : runs) {
    const auto [it, added] = index.emplace(r.record, records.size());
    if (added) {
      records.push_back(levels);
      for (FragilityLevel& l : records.back()) l.n = l.events = 0;
    }
    auto& own = records[it->second];
    const auto at = std::lower_bound(own.begin(), own.end(), r.im,
                                     [](const FragilityLevel& l, double x) { return l.im * (1.0 + 1e-9) < x; });
    ++at->n;
    at->events += r.event ? 1 : 0;
  }
  if (samples == 0 || records.empty()) return bounds;
  const FragilityFit whole = fit_fragility_mle(levels);
  const std::optional<std::pair<double, double>> estimate =
      whole.fitted ? std::optional<std::pair<double, double>>({whole.theta, whole.beta}) : std::nullopt;

  std::unique_ptr<gsl_rng, decltype(&gsl_rng_free)> rng(gsl_rng_alloc(gsl_rng_mt19937), &gsl_rng_free);
  gsl_rng_set(rng.get(), static_cast<unsigned long>(seed));
  std::vector<double> thetas, betas;
  std::vector<FragilityLevel> sample(levels.size()), used;
  for (std::size_t s = 0; s < samples; ++s) {
    for (FragilityLevel& l : sample) l.n = l.events = 0;
    for (std::size_t r = 0; r < records.size(); ++r) {
      const auto& drawn = records[gsl_rng_uniform_int(rng.get(), records.size())];
      for (std::size_t j = 0; j < sample.size(); ++j) {
        sample[j].im = drawn[j].im;
        sample[j].n += drawn[j].n;
        sample[j].events += drawn[j].events;
      }
    }
    used.clear();
    for (const FragilityLevel& l : sample)
      if (l.n > 0) used.push_back(l);
    // From the estimate of every record's runs: a resample's maximum is near it.
    const FragilityFit fit = fit_fragility_mle(used, estimate);
    if (!fit.fitted) {
      ++bounds.degenerate;
      continue;
    }
    thetas.push_back(fit.theta);
    betas.push_back(fit.beta);
  }
  if (thetas.size() < 2) return bounds;
  std::sort(thetas.begin(), thetas.end());
  std::sort(betas.begin(), betas.end());
  bounds.theta_low = gsl_stats_quantile_from_sorted_data(thetas.data(), 1, thetas.size(), 0.05);
  bounds.theta_high = gsl_stats_quantile_from_sorted_data(thetas.data(), 1, thetas.size(), 0.95);
  bounds.beta_low = gsl_stats_quantile_from_sorted_data(betas.data(), 1, betas.size(), 0.05);
  bounds.beta_high = gsl_stats_quantile_from_sorted_data(betas.data(), 1, betas.size(), 0.95);
  return bounds;
}

FirstEventFit fit_first_event(const std::vector<FragilityRun>& runs) {
  FirstEventFit fit;
  std::vector<std::string> order;
  std::map<std::string, double> first;  // record -> lowest IM with the event (NaN: none)
  for (const FragilityRun& r : runs) {
    const auto [it, added] = first.emplace(r.record, kNaN);
    if (added) order.push_back(r.record);
    if (r.event && !(it->second <= r.im)) it->second = r.im;
  }
  std::vector<double> logs;
  for (const std::string& record : order) {
    const double im = first[record];
    if (std::isnan(im)) {
      fit.censored_records.push_back(record);
    } else {
      logs.push_back(std::log(im));
    }
  }
  fit.records = logs.size();
  fit.censored = fit.censored_records.size();
  if (logs.size() < 2) {
    fit.problem = std::to_string(logs.size()) + " of " + std::to_string(order.size()) +
                  " records had the event: the moments need at least two";
    return fit;
  }
  const double sd = gsl_stats_sd(logs.data(), 1, logs.size());
  if (!(sd > 0.0)) {
    fit.problem = "every record had its first event at the same IM: no dispersion can be estimated";
    return fit;
  }
  fit.fitted = true;
  fit.theta = std::exp(gsl_stats_mean(logs.data(), 1, logs.size()));
  fit.beta = sd;
  return fit;
}

}  // namespace adjoin
