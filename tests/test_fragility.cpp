// Fragility curves (post/fragility.hpp, post/fragility_event.hpp, `adjoin fragility`): the
// maximum-likelihood fit against a direct maximisation of the binomial likelihood over a
// (theta, beta) grid written here, data with a known answer, the bootstrap, degenerate data,
// the IM-at-first-event moments, event expressions and the command end to end.
#include <catch2/catch.hpp>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/post/fragility.hpp"
#include "adjoin/post/fragility_event.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"
#include "png_check.hpp"

using namespace adjoin;
using adjoin::test::needs_program;
using adjoin::test::run_cli;
using adjoin::test::shell_word;
using adjoin::test::slurp;
using adjoin::test::write_temp;
namespace fs = std::filesystem;

namespace {

// ln L of the counts as this test computes it: binomial probabilities with Phi from erfc.
double grid_log_likelihood(const std::vector<FragilityLevel>& levels, double ln_theta, double ln_beta) {
  double sum = 0.0;
  for (const FragilityLevel& l : levels) {
    const double p = 0.5 * std::erfc(-(std::log(l.im) - ln_theta) / (std::exp(ln_beta) * std::sqrt(2.0)));
    const double k = double(l.events), m = double(l.n - l.events);
    sum += std::lgamma(l.n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(m + 1.0);
    if (k > 0) sum += k * std::log(p);
    if (m > 0) sum += m * std::log1p(-p);
  }
  return sum;
}

// The maximiser by brute force: a 41 x 41 grid over ln theta within 6 of the middle level's
// ln IM and ln beta within 4 of ln 0.5, then a grid 3 times finer around its best point (wide
// enough to follow a likelihood whose ridge is long and oblique), until
// the spacing is below 1e-9.
constexpr double kGridHalfU = 6.0, kGridHalfV = 4.0;
std::pair<double, double> grid_maximum(const std::vector<FragilityLevel>& levels) {
  double cu = std::log(levels[levels.size() / 2].im), cv = std::log(0.5), half_u = kGridHalfU, half_v = kGridHalfV;
  while (half_u > 1e-9) {
    double best = -INFINITY, bu = cu, bv = cv;
    for (int i = -20; i <= 20; ++i)
      for (int j = -20; j <= 20; ++j) {
        const double u = cu + half_u * i / 20.0, v = cv + half_v * j / 20.0;
        const double l = grid_log_likelihood(levels, u, v);
        if (l > best) {
          best = l;
          bu = u;
          bv = v;
        }
      }
    cu = bu;
    cv = bv;
    half_u /= 3.0;
    half_v /= 3.0;
  }
  return {std::exp(cu), std::exp(cv)};
}

std::vector<FragilityLevel> counts(const std::vector<double>& im, std::size_t n, const std::vector<std::size_t>& events) {
  std::vector<FragilityLevel> levels;
  for (std::size_t j = 0; j < im.size(); ++j) levels.push_back({im[j], n, events[j]});
  return levels;
}

// Runs of `records` records at every level; record r has the event at and above its capacity
// theta exp(beta z_r), z_r the standard normal's (r + 0.5) / records quantile.
std::vector<FragilityRun> stripes(std::size_t records, const std::vector<double>& im, double theta, double beta) {
  std::vector<FragilityRun> runs;
  for (std::size_t r = 0; r < records; ++r) {
    const double capacity = theta * std::exp(beta * gsl_cdf_ugaussian_Pinv((r + 0.5) / double(records)));
    for (double x : im) runs.push_back({"rec" + std::to_string(r), x, x >= capacity});
  }
  return runs;
}

const std::vector<double> kLevels{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0};

}  // namespace

TEST_CASE("fragility: the maximum-likelihood fit equals a direct maximisation over a grid", "[fragility]") {
  // Irregular counts (not a curve's expected values), 20 runs per level.
  const auto levels = counts(kLevels, 20, {0, 1, 4, 7, 12, 13, 18, 19});
  const FragilityFit fit = fit_fragility_mle(levels);
  REQUIRE(fit.fitted);
  const auto [theta, beta] = grid_maximum(levels);
  CHECK(fit.theta == Approx(theta).epsilon(1e-4));
  CHECK(fit.beta == Approx(beta).epsilon(1e-4));
  CHECK(fit.log_likelihood == Approx(grid_log_likelihood(levels, std::log(theta), std::log(beta))).epsilon(1e-9));
  // The reported ln L is the binomial likelihood, coefficients included.
  CHECK(fragility_log_likelihood(levels, fit.theta, fit.beta) == Approx(fit.log_likelihood).epsilon(1e-12));

  // Uneven run counts per level, a level with one run.
  std::vector<FragilityLevel> uneven{{0.15, 5, 0}, {0.3, 12, 2}, {0.45, 1, 1}, {0.6, 30, 17}, {0.9, 8, 7}};
  const FragilityFit fit2 = fit_fragility_mle(uneven);
  REQUIRE(fit2.fitted);
  const auto [theta2, beta2] = grid_maximum(uneven);
  CHECK(fit2.theta == Approx(theta2).epsilon(1e-4));
  CHECK(fit2.beta == Approx(beta2).epsilon(1e-4));
}

TEST_CASE("fragility: small random datasets, fitted or reported, agree with the grid", "[fragility]") {
  // Few runs per level (as in IDA traces and in bootstrap resamples), where the likelihood is
  // flat and a poor start would send the optimiser off to beta -> infinity.
  gsl_rng* rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 2024);
  std::size_t fitted = 0, compared = 0;
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<FragilityLevel> levels;
    const std::size_t count = 3 + gsl_rng_uniform_int(rng, 6);
    double im = 0.05 + 0.1 * gsl_rng_uniform(rng);
    for (std::size_t j = 0; j < count; ++j) {
      const std::size_t n = 1 + gsl_rng_uniform_int(rng, 5);
      levels.push_back({im, n, gsl_ran_binomial(rng, fragility_probability(0.4, 0.2 + gsl_rng_uniform(rng), im), n)});
      im *= 1.1 + gsl_rng_uniform(rng);
    }
    INFO("trial " << trial);
    const FragilityFit fit = fit_fragility_mle(levels);
    if (!fit.fitted) {
      CHECK_FALSE(fit.problem.empty());
      continue;
    }
    ++fitted;
    const auto [theta, beta] = grid_maximum(levels);
    // Where the grid's answer is on the edge of its first box, the maximum is outside it: then
    // the fit is compared by ln L only.
    const bool inside = std::abs(std::log(theta) - std::log(levels[levels.size() / 2].im)) < kGridHalfU - 0.2 &&
                        std::abs(std::log(beta) - std::log(0.5)) < kGridHalfV - 0.2;
    if (inside) {
      ++compared;
      CHECK(fit.theta == Approx(theta).epsilon(1e-4));
      CHECK(fit.beta == Approx(beta).epsilon(1e-4));
    }
    CHECK(fit.log_likelihood >= grid_log_likelihood(levels, std::log(theta), std::log(beta)) - 1e-9);
  }
  gsl_rng_free(rng);
  CHECK(fitted > 50);
  CHECK(compared > 40);
}

TEST_CASE("fragility: a nearly flat maximum is found through the probit coordinates", "[fragility]") {
  // The fraction hardly grows with IM (positively correlated, so a maximum exists), at a beta
  // so large that BFGS in (ln theta, ln beta) cannot converge: Newton in (a, b) =
  // (-ln theta / beta, 1 / beta), where ln L is concave, finds it.
  const std::vector<FragilityLevel> levels{{0.668516, 1, 1}, {1.25817, 3, 1}, {1.61069, 3, 3},
                                           {2.11135, 3, 1},  {2.27375, 4, 4}, {4.20359, 3, 2}};
  const FragilityFit fit = fit_fragility_mle(levels);
  REQUIRE(fit.fitted);
  CHECK(fit.beta > 50.0);
  // A maximum in (a, b): no neighbour is higher.
  const double b = 1.0 / fit.beta, a = -std::log(fit.theta) * b;
  const double at = grid_log_likelihood(levels, -a / b, -std::log(b));
  for (double da : {-1e-4, 0.0, 1e-4})
    for (double db : {-1e-5, 0.0, 1e-5}) {
      if (da == 0.0 && db == 0.0) continue;
      CHECK(grid_log_likelihood(levels, -(a + da) / (b + db), -std::log(b + db)) <= at + 1e-12);
    }
}

TEST_CASE("fragility: counts from a known lognormal give back its theta and beta", "[fragility]") {
  // The expected counts of a million runs per level of theta = 0.45 g, beta = 0.35, rounded:
  // the fractions are the curve's to 5e-7, so the fit is the curve to about 1e-5.
  const double theta = 0.45, beta = 0.35;
  const std::size_t n = 1000000;
  std::vector<std::size_t> k;
  for (double x : kLevels) k.push_back(static_cast<std::size_t>(std::lround(n * fragility_probability(theta, beta, x))));
  const FragilityFit fit = fit_fragility_mle(counts(kLevels, n, k));
  REQUIRE(fit.fitted);
  CHECK(fit.theta == Approx(theta).epsilon(1e-5));
  CHECK(fit.beta == Approx(beta).epsilon(1e-5));

  // Binomial draws (GSL's mt19937, seed 7) of 400 runs per level: within sampling error
  // (standard errors about 1 % of theta and 5 % of beta here).
  gsl_rng* rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 7);
  std::vector<std::size_t> drawn;
  for (double x : kLevels) drawn.push_back(gsl_ran_binomial(rng, fragility_probability(theta, beta, x), 400));
  gsl_rng_free(rng);
  const FragilityFit sampled = fit_fragility_mle(counts(kLevels, 400, drawn));
  REQUIRE(sampled.fitted);
  CHECK(sampled.theta == Approx(theta).epsilon(0.03));
  CHECK(sampled.beta == Approx(beta).epsilon(0.15));
}

TEST_CASE("fragility: the bootstrap bounds contain the estimate and repeat with the seed", "[fragility]") {
  const auto runs = stripes(20, kLevels, 0.5, 0.4);
  const FragilityFit fit = fit_fragility_mle(fragility_levels(runs));
  REQUIRE(fit.fitted);
  const FragilityBounds a = bootstrap_fragility(runs, 300, 11), b = bootstrap_fragility(runs, 300, 11),
                        c = bootstrap_fragility(runs, 300, 12);
  CHECK(a.samples == 300);
  CHECK(a.theta_low < fit.theta);
  CHECK(fit.theta < a.theta_high);
  CHECK(a.beta_low < fit.beta);
  CHECK(fit.beta < a.beta_high);
  // Bit for bit with the same seed; another seed draws other resamples.
  CHECK(a.theta_low == b.theta_low);
  CHECK(a.theta_high == b.theta_high);
  CHECK(a.beta_low == b.beta_low);
  CHECK(a.beta_high == b.beta_high);
  CHECK(a.degenerate == b.degenerate);
  CHECK(a.theta_low != c.theta_low);
  // Resampling records, not runs: a resample of one record repeated has its counts in steps
  // of the record count, so with every record identical the bounds collapse on the estimate's
  // level pattern and the resamples are all degenerate (a perfect step).
  const auto same = stripes(1, kLevels, 0.5, 0.4);
  const FragilityBounds none = bootstrap_fragility(same, 50, 1);
  CHECK(none.degenerate == 50);
  CHECK(std::isnan(none.theta_low));
}

TEST_CASE("fragility: degenerate data is reported, never given a theta", "[fragility]") {
  struct Case {
    const char* name;
    std::vector<std::size_t> events;
    const char* says;
  };
  const Case cases[] = {
      {"no events", {0, 0, 0, 0, 0, 0, 0, 0}, "no run had the event"},
      {"events everywhere", {10, 10, 10, 10, 10, 10, 10, 10}, "every run had the event"},
      {"a perfect step", {0, 0, 0, 10, 10, 10, 10, 10}, "separate the runs perfectly"},
      {"one mixed level at the step", {0, 0, 0, 4, 10, 10, 10, 10}, "separate the runs perfectly"},
      {"fractions falling with IM", {9, 8, 6, 5, 5, 3, 2, 1}, "does not grow with IM"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const FragilityFit fit = fit_fragility_mle(counts(kLevels, 10, c.events));
    CHECK_FALSE(fit.fitted);
    CHECK(fit.problem.find(c.says) != std::string::npos);
    CHECK(std::isnan(fit.theta));
    CHECK(std::isnan(fit.beta));
  }
  // Two mixed levels, or a non-monotone 0/1 pattern, have a maximum.
  CHECK(fit_fragility_mle(counts(kLevels, 10, {0, 0, 0, 3, 8, 10, 10, 10})).fitted);
  CHECK(fit_fragility_mle(counts(kLevels, 10, {0, 0, 10, 0, 10, 10, 10, 10})).fitted);
}

TEST_CASE("fragility: levels group runs, and traces are told from stripes", "[fragility]") {
  const std::vector<FragilityRun> runs{{"a", 0.2, false}, {"b", 0.2, true}, {"a", 0.4, true}, {"b", 0.4 * (1 + 1e-12), true}};
  const auto levels = fragility_levels(runs);
  REQUIRE(levels.size() == 2);
  CHECK(levels[0].im == 0.2);
  CHECK(levels[0].n == 2);
  CHECK(levels[0].events == 1);
  CHECK(levels[1].n == 2);
  CHECK(levels[1].events == 2);
  CHECK_FALSE(fragility_is_trace(runs));
  CHECK(fragility_is_trace({{"a", 0.2, false}, {"a", 0.4, true}, {"b", 0.3, true}}));
}

TEST_CASE("fragility: IM at first event, with censored records", "[fragility]") {
  // Traces: each record its own levels; c never has the event (censored); a's event at 0.9
  // after 0.6 does not count, its first is 0.6; b's first event is at 0.3 (the lowest, not
  // the first row read).
  const std::vector<FragilityRun> runs{{"a", 0.2, false}, {"a", 0.6, true},  {"a", 0.9, true},  {"b", 0.5, true},
                                       {"b", 0.3, true},  {"b", 0.1, false}, {"c", 0.2, false}, {"c", 1.0, false},
                                       {"d", 0.45, true}};
  REQUIRE(fragility_is_trace(runs));
  const FirstEventFit fit = fit_first_event(runs);
  REQUIRE(fit.fitted);
  CHECK(fit.records == 3);
  CHECK(fit.censored == 1);
  REQUIRE(fit.censored_records == std::vector<std::string>{"c"});
  const double l[3] = {std::log(0.6), std::log(0.3), std::log(0.45)};
  const double mean = (l[0] + l[1] + l[2]) / 3.0;
  const double sd = std::sqrt(((l[0] - mean) * (l[0] - mean) + (l[1] - mean) * (l[1] - mean) + (l[2] - mean) * (l[2] - mean)) / 2.0);
  CHECK(fit.theta == Approx(std::exp(mean)).epsilon(1e-14));
  CHECK(fit.beta == Approx(sd).epsilon(1e-14));

  const FirstEventFit one = fit_first_event({{"a", 0.2, true}, {"b", 0.3, false}});
  CHECK_FALSE(one.fitted);
  CHECK(one.problem.find("at least two") != std::string::npos);
}

TEST_CASE("fragility: event expressions", "[fragility]") {
  const std::vector<std::string> columns{"record", "im", "scale", "contact1.impacts", "A.drift_ratio1", "link1.stroke_max"};
  const auto row = [](double impacts, double drift, double stroke) {
    return std::vector<double>{NAN, 0.3, 1.0, impacts, drift, stroke};
  };
  SECTION("comparisons") {
    const auto e = FragilityEvent::parse("contact1.impacts > 0", columns);
    CHECK(e.evaluate(row(1, 0, 0)) == true);
    CHECK(e.evaluate(row(0, 0, 0)) == false);
    CHECK(FragilityEvent::parse("A.drift_ratio1>=0.02", columns).evaluate(row(0, 0.02, 0)) == true);
    CHECK(FragilityEvent::parse("A.drift_ratio1 < 2e-2", columns).evaluate(row(0, 0.02, 0)) == false);
    CHECK(FragilityEvent::parse("A.drift_ratio1 <= 2e-2", columns).evaluate(row(0, 0.02, 0)) == true);
    CHECK(e.columns_used() == std::vector<std::size_t>{3});
  }
  SECTION("and binds tighter than or; parentheses group") {
    // a or b and c: true when a alone holds; (a or b) and c: false then.
    const std::string a = "contact1.impacts > 0", b = "A.drift_ratio1 > 0.02", c = "link1.stroke_max > 0.1";
    const auto only_a = row(1, 0, 0);
    CHECK(FragilityEvent::parse(a + " or " + b + " and " + c, columns).evaluate(only_a) == true);
    CHECK(FragilityEvent::parse("(" + a + " or " + b + ") and " + c, columns).evaluate(only_a) == false);
    CHECK(FragilityEvent::parse(b + " and " + c + " or " + a, columns).evaluate(only_a) == true);
    CHECK(FragilityEvent::parse(a + " and " + b, columns).columns_used() == std::vector<std::size_t>{3, 4});
  }
  SECTION("a missing value: Kleene's logic") {
    const auto missing_drift = row(1, NAN, 0);
    CHECK_FALSE(FragilityEvent::parse("A.drift_ratio1 > 0.02", columns).evaluate(missing_drift).has_value());
    CHECK(FragilityEvent::parse("contact1.impacts > 0 or A.drift_ratio1 > 0.02", columns).evaluate(missing_drift) == true);
    CHECK(FragilityEvent::parse("contact1.impacts > 5 and A.drift_ratio1 > 0.02", columns).evaluate(missing_drift) == false);
    CHECK_FALSE(FragilityEvent::parse("contact1.impacts > 0 and A.drift_ratio1 > 0.02", columns).evaluate(missing_drift).has_value());
  }
  SECTION("errors name the column or the token") {
    const auto message = [&](const std::string& text) {
      try {
        FragilityEvent::parse(text, columns);
      } catch (const InputError& e) {
        return std::string(e.what());
      }
      return std::string("(no error)");
    };
    const std::string unknown = message("contact2.impacts > 0");
    CHECK(unknown.find("no column \"contact2.impacts\"") != std::string::npos);
    CHECK(unknown.find("the table has: record, im, scale, contact1.impacts, A.drift_ratio1, link1.stroke_max") != std::string::npos);
    CHECK(message("contact1.impacts == 0").find("expected one of > >= < <= after contact1.impacts") != std::string::npos);
    CHECK(message("contact1.impacts == 0").find("found \"==\" at character 18") != std::string::npos);
    CHECK(message("contact1.impacts").find("(a true/false column reads as 1/0: contact1.impacts > 0), found the end") !=
          std::string::npos);
    CHECK(message("contact1.impacts >").find("expected a finite number after contact1.impacts >, found the end") != std::string::npos);
    CHECK(message("contact1.impacts > 0 and").find("expected a column name") != std::string::npos);
    CHECK(message("contact1.impacts > 0 link1.stroke_max > 1").find("expected `and`, `or` or the end, found \"link1.stroke_max\"") !=
          std::string::npos);
    CHECK(message("(contact1.impacts > 0").find("expected `)`") != std::string::npos);
    CHECK(message("contact1.impacts > 1e999").find("expected a finite number") != std::string::npos);
    CHECK(message("").find("expected a column name") != std::string::npos);
    CHECK(message("contact1.impacts > 0 & A.drift_ratio1 > 0").find("\"&\" at character 22") != std::string::npos);
    CHECK(message("contact1.impacts > 0").rfind("(no error)", 0) == 0);
  }
}

namespace {

// An ida.csv of `records` records at kLevels: the event (pounding) at and above each record's
// capacity, theta exp(beta z_r); the drift grows with IM. The run `failed` (record, IM) is
// written as a failed run: empty values and an error.
fs::path ida_table(const std::string& name, std::size_t records, double theta, double beta,
                   const std::pair<std::string, double>& failed = {}) {
  std::string text = "record,im,scale,contact1.impacts,A.drift_ratio_max,error\n";
  for (const FragilityRun& r : stripes(records, kLevels, theta, beta)) {
    char line[160];
    if (r.record == failed.first && r.im == failed.second)
      std::snprintf(line, sizeof line, "%s.AT2,%g,%g,,,diverged\n", r.record.c_str(), r.im, 3.0 * r.im);
    else
      std::snprintf(line, sizeof line, "%s.AT2,%g,%g,%d,%g,\n", r.record.c_str(), r.im, 3.0 * r.im, r.event ? 2 : 0, 0.05 * r.im);
    text += line;
  }
  return write_temp(name, text);
}

}  // namespace

TEST_CASE("fragility: the command end to end", "[fragility][cli]") {
  const fs::path table = ida_table("none.csv", 15, 0.45, 0.4);
  // --out in a folder that is not there yet: made for the file.
  const fs::path out = fs::path(ADJOIN_TEST_TMP) / "made" / "fragility.json";
  fs::remove_all(out.parent_path());
  const auto r = run_cli("fragility " + shell_word(table) + " --event 'contact1.impacts > 0' --bootstrap 200 --seed 3 --at 0.5 --out " +
                         shell_word(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto json = nlohmann::json::parse(slurp(out));
  // The counts and the fit are the library's on the same runs.
  const auto runs = stripes(15, kLevels, 0.45, 0.4);
  const auto levels = fragility_levels(runs);
  const FragilityFit fit = fit_fragility_mle(levels);
  REQUIRE(fit.fitted);
  CHECK(json["theta"].get<double>() == fit.theta);
  CHECK(json["beta"].get<double>() == fit.beta);
  CHECK(json["log_likelihood"].get<double>() == fit.log_likelihood);
  REQUIRE(json["levels"].size() == kLevels.size());
  for (std::size_t j = 0; j < kLevels.size(); ++j) {
    CHECK(json["levels"][j].get<double>() == kLevels[j]);
    CHECK(json["n"][j].get<std::size_t>() == 15);
    CHECK(json["events"][j].get<std::size_t>() == levels[j].events);
  }
  CHECK(json["fitted"] == true);
  CHECK(json["event"] == "contact1.impacts > 0");
  CHECK(json["records"] == 15);
  CHECK(json["bootstrap"]["samples"] == 200);
  CHECK(json["bootstrap"]["theta"][0].get<double>() < fit.theta);
  CHECK(json["bootstrap"]["theta"][1].get<double>() > fit.theta);
  CHECK(json["at"]["probability"].get<double>() == Approx(fragility_probability(fit.theta, fit.beta, 0.5)).epsilon(1e-15));
  CHECK_FALSE(json.contains("first_event"));  // stripes, not traces
  CHECK(r.out.find("maximum likelihood: theta =") != std::string::npos);

  SECTION("several designs, labelled, with a figure") {
    needs_program("gnuplot");
    const fs::path damped = ida_table("damped.csv", 15, 0.7, 0.3);
    const fs::path image = fs::path(ADJOIN_TEST_TMP) / "fragility.png";
    const auto both = run_cli("fragility " + shell_word(table) + " " + shell_word(damped) +
                              " --label none,friction --event 'contact1.impacts > 0' --bootstrap 0 --at 0.5 --out " +
                              shell_word(out) + " --plot " + shell_word(image));
    INFO(both.err);
    REQUIRE(both.status == 0);
    const auto j = nlohmann::json::parse(slurp(out));
    REQUIRE(j["designs"].size() == 2);
    CHECK(j["designs"][0]["label"] == "none");
    CHECK(j["designs"][1]["label"] == "friction");
    CHECK(j["designs"][0]["bootstrap"].is_null());
    // The damped design is less fragile: a larger theta, a smaller probability at 0.5 g.
    CHECK(j["designs"][1]["theta"].get<double>() > j["designs"][0]["theta"].get<double>());
    CHECK(j["designs"][1]["at"]["probability"].get<double>() < j["designs"][0]["at"]["probability"].get<double>());
    adjoin::test::require_png(image, 900, 600);
  }
  SECTION("stripes with a failed run are still stripes") {
    const fs::path failed = ida_table("failed.csv", 15, 0.45, 0.4, {"rec3", 0.5});
    const auto f = run_cli("fragility " + shell_word(failed) + " --event 'contact1.impacts > 0' --bootstrap 0 --out " + shell_word(out));
    INFO(f.err);
    REQUIRE(f.status == 0);
    const auto j = nlohmann::json::parse(slurp(out));
    CHECK(j["skipped"]["failed"] == 1);
    CHECK(j["runs"] == 119);
    CHECK_FALSE(j.contains("first_event"));
  }
  SECTION("an unknown column: exit 2 naming it and listing the table's") {
    const auto bad = run_cli("fragility " + shell_word(table) + " --event 'contact2.impacts > 0' --out " + shell_word(out));
    CHECK(bad.status == 2);
    CHECK(bad.err.rfind("error: ", 0) == 0);
    CHECK(bad.err.find("no column \"contact2.impacts\"") != std::string::npos);
    CHECK(bad.err.find("record, im, scale, contact1.impacts, A.drift_ratio_max") != std::string::npos);
  }
  SECTION("a wrong number of labels: exit 2") {
    const auto bad = run_cli("fragility " + shell_word(table) + " --label a,b --event 'contact1.impacts > 0' --out " + shell_word(out));
    CHECK(bad.status == 2);
    CHECK(bad.err.find("--label: 2 labels for 1 tables") != std::string::npos);
  }
  SECTION("no events: reported in the JSON and on stderr, not a theta") {
    const auto none = run_cli("fragility " + shell_word(table) + " --event 'A.drift_ratio_max > 1' --out " + shell_word(out));
    CHECK(none.status == 0);
    CHECK(none.err.find("warning:") != std::string::npos);
    CHECK(none.err.find("no run had the event") != std::string::npos);
    const auto j = nlohmann::json::parse(slurp(out));
    CHECK(j["fitted"] == false);
    CHECK(j["theta"].is_null());
    CHECK(j["beta"].is_null());
    CHECK(j["problem"].get<std::string>().find("no run had the event (0 of 120 runs at 8 IM levels)") != std::string::npos);
  }
}

TEST_CASE("fragility: the command on IDA traces, failed runs and empty cells", "[fragility][cli]") {
  // Traces: each record its own IMs. r3 fails at 0.7 (an error), r4's drift is empty at 0.5,
  // r5 never has the event.
  const fs::path table = write_temp("trace.csv",
                                    "record,im,scale,A.drift_ratio_max,error\n"
                                    "r1,0.2,1,0.005,\n r1,0.4,2,0.025,\n"
                                    "r2,0.3,1,0.01,\nr2,0.5,2,0.019,\nr2,0.6,2,0.03,\n"
                                    "r3,0.25,1,0.012,\nr3,0.35,1,0.021,\nr3,0.7,1,,diverged\n"
                                    "r4,0.3,1,0.01,\nr4,0.5,1,,\nr4,0.55,1,0.04,\n"
                                    "r5,0.2,1,0.001,\nr5,0.9,1,0.015,\n");
  const fs::path out = fs::path(ADJOIN_TEST_TMP) / "trace.json";
  const auto r = run_cli("fragility " + shell_word(table) + " --event 'A.drift_ratio_max > 0.02' --bootstrap 50 --out " +
                         shell_word(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(slurp(out));
  CHECK(j["skipped"]["failed"] == 1);
  CHECK(j["skipped"]["unknown"] == 1);
  CHECK(j["runs"] == 11);
  REQUIRE(j.contains("first_event"));
  CHECK(j["first_event"]["records"] == 4);
  CHECK(j["first_event"]["censored"] == 1);
  CHECK(j["first_event"]["censored_records"][0] == "r5");
  const double l[4] = {std::log(0.4), std::log(0.6), std::log(0.35), std::log(0.55)};
  const double mean = (l[0] + l[1] + l[2] + l[3]) / 4.0;
  CHECK(j["first_event"]["theta"].get<double>() == Approx(std::exp(mean)).epsilon(1e-12));
  CHECK(r.err.find("1 runs left out, their event reads an empty cell (the first at line 11)") != std::string::npos);
  CHECK(r.err.find("1 records never had the event") != std::string::npos);
}
