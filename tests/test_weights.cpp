// Grünwald–Letnikov weights against their closed form, and the GL derivative of t^p against
// the exact fractional derivative: error small and first order in h; the weights kept for the process
// (convolution_weights) equal the recurrences' bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <thread>
#include <vector>

#include "adjoin/fractional/weights.hpp"

using adjoin::grunwald_letnikov_weights;

namespace {

// ln Gamma(j - g) - ln Gamma(j + 1) for an integer j, accurate in the difference itself:
// lgamma of each would lose ~1e-10 relative at j = 1e5 because both values are ~1e6. Small j
// by tgamma directly; large j by Stirling's series with the logarithms combined so that
// nothing large cancels:
//   (z1 - 1/2) ln z1 - (z2 - 1/2) ln z2 - (z1 - z2) = (z1 - 1/2) log1p(d/z2) + d ln z2 - d
// with z1 = j - g, z2 = j + 1, d = z1 - z2 = -(1 + g).
long double log_gamma_ratio(std::size_t j, long double g) {
  const long double jj = static_cast<long double>(j);
  if (j < 30) return std::log(std::abs(std::tgamma(jj - g) / std::tgamma(jj + 1.0L)));
  const long double d = -(1.0L + g);
  const long double z1 = jj - g, z2 = jj + 1.0L;
  auto stirling_tail = [](long double z) {  // sum B_2k / (2k (2k-1) z^{2k-1}), k = 1..5
    const long double r = 1.0L / (z * z);
    return (1.0L / 12 - r * (1.0L / 360 - r * (1.0L / 1260 - r * (1.0L / 1680 - r / 1188)))) / z;
  };
  return (z1 - 0.5L) * std::log1p(d / z2) + d * std::log(z2) - d + stirling_tail(z1) -
         stirling_tail(z2);
}

// w_j = Gamma(j - g) / (Gamma(-g) Gamma(j + 1)), in long double; 0 < g < 1, so only
// Gamma(-g) < 0 carries a sign.
double closed_form_weight(std::size_t j, double g) {
  if (j == 0) return 1.0;
  const long double lg = g;
  return static_cast<double>(std::exp(log_gamma_ratio(j, lg)) / std::tgamma(-lg));
}

}  // namespace

TEST_CASE("GL weights match Gamma(j-g)/(Gamma(-g) Gamma(j+1)) up to j = 1e5", "[weights]") {
  constexpr std::size_t count = 100001;
  for (double g : {0.01, 0.23, 0.5, 0.53, 0.99}) {
    const std::vector<double> w = grunwald_letnikov_weights(g, count);
    REQUIRE(w.size() == count);
    CHECK(w[0] == 1.0);
    CHECK(w[1] == Approx(-g).epsilon(1e-15));
    double worst = 0.0;
    for (std::size_t j = 1; j < count; ++j)
      worst = std::max(worst, std::abs(w[j] / closed_form_weight(j, g) - 1.0));
    INFO("order " << g << ": max relative error " << worst);
    CHECK(worst < 1e-13);
    // Every weight past w_0 has the sign of -g (the recurrence never crosses zero).
    CHECK(*std::max_element(w.begin() + 1, w.end()) < 0.0);
  }
}

TEST_CASE("GL weights: degenerate counts and integer order", "[weights]") {
  CHECK(grunwald_letnikov_weights(0.5, 0).empty());
  CHECK(grunwald_letnikov_weights(0.5, 1) == std::vector<double>{1.0});
  // Order 1: (1 - zeta)^1 = 1 - zeta, the backward difference.
  const auto w = grunwald_letnikov_weights(1.0, 5);
  CHECK(w == std::vector<double>{1.0, -1.0, 0.0, 0.0, 0.0});
}

TEST_CASE("GL derivative of t^p converges at first order", "[weights]") {
  struct Case { double g, p; };
  for (const Case c : {Case{0.5, 1.0}, Case{0.23, 2.0}, Case{0.53, 1.5}, Case{0.9, 3.0}}) {
    // D^g t^p = Gamma(p + 1) / Gamma(p + 1 - g) t^{p - g}; evaluated at t = 1.
    const double exact = std::tgamma(c.p + 1.0) / std::tgamma(c.p + 1.0 - c.g);
    std::vector<double> errors;
    for (std::size_t m : {100u, 200u, 400u, 800u, 1600u, 3200u, 6400u}) {
      const double h = 1.0 / static_cast<double>(m);
      const std::vector<double> w = grunwald_letnikov_weights(c.g, m + 1);
      double sum = 0.0;
      for (std::size_t j = 0; j <= m; ++j)
        sum += w[j] * std::pow(static_cast<double>(m - j) * h, c.p);
      errors.push_back(std::abs(std::pow(h, -c.g) * sum - exact));
    }
    for (std::size_t i = 1; i < errors.size(); ++i) {
      const double order = std::log2(errors[i - 1] / errors[i]);
      INFO("g = " << c.g << ", p = " << c.p << ", h = 1/" << (100u << i) << ": error "
                  << errors[i] << ", observed order " << order);
      CHECK(order > 0.9);
      CHECK(order < 1.1);
    }
    // The leading error term is (g/2) h D^{1+g} z(t) (expand (1 - e^{-h s})^g / h^g in h),
    // with D^{1+g} t^p = Gamma(p + 1) / Gamma(p - g) t^{p-g-1}: the error constant itself.
    const double constant = 0.5 * c.g * std::tgamma(c.p + 1.0) / std::tgamma(c.p - c.g);
    INFO("error / h at h = 1/6400: " << errors.back() * 6400.0 << ", predicted " << constant);
    CHECK(errors.back() * 6400.0 == Approx(constant).epsilon(0.01));
  }
}

// convolution_weights keeps long sequences for the process and copies their prefixes: whatever
// the order of the calls, each answer must equal the recurrence's own, bit for bit (a wrong
// prefix, a stale entry of another order or rule, or an entry cut short would not).
TEST_CASE("convolution_weights: kept sequences equal the recurrences' bit for bit", "[weights]") {
  using adjoin::WeightRule;
  const double orders[] = {0.31, 0.62};
  for (const WeightRule rule : {WeightRule::bdf2, WeightRule::grunwald_letnikov}) {
    auto direct = [&](double g, std::size_t n) {
      return rule == WeightRule::bdf2 ? adjoin::bdf2_weights(g, n) : adjoin::grunwald_letnikov_weights(g, n);
    };
    for (const double g : orders) {
      // Short (computed directly), long (kept), shorter than kept (a prefix), longer (replaces it).
      for (const std::size_t n : {std::size_t{100}, std::size_t{5000}, std::size_t{3000}, std::size_t{20000}, std::size_t{257}}) {
        const std::vector<double> w = adjoin::convolution_weights(rule, g, n);
        const std::vector<double> exact = direct(g, n);
        REQUIRE(w.size() == n);
        CHECK(w == exact);  // (operator==: exact equality of every element)
      }
    }
  }
  // The rules are kept apart: the same order under the other rule differs from the first weight.
  CHECK(adjoin::convolution_weights(WeightRule::bdf2, 0.31, 1000)[0] != adjoin::convolution_weights(WeightRule::grunwald_letnikov, 0.31, 1000)[0]);
}

// The kept sequences are shared by threads (a sweep's runs): threads asking for the same and for
// different (rule, order, length) at once each get the recurrence's own weights (CI runs this
// under ThreadSanitizer, which reports any unguarded access to the kept sequences).
TEST_CASE("convolution_weights: threads asking at once get the recurrences' weights", "[weights][threads]") {
  using adjoin::WeightRule;
  constexpr int kThreads = 4;
  std::vector<int> wrong(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([t, &wrong] {
      for (int round = 0; round < 20; ++round) {
        const WeightRule rule = (t + round) % 2 == 0 ? WeightRule::bdf2 : WeightRule::grunwald_letnikov;
        const double order = round % 3 == 0 ? 0.47 : 0.73;
        const std::size_t n = 300 + static_cast<std::size_t>((t * 7 + round * 13) % 11) * 700;
        const std::vector<double> exact =
            rule == WeightRule::bdf2 ? adjoin::bdf2_weights(order, n) : adjoin::grunwald_letnikov_weights(order, n);
        if (adjoin::convolution_weights(rule, order, n) != exact) ++wrong[static_cast<std::size_t>(t)];
      }
    });
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) CHECK(wrong[static_cast<std::size_t>(t)] == 0);
}
