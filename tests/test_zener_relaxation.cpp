// The discrete fractional Zener rod (detail::RodLaw with Grünwald–Letnikov weights) under a
// unit step strain against the exact relaxation
//
//     f(t) = k [1 + (tau_x / tau_f - 1) E_g(-t^g / tau_f)]
//
// (Laplace: F(s) = (k / s) (1 + tau_x s^g) / (1 + tau_f s^g)). At fixed t > 0 the GL scheme is
// first order, so halving h must halve the error.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <vector>

#include "../src/solver/rod_law.hpp"
#include "adjoin/fractional/mittag_leffler.hpp"
#include "adjoin/fractional/weights.hpp"

namespace {

struct Relaxation {
  double order, tau_x, tau_f;
  double exact(double t) const {
    return 1.0 + (tau_x / tau_f - 1.0) * adjoin::mittag_leffler(order, -std::pow(t, order) / tau_f);
  }
};

// f_m for m = 0..steps under x_m = 1, with unit stiffness.
std::vector<double> discrete_relaxation(const Relaxation& r, double h, std::size_t steps,
                                        adjoin::HistoryEngine engine) {
  adjoin::Rod rod{r.order, r.tau_x, r.tau_f, false};
  adjoin::detail::RodLaw law(rod, 1.0, h, engine,
                             adjoin::grunwald_letnikov_weights(r.order, steps + 1));
  std::vector<double> f(steps + 1);
  for (std::size_t m = 0; m <= steps; ++m) {
    f[m] = law.force(1.0);
    law.commit(1.0, f[m]);
  }
  return f;
}

// |f_m - f(t_m)| at each sample time, for h = 1 / per_unit.
std::vector<double> errors_at(const Relaxation& r, const std::vector<double>& times,
                              std::size_t per_unit, adjoin::HistoryEngine engine) {
  const double h = 1.0 / static_cast<double>(per_unit);
  const auto f = discrete_relaxation(r, h, 2 * per_unit, engine);
  std::vector<double> errors;
  for (double t : times) {
    const auto m = static_cast<std::size_t>(std::lround(t * static_cast<double>(per_unit)));
    errors.push_back(std::abs(f[m] - r.exact(t)));
  }
  return errors;
}

// Observed order at each sample time between successive halvings of h, and the largest error
// at the finest h against `bound`.
void check_first_order(const Relaxation& r, double bound) {
  const std::vector<double> times{0.25, 0.5, 1.0, 2.0};
  const std::vector<std::size_t> ladder{100, 200, 400, 800, 1600, 3200};
  std::vector<std::vector<double>> errors;
  for (std::size_t per_unit : ladder)
    errors.push_back(errors_at(r, times, per_unit, adjoin::HistoryEngine::direct));
  for (std::size_t i = 1; i < ladder.size(); ++i)
    for (std::size_t k = 0; k < times.size(); ++k) {
      const double order = std::log2(errors[i - 1][k] / errors[i][k]);
      INFO("g = " << r.order << ", t = " << times[k] << ", h = 1/" << ladder[i] << ": error "
                  << errors[i][k] << ", observed order " << order);
      CHECK(order > 0.9);
      CHECK(order < 1.1);
    }
  const double finest = *std::max_element(errors.back().begin(), errors.back().end());
  INFO("g = " << r.order << ": largest error at h = 1/" << ladder.back() << ": " << finest);
  CHECK(finest < bound);
}

}  // namespace

TEST_CASE("Zener rod relaxation, rod 2 of the paper (g = 0.53)", "[zener]") {
  // Relaxes from tau_x / tau_f = 20 at t = 0+ towards 1.
  check_first_order({0.53, 4.0, 0.2}, 1e-3);
}

TEST_CASE("Zener rod relaxation, rod 1 of the paper (g = 0.23)", "[zener]") {
  // tau_f^{1/g} ~ 4e-11: the rod is deep in its slow power-law tail for every h used.
  check_first_order({0.23, 1.183, 0.004}, 2e-4);
}

TEST_CASE("Zener rod: the instantaneous stiffness tends to tau_x / tau_f", "[zener]") {
  // f_0 = k (1 + tau_x h^{-g}) / (1 + tau_f h^{-g}) -> k tau_x / tau_f as h -> 0, the glassy
  // modulus f(0+) of the exact solution.
  const Relaxation r{0.53, 4.0, 0.2};
  const auto f = discrete_relaxation(r, 1e-12, 0, adjoin::HistoryEngine::direct);
  CHECK(f[0] == Approx(r.tau_x / r.tau_f).epsilon(1e-5));
  CHECK(r.exact(1e-30) == Approx(r.tau_x / r.tau_f).epsilon(1e-12));
}

TEST_CASE("Zener rod: the fft history engine gives the direct engine's forces", "[zener]") {
  for (const Relaxation r : {Relaxation{0.53, 4.0, 0.2}, Relaxation{0.23, 1.183, 0.004}}) {
    const auto direct = discrete_relaxation(r, 1.0 / 3200, 6400, adjoin::HistoryEngine::direct);
    const auto fft = discrete_relaxation(r, 1.0 / 3200, 6400, adjoin::HistoryEngine::fft);
    double worst = 0.0;
    for (std::size_t m = 0; m < direct.size(); ++m)
      worst = std::max(worst, std::abs(fft[m] - direct[m]) / std::abs(direct[m]));
    INFO("g = " << r.order << ": max relative difference " << worst);
    CHECK(worst < 1e-12);
  }
}
