// The bilinear elements' passes over all elements (src/solver/bilinear_lanes.hpp) against the
// per-element formulas they replace (bilinear_step.hpp's test, Pair::add's scatter), bit for
// bit, on both processor paths, for chains (storey laws) and for any other layout.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "../src/solver/bilinear_lanes.hpp"

using namespace adjoin::detail;

namespace {

// Two buildings' storey laws (floors 0..na-1 and na..na+nb-1), as chains.
std::vector<BilinearElement> storey_laws(int na, int nb) {
  std::vector<BilinearElement> out;
  for (int e = 0; e < na + nb; ++e) {
    BilinearElement el;
    el.i = e;
    el.j = e == 0 || e == na ? -1 : e - 1;
    el.storey = e;
    el.storey_law = true;
    el.k = 1.0e6 * (1.0 + 0.1 * e);
    el.limit = 5.0e3 * (1.0 + 0.05 * e);
    out.push_back(el);
  }
  return out;
}

}  // namespace

TEST_CASE("the bilinear elements' layout is a chain for storey laws only", "[bilinear][kernels]") {
  const BilinearLayout chains(storey_laws(5, 3));
  CHECK(chains.chains);
  CHECK(chains.starts == std::vector<int>{5});
  std::vector<BilinearElement> with_device = storey_laws(5, 3);
  BilinearElement device = with_device[1];
  device.storey_law = false;
  with_device.push_back(device);  // (a device on storey 2: floors 1 and 0)
  CHECK_FALSE(BilinearLayout(with_device).chains);
  std::vector<BilinearElement> isolated = storey_laws(5, 3);
  isolated[5].j = 8;  // (B's storey 1 on a base floor)
  CHECK_FALSE(BilinearLayout(isolated).chains);
}

TEST_CASE("the bilinear elements' passes equal the per-element formulas bit for bit, on both processor paths", "[bilinear][kernels]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const BilinearKernels* kernels : {&baseline_bilinear_kernels(), &bilinear_kernels()}) {
    for (const auto& [na, nb] : {std::pair{5, 3}, std::pair{20, 20}, std::pair{7, 0}, std::pair{1, 2}}) {
      std::vector<BilinearElement> elements = storey_laws(na, nb);
      for (bool chain : {true, false}) {
        INFO("storeys " << na << " + " << nb << (chain ? ", chains" : ", gathered"));
        if (!chain) {  // the same elements with a device: the general passes
          BilinearElement device = elements[0];
          device.storey_law = false;
          device.storey = 0;
          elements.push_back(device);
        }
        const BilinearLayout layout(elements);
        REQUIRE(layout.chains == chain);
        const int n = layout.size(), floors = na + nb;
        BilinearStates b(layout);
        std::vector<double> x(static_cast<std::size_t>(floors));
        for (double& v : x) v = 0.01 * u(random);
        for (int e = 0; e < n; ++e) {
          b.up[e] = 0.002 * u(random);
          b.q[e] = 1.0 + e;  // (kept where the test fails)
          b.bound[e] = e % 5 == 3 ? -1.0 : layout.limit[e];
        }
        x[0] = -0.0;  // (a chain's start: d = x - 0.0 keeps the sign of a zero)
        if (na >= 2 && nb > 0) x[static_cast<std::size_t>(na)] = -0.0;
        x[1] = std::numeric_limits<double>::quiet_NaN();  // (a NaN fails the test, as |q| <= F_h does)
        b.up[0] = x[0];                                    // (and q = 0 passes it)
        // The test, without and with the forces kept; the drifts x_i - x_j, x_j = 0 at the ground.
        const std::vector<double> q_before = b.q;
        const int count = bilinear_test(*kernels, layout, x.data(), b, false);
        CHECK(b.q == q_before);
        for (int e = 0; e < n; ++e) {
          const BilinearElement& el = elements[static_cast<std::size_t>(e)];
          const double d = x[el.i] - (el.j >= 0 ? x[el.j] : 0.0);
          CHECK((b.d[e] == d || (std::isnan(b.d[e]) && std::isnan(d))));
          CHECK(std::signbit(b.d[e]) == std::signbit(d));
        }
        const std::vector<double> flags = b.flag;
        CHECK(bilinear_test(*kernels, layout, x.data(), b, true) == count);
        CHECK(b.flag == flags);
        int failed = 0, passed = 0;
        for (int e = 0; e < n; ++e) {
          const double q1 = layout.k[e] * (b.d[e] - b.up[e]);
          const bool stays = b.bound[e] >= 0.0 && std::abs(q1) <= layout.limit[e];
          CHECK(b.flag[e] == (stays ? 0.0 : 1.0));
          if (stays) CHECK(b.q[e] == q1);
          else CHECK(b.q[e] == q_before[static_cast<std::size_t>(e)]);
          (stays ? passed : failed) += 1;
        }
        CHECK(count == failed);
        CHECK(failed >= (n > 3 ? 2 : 1));  // (the NaN and the closed bound at least)
        CHECK(passed >= 1);
        // The offsets into the floors' forces: +f at i, -f at j, in the elements' order.
        std::vector<double> f(static_cast<std::size_t>(n)), p(static_cast<std::size_t>(floors)), expected;
        for (double& v : f) v = 1.0e4 * u(random);
        for (double& v : p) v = 1.0e5 * u(random);
        expected = p;
        for (int e = 0; e < n; ++e) {
          const BilinearElement& el = elements[static_cast<std::size_t>(e)];
          if (el.i >= 0) expected[static_cast<std::size_t>(el.i)] += f[static_cast<std::size_t>(e)];
          if (el.j >= 0) expected[static_cast<std::size_t>(el.j)] -= f[static_cast<std::size_t>(e)];
        }
        bilinear_scatter(*kernels, layout, f.data(), p.data());
        CHECK(p == expected);
        if (chain) {  // the storeys' forces and z
          std::vector<double> force = p, hyst(static_cast<std::size_t>(n));
          kernels->chain_storeys(n, f.data(), b.q.data(), layout.k.data(), force.data(), hyst.data());
          for (int e = 0; e < n; ++e) {
            CHECK(force[static_cast<std::size_t>(e)] == p[static_cast<std::size_t>(e)] + f[static_cast<std::size_t>(e)]);
            CHECK(hyst[static_cast<std::size_t>(e)] == b.q[e] / layout.k[e]);
          }
        }
      }
    }
  }
}
