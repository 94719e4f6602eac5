// The Mittag-Leffler evaluator against closed forms, its power series, its integral
// representation and its asymptotic expansion. Tolerance: 1e-10 relative to max(1, |E|),
// i.e. relative for large values and absolute for small ones (the contract promises ~1e-13).
#include <catch2/catch.hpp>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "adjoin/fractional/mittag_leffler.hpp"

using adjoin::mittag_leffler;

namespace {

constexpr double kTol = 1e-10;

double scaled_error(double value, double reference) {
  return std::abs(value - reference) / std::max(1.0, std::abs(reference));
}

// sum_k z^k / Gamma(alpha k + beta) in long double; |z| <= 1.5 keeps cancellation harmless.
double series(double alpha, double beta, double z) {
  long double sum = 0.0L;
  for (int k = 0; k < 400; ++k) {
    const long double term =
        std::pow(static_cast<long double>(std::abs(z)), k) /
        std::exp(std::lgamma(static_cast<long double>(alpha) * k + beta));
    sum += (z < 0 && k % 2 == 1) ? -term : term;
    if (k > 20 && term < 1e-25L) break;
  }
  return static_cast<double>(sum);
}

// E_a(-x) = sin(a pi)/(a pi) ∫_0^∞ exp(-(x u)^{1/a}) / (u^2 + 2 u cos(a pi) + 1) du for
// 0 < a < 1, x > 0: the completely monotone representation with r = u^{1/a}, which removes
// the r^{a-1} singularity. With v = x u the exponential has unit width whatever x is:
// E_a(-x) = sin(a pi)/(a pi x) ∫_0^∞ exp(-v^{1/a}) / ((v/x)^2 + 2 (v/x) cos(a pi) + 1) dv,
// integrated with breakpoints where the two factors change scale (v = x and v = 1) up to
// v = 750^a, beyond which exp(-v^{1/a}) underflows.
struct IntegralParams { double a, x; };
double integrand(double v, void* raw) {
  const auto* prm = static_cast<const IntegralParams*>(raw);
  const double c = std::cos(prm->a * std::numbers::pi);
  const double u = v / prm->x;
  return std::exp(-std::pow(v, 1.0 / prm->a)) / (u * u + 2.0 * u * c + 1.0);
}
double integral_representation(double a, double x) {
  IntegralParams prm{a, x};
  gsl_function f{&integrand, &prm};
  const double end = std::pow(750.0, a);
  std::vector<double> points{0.0};
  for (double p : {std::min(x, 1.0), std::max(x, 1.0)})
    if (p < end && p > points.back()) points.push_back(p);
  points.push_back(end);
  gsl_integration_workspace* ws = gsl_integration_workspace_alloc(2000);
  double sum = 0.0, err = 0.0;
  gsl_integration_qagp(&f, points.data(), points.size(), 1e-17, 1e-14, 2000, ws, &sum, &err);
  gsl_integration_workspace_free(ws);
  return std::sin(a * std::numbers::pi) / (a * std::numbers::pi * x) * sum;
}

}  // namespace

TEST_CASE("E_1(z) = exp(z)", "[mittag_leffler]") {
  double worst = 0.0;
  for (double t = 0.0; t <= 20.0; t += 0.125) {
    worst = std::max(worst, scaled_error(mittag_leffler(1.0, -t), std::exp(-t)));
    worst = std::max(worst, std::abs(mittag_leffler(1.0, t) / std::exp(t) - 1.0));
  }
  INFO("max error " << worst);
  CHECK(worst < kTol);
}

TEST_CASE("E_{1/2}(-t) = exp(t^2) erfc(t), E_{1/2}(t) = exp(t^2) erfc(-t)", "[mittag_leffler]") {
  double worst = 0.0;
  for (double t = 0.0; t <= 20.0; t += 0.125) {  // t multiple of 1/8: t*t is exact
    const long double lt = t;
    const double minus = static_cast<double>(std::exp(lt * lt) * std::erfc(lt));
    worst = std::max(worst, scaled_error(mittag_leffler(0.5, -t), minus));
    if (t <= 10.0) {  // exp(t^2) stays a double
      const double plus = static_cast<double>(std::exp(lt * lt) * std::erfc(-lt));
      worst = std::max(worst, std::abs(mittag_leffler(0.5, t) / plus - 1.0));
    }
  }
  INFO("max error " << worst);
  CHECK(worst < kTol);
}

TEST_CASE("E_2(-t^2) = cos t and E_{2,2}(-t^2) = sin(t)/t", "[mittag_leffler]") {
  double worst = 0.0;
  for (double t = 0.125; t <= 20.0; t += 0.125) {
    worst = std::max(worst, scaled_error(mittag_leffler(2.0, -t * t), std::cos(t)));
    worst = std::max(worst, scaled_error(mittag_leffler(2.0, 2.0, -t * t), std::sin(t) / t));
    // E_2(t^2) = cosh t.
    worst = std::max(worst, std::abs(mittag_leffler(2.0, t * t) / std::cosh(t) - 1.0));
  }
  INFO("max error " << worst);
  CHECK(worst < kTol);
}

TEST_CASE("E_{1,2}(z) = (exp(z) - 1)/z and E_{a,b}(0) = 1/Gamma(b)", "[mittag_leffler]") {
  double worst = 0.0;
  for (double t = 0.125; t <= 20.0; t += 0.125)
    worst = std::max(worst, scaled_error(mittag_leffler(1.0, 2.0, -t), -std::expm1(-t) / t));
  for (double a : {0.1, 0.23, 0.5, 0.53, 0.99, 1.0, 1.5, 2.0})
    for (double b : {0.3, 1.0, 1.7, 2.0, 3.5})
      worst = std::max(worst, scaled_error(mittag_leffler(a, b, 0.0), 1.0 / std::tgamma(b)));
  INFO("max error " << worst);
  CHECK(worst < kTol);
}

TEST_CASE("Mittag-Leffler against its power series for |z| <= 1.5", "[mittag_leffler]") {
  double worst = 0.0;
  for (double a : {0.23, 0.53, 0.8, 1.3, 1.75, 2.0})
    for (double b : {1.0, 0.6, 1.4})
      for (double z = -1.5; z <= 1.5; z += 0.0625)
        worst = std::max(worst, scaled_error(mittag_leffler(a, b, z), series(a, b, z)));
  INFO("max error " << worst);
  CHECK(worst < kTol);
}

TEST_CASE("E_a(-x) for 0 < a < 1 against the integral representation", "[mittag_leffler]") {
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  double worst = 0.0;
  for (double a : {0.1, 0.23, 0.53, 0.75, 0.95})
    for (double x : {0.01, 0.3, 1.0, 2.5, 7.0, 30.0, 100.0, 300.0, 1000.0})
      worst = std::max(worst, scaled_error(mittag_leffler(a, -x), integral_representation(a, x)));
  gsl_set_error_handler(old);
  INFO("max error " << worst);
  CHECK(worst < kTol);
}

TEST_CASE("E_a(-x) for large x against the asymptotic expansion", "[mittag_leffler]") {
  // E_a(-x) ~ sum_{k=1}^{K} (-1)^{k+1} x^{-k} / Gamma(1 - a k) for 0 < a < 2; with x >= 1e3
  // the truncation error x^{-K-1} / Gamma(1 - a (K+1)) is far below the tolerance for K = 8, and for
  // a > 1 the oscillating pole terms are damped by exp(-x^{1/a} |cos(pi/a)|).
  double worst = 0.0;
  for (double a : {0.23, 0.53, 0.9, 1.2, 1.5})
    for (double x : {1e3, 1e4, 1e6}) {
      double ref = 0.0;
      for (int k = 1; k <= 8; ++k) {
        const double arg = 1.0 - a * k;
        // 1/Gamma vanishes at the poles 0, -1, -2, ...
        if (arg <= 0.0 && arg == std::floor(arg)) continue;
        ref += (k % 2 == 1 ? 1.0 : -1.0) * std::pow(x, -k) / std::tgamma(arg);
      }
      worst = std::max(worst, std::abs(mittag_leffler(a, -x) - ref) / std::abs(ref));
    }
  INFO("max relative error " << worst);
  CHECK(worst < kTol);
}

TEST_CASE("Mittag-Leffler rejects invalid parameters", "[mittag_leffler]") {
  CHECK_THROWS_AS(mittag_leffler(0.0, 1.0, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(mittag_leffler(-1.0, 1.0, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(mittag_leffler(0.5, 0.0, 0.5), std::invalid_argument);
  CHECK(std::isnan(mittag_leffler(0.5, 1.0, std::nan(""))));
}
