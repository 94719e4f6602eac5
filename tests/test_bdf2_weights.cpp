// BDF2 convolution-quadrature weights: the Miller recurrence against an independent product
// of two binomial series, and second-order accuracy of the fractional derivative they give.
#include <catch2/catch.hpp>
#include <cmath>

#include "adjoin/fractional/weights.hpp"

using namespace adjoin;

TEST_CASE("BDF2 weights equal the coefficients of (3/2)^g (1 - z)^g (1 - z/3)^g", "[weights][bdf2]") {
  for (double g : {0.01, 0.23, 0.53, 0.99}) {
    const std::size_t n = 3000;
    const auto w = bdf2_weights(g, n);
    // Independent: (1 - z)^g has the GL coefficients; (1 - z/3)^g the same scaled by 3^{-j}.
    const auto a = grunwald_letnikov_weights(g, n);
    std::vector<double> b(n);
    for (std::size_t j = 0; j < n; ++j) b[j] = a[j] * std::pow(3.0, -static_cast<double>(j));
    double worst = 0.0;
    for (std::size_t m = 0; m < n; ++m) {
      long double c = 0.0L;
      for (std::size_t j = 0; j <= m; ++j) c += static_cast<long double>(a[j]) * b[m - j];
      const double expected = std::pow(1.5, g) * static_cast<double>(c);
      worst = std::max(worst, std::abs(w[m] - expected) / std::max(std::abs(expected), 1e-300));
    }
    INFO("order " << g);
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("BDF2 convolution quadrature differentiates t^p at second order", "[weights][bdf2]") {
  for (double g : {0.23, 0.53, 0.9}) {
    for (double p : {2.0, 3.0}) {
      const double exact = std::tgamma(p + 1.0) / std::tgamma(p + 1.0 - g);  // at t = 1
      std::vector<double> errors;
      for (std::size_t m : {100, 200, 400, 800}) {
        const double h = 1.0 / static_cast<double>(m);
        const auto w = bdf2_weights(g, m + 1);
        double sum = 0.0;
        for (std::size_t j = 0; j <= m; ++j) sum += w[j] * std::pow(static_cast<double>(m - j) * h, p);
        errors.push_back(std::abs(std::pow(h, -g) * sum - exact));
      }
      for (std::size_t i = 1; i < errors.size(); ++i) {
        INFO("g = " << g << ", p = " << p << ", errors " << errors[i - 1] << " -> " << errors[i]);
        CHECK(std::log2(errors[i - 1] / errors[i]) == Approx(2.0).margin(0.1));
      }
    }
  }
}
