// fractional/soe_history: the sum-of-exponentials history. Its weights against exact ones
// (long double recurrences) for GL and BDF2 at orders 0.05..0.95 and lags to 2^22; its lag
// sums against the direct engine's; whole runs (the paper's strong scene on both steppers, a
// record scene with 130 switches, a building with Zener storeys, a friction link and a
// contact) against direct, with the same switches; order 2 kept;
// constant history memory; the scene keys and the summary's bound.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>

#include "adjoin/fractional/direct_history.hpp"
#include "adjoin/fractional/soe_history.hpp"
#include "adjoin/fractional/weights.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/study/run.hpp"
#include "scene_helpers.hpp"
#include "state_recorder.hpp"

using namespace adjoin;
using adjoin::test::paper_scene;
using adjoin::test::trajectory;

namespace {

// The largest relative error of the compression's weights over lags n0..N (every lag below
// 8192, every 61st above), against J.C.P. Miller's recurrence for delta^order run in long
// double (the double recurrence of bdf2_weights drifts by 2e-10 relative by 2^22 lags at
// orders 0.05 and 0.95, so it cannot be the reference there; the long double one drifts by
// about 1e-13).
double largest_weight_error(const SoeCompression& c, std::size_t N) {
  const long double a = c.order;
  const long double p0 = c.rule == WeightRule::bdf2 ? 1.5L : 1.0L, p1 = c.rule == WeightRule::bdf2 ? -2.0L : -1.0L,
                    p2 = c.rule == WeightRule::bdf2 ? 0.5L : 0.0L;
  long double before = 0.0L, last = std::pow(p0, a);  // w_{n-2}, w_{n-1}
  double worst = 0.0;
  for (std::size_t n = 1; n <= N; ++n) {
    const long double dn = static_cast<long double>(n);
    long double s = ((a + 1) - dn) * p1 * last;
    if (n >= 2) s += ((a + 1) * 2 - dn) * p2 * before;
    const long double w = s / (dn * p0);
    before = last;
    last = w;
    if (n >= c.window && (n < 8192 || n % 61 == 0 || n == N))
      worst = std::max(worst, static_cast<double>(std::fabs((c.weight(n) - w) / w)));
  }
  return worst;
}

template <class Get>
double largest_difference(const std::vector<StructureState>& a, const std::vector<StructureState>& b, Get get) {
  double scale = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    scale = std::max(scale, std::abs(get(a[i])));
    diff = std::max(diff, std::abs(get(a[i]) - get(b[i])));
  }
  return diff / scale;
}

using Recorder = adjoin::test::StateRecorder;

}  // namespace

TEST_CASE("soe weights are within the tolerance of the exact ones for orders 0.05 to 0.95 up to 2^22 lags", "[soe]") {
  const std::size_t N = std::size_t{1} << 22;
  for (WeightRule rule : {WeightRule::grunwald_letnikov, WeightRule::bdf2})
    for (int k = 0; k < 10; ++k) {
      const double order = 0.05 + 0.1 * k;
      const auto c = soe_compression(rule, order, 1e-12, N);
      const double error = largest_weight_error(*c, N);
      INFO((rule == WeightRule::bdf2 ? "bdf2" : "gl") << " order " << order << ": " << c->modes() << " modes, error "
                                                       << error << ", reported " << c->error);
      CHECK(error < 1e-12);
      CHECK(c->error <= 1e-12);
      // The reported bound is the error where the long double reference is exact to 1e-16
      // (its own drift reaches 1e-13 by 2^22 lags, so the bound is checked below 8192 only).
      CHECK(largest_weight_error(*c, 8191) <= c->error * (1 + 1e-3) + 1e-15);
      CHECK(c->modes() <= 100);
      // Below the window: the exact weights themselves.
      const std::vector<double> exact = convolution_weights(rule, order, c->window);
      for (std::size_t n = 0; n < c->window; ++n) CHECK(c->weight(n) == exact[n]);
    }
}

TEST_CASE("a looser soe tolerance takes fewer modes and keeps its bound", "[soe]") {
  const std::size_t N = std::size_t{1} << 20;
  const auto tight = soe_compression(WeightRule::bdf2, 0.5, 1e-12, N);
  const auto loose = soe_compression(WeightRule::bdf2, 0.5, 1e-6, N);
  CHECK(loose->modes() < tight->modes() * 2 / 3);
  CHECK(loose->error <= 1e-6);
  CHECK(largest_weight_error(*loose, N) < 1e-6);
  CHECK_THROWS_AS(soe_compression(WeightRule::bdf2, 1.0, 1e-12, 1000), std::invalid_argument);
  CHECK_THROWS_AS(soe_compression(WeightRule::bdf2, 0.5, 1e-16, 1000), std::invalid_argument);
  // At the smallest tolerance accepted the bound is still reported as found.
  const auto finest = soe_compression(WeightRule::bdf2, 0.5, 1e-15, 1000);
  CHECK(finest->error < 1e-13);
  CHECK(finest->modes() < 200);
}

TEST_CASE("a soe compression is designed for the run's length rounded up to a power of two", "[soe]") {
  for (WeightRule rule : {WeightRule::grunwald_letnikov, WeightRule::bdf2}) {
    const auto short_run = soe_compression(rule, 0.53, 1e-12, 8000);
    const auto long_run = soe_compression(rule, 0.53, 1e-12, 100000);
    CHECK(short_run->design_length == 8192);
    CHECK(long_run->design_length == 131072);
    CHECK(soe_compression(rule, 0.53, 1e-12, 8192) == short_run);  // the same length: the cached one
    CHECK(soe_compression(rule, 0.53, 1e-12, 10)->design_length == 1024);  // the least
    // A longer run made before does not change a short run's modes.
    CHECK(soe_compression(rule, 0.53, 1e-12, 5000) == short_run);
    CHECK(short_run->modes() < long_run->modes());
    // The reported bound holds over the lags the design serves (every one, exact reference).
    CHECK(short_run->error <= 1e-12);
    CHECK(largest_weight_error(*short_run, 8192) <= short_run->error * (1 + 1e-3) + 1e-15);
  }
}

TEST_CASE("soe lag sums equal the direct engine's within the weights' bound", "[soe]") {
  const std::size_t count = 16385;
  for (WeightRule rule : {WeightRule::grunwald_letnikov, WeightRule::bdf2}) {
    const std::vector<double> w = convolution_weights(rule, 0.37, count);
    DirectHistory direct(w);
    const auto soe = make_history(HistoryEngine::soe, rule, 0.37, count, 1e-12);
    std::mt19937 random(7);
    std::normal_distribution<double> normal;
    std::vector<double> y;
    double worst = 0.0;
    for (std::size_t m = 0; m + 1 < count; ++m) {
      y.push_back(std::sin(1e-3 * static_cast<double>(m)) + 0.1 * normal(random));
      direct.push(y.back());
      soe->push(y.back());
      if (m % 97 != 0) continue;
      double size = 0.0;  // sum |w_j y_{m+1-j}|: the scale a relative weight error acts on
      for (std::size_t j = 1; j <= y.size(); ++j) size += std::abs(w[j] * y[y.size() - j]);
      worst = std::max(worst, std::abs(soe->lag_sum() - direct.lag_sum()) / size);
    }
    INFO("largest difference relative to sum |w y|: " << worst);
    CHECK(worst < 1e-12);
    CHECK(soe->size() == direct.size());
    soe->push(0.0);  // y_N: the last one accepted
    CHECK(soe->lag_sum() == 0.0);
    CHECK_THROWS_AS(soe->push(0.0), std::logic_error);
  }
}

TEST_CASE("the strong scene with soe follows direct on both steppers, with the same switches", "[soe][scene]") {
  for (const char* scheme : {"paper", "implicit"}) {
    const std::string s = std::string("solver.scheme=") + scheme;
    const auto direct = trajectory(paper_scene("strong", {s, "solver.history=direct"}));
    const auto soe = trajectory(paper_scene("strong", {s, "solver.history=soe"}));
    REQUIRE(direct.size() == soe.size());
    int switches = 0;
    for (std::size_t i = 0; i < direct.size(); ++i) {
      CHECK(direct[i].link_phase[0] == soe[i].link_phase[0]);
      switches += i > 0 && direct[i].link_phase[0] != direct[i - 1].link_phase[0];
    }
    CHECK(switches >= 4);  // stick, alternating slips, final stick
    const double dx1 = largest_difference(direct, soe, [](const StructureState& x) { return x.x[0]; });
    const double dx2 = largest_difference(direct, soe, [](const StructureState& x) { return x.x[1]; });
    const double df1 = largest_difference(direct, soe, [](const StructureState& x) { return x.storey_force[0]; });
    const double df2 = largest_difference(direct, soe, [](const StructureState& x) { return x.storey_force[1]; });
    const double dq = largest_difference(direct, soe, [](const StructureState& x) { return x.link_force[0]; });
    INFO(scheme << ": relative differences x1 " << dx1 << ", x2 " << dx2 << ", f1 " << df1 << ", f2 " << df2 << ", q " << dq);
    CHECK(std::max({dx1, dx2, df1, df2, dq}) < 1e-10);
  }
}

TEST_CASE("a record scene with over a hundred switches: soe follows direct with the same switches", "[soe][scene]") {
  // si-record with a tenth of its slip force: 131 phases in 30 s (15,000 steps).
  auto run = [](const char* engine) {
    return trajectory(load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/si-record.toml",
                                 {std::string("solver.history=") + engine, "model.slip_force=2e4"}));
  };
  const auto direct = run("direct"), soe = run("soe");
  REQUIRE(direct.size() == soe.size());
  int switches = 0;
  bool same = true;
  for (std::size_t i = 0; i < direct.size(); ++i) {
    same = same && direct[i].link_phase[0] == soe[i].link_phase[0];
    switches += i > 0 && direct[i].link_phase[0] != direct[i - 1].link_phase[0];
  }
  CHECK(same);
  CHECK(switches > 100);
  const double dx1 = largest_difference(direct, soe, [](const StructureState& x) { return x.x[0]; });
  const double dq = largest_difference(direct, soe, [](const StructureState& x) { return x.link_force[0]; });
  const double df2 = largest_difference(direct, soe, [](const StructureState& x) { return x.storey_force[1]; });
  INFO(switches << " switches; relative differences x1 " << dx1 << ", q " << dq << ", f2 " << df2);
  CHECK(std::max({dx1, dq, df2}) < 1e-10);
}

TEST_CASE("a building with Zener storeys, a friction link and a contact: soe follows direct", "[soe][building]") {
  const std::string file = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";
  auto run = [&](const char* engine) {
    const BuildingScene scene = load_building_scene(file, {std::string("solver.history=") + engine, "solver.t_end=15"});
    Recorder r;
    const SolverSummary summary = simulate_structure(scene.solver, scene.structure, *scene.ground, r);
    return std::pair{r.states, summary};
  };
  const auto [direct, direct_summary] = run("direct");
  const auto [soe, soe_summary] = run("soe");
  REQUIRE(direct.size() == soe.size());
  CHECK(soe_summary.history_modes > 0);
  CHECK(soe_summary.history_error <= 1e-12);
  CHECK(direct_summary.history_error == 0.0);
  double scale = 0.0, diff = 0.0, force_scale = 0.0, force_diff = 0.0;
  int switches = 0;
  for (std::size_t i = 0; i < direct.size(); ++i) {
    scale = std::max(scale, direct[i].x.cwiseAbs().maxCoeff());
    diff = std::max(diff, (direct[i].x - soe[i].x).cwiseAbs().maxCoeff());
    force_scale = std::max(force_scale, direct[i].link_force.cwiseAbs().maxCoeff());
    force_diff = std::max(force_diff, (direct[i].link_force - soe[i].link_force).cwiseAbs().maxCoeff());
    CHECK(direct[i].link_phase == soe[i].link_phase);
    switches += i > 0 && direct[i].link_phase != direct[i - 1].link_phase;
  }
  INFO("switches " << switches << ", relative differences: floors " << diff / scale << ", link force " << force_diff / force_scale);
  CHECK(switches >= 10);
  CHECK(diff < 1e-10 * scale);
  CHECK(force_diff < 1e-10 * force_scale);
}

TEST_CASE("soe keeps the implicit scheme's order 2 on the strong scene", "[soe][order]") {
  std::vector<Report> r;
  for (const char* h : {"0.004", "0.002", "0.001"})
    r.push_back(run(paper_scene("strong", {"solver.scheme=implicit", "solver.history=soe", std::string("solver.h=") + h})));
  auto order = [&](auto get) { return std::log2(std::abs(get(r[0]) - get(r[1])) / std::abs(get(r[1]) - get(r[2]))); };
  const double p_x1 = order([](const Report& x) { return x.peak("A.x1").max_abs; });
  const double p_friction = order([](const Report& x) { return x.link_energy(0); });
  INFO("orders: x1 " << p_x1 << ", friction " << p_friction);
  CHECK(p_x1 > 1.7);
  CHECK(p_friction > 1.7);
}

TEST_CASE("soe's history memory does not grow with the number of steps", "[soe][memory]") {
  // h = 0.002: t_end = 8.192 is 2^12 steps, 131.072 is 2^16.
  auto bytes = [](const char* engine, const char* t_end) {
    return run(paper_scene("strong", {"solver.scheme=implicit", std::string("solver.history=") + engine,
                                            std::string("solver.t_end=") + t_end, "solver.error_estimate=false"}))
        .solver.history_bytes;
  };
  const std::size_t small = bytes("soe", "8.192"), large = bytes("soe", "131.072");
  CHECK(small > 0);
  // The compression is designed for the run's length: Q changes slowly with it (about 60
  // modes at 2^12 steps, 70 at 2^16, 88 at 2^24), nothing else grows.
  CHECK(large < small * 5 / 4);
  CHECK(small < large * 5 / 4);
  CHECK(large < 40000);  // two rods: about 90 modes and a 32-lag window each, and the shared coefficients
  CHECK(bytes("fft", "131.072") > 8 * bytes("fft", "8.192"));  // what it replaces grows
}

TEST_CASE("solver.history = soe and solver.history_tolerance from a scene, the bound in the summary", "[soe][scene]") {
  const Scene scene = paper_scene("strong", {"solver.history=soe", "solver.history_tolerance=1e-9"});
  const Report r = run(scene);
  CHECK(r.solver.history == "soe");
  const auto summary = nlohmann::json::parse(summary_json(scene, r));
  CHECK(summary["solver"]["history_error"].get<double>() == r.solver.history_error);
  CHECK(summary["solver"]["history_modes"].get<std::size_t>() == r.solver.history_modes);
  CHECK(r.solver.history_error > 0.0);
  CHECK(r.solver.history_error <= 1e-9);
  CHECK(r.solver.history_modes > 10);
  CHECK(r.solver.history_modes < soe_compression(WeightRule::grunwald_letnikov, 0.23, 1e-12, 8000)->modes());
  const Report exact = run(paper_scene("strong", {"solver.history=fft"}));
  CHECK(exact.solver.history_error == 0.0);
  CHECK(exact.solver.history_modes == 0);
  CHECK_FALSE(nlohmann::json::parse(summary_json(paper_scene("strong", {"solver.history=fft"}), exact))["solver"].contains("history_error"));
  CHECK_THROWS_WITH(paper_scene("strong", {"solver.history_tolerance=0"}), Catch::Contains("solver.history_tolerance"));
  CHECK_THROWS_WITH(paper_scene("strong", {"solver.history_tolerance=1e-16"}), Catch::Contains("[1e-15, 1)"));
  CHECK_THROWS_WITH(paper_scene("strong", {"solver.history=sum"}), Catch::Contains("\"soe\""));
}
