// The implicit schemes (the default): exact stick, second order, stability, shortcuts.
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/study/run.hpp"
#include "scene_helpers.hpp"

using namespace adjoin;
using adjoin::test::paper_scene;
using adjoin::test::trajectory;

namespace {

double order_of(double coarse_error, double fine_error) { return std::log2(coarse_error / fine_error); }

// Exact response of x'' + w^2 x = u0 W^2 e^{-k t} sin(W t) from rest.
double sdof_decaying_sine(double w, double u0, double W, double k, double t) {
  using C = std::complex<double>;
  const C s(-k, W);
  const C a = u0 * W * W / (s * s + w * w);
  return (a * std::exp(s * t)).imag() - a.imag() * std::cos(w * t) - (a * s).imag() / w * std::sin(w * t);
}

}  // namespace

TEST_CASE("implicit is the default scheme", "[implicit]") {
  CHECK(SolverOptions{}.scheme == Scheme::implicit);
  const Scene s = paper_scene("strong", {"solver.scheme=implicit"});
  CHECK(s.solver.scheme == Scheme::implicit);
}

TEST_CASE("implicit, weak excitation: stick throughout, exactly one velocity", "[implicit]") {
  for (const char* scheme : {"implicit", "implicit-gl"}) {
    const Scene scene = paper_scene("weak", {std::string("solver.scheme=") + scheme});
    double max_q = 0.0;
    for (const StructureState& s : trajectory(scene)) {
      REQUIRE(s.link_phase[0] == Phase::stick);
      REQUIRE(s.x[0] == s.x[1]);
      REQUIRE(s.v[0] == s.v[1]);
      max_q = std::max(max_q, std::abs(s.link_force[0]));
    }
    CHECK(max_q < two_block_model(scene).mu);
    CHECK(max_q > 0.5 * two_block_model(scene).mu);
  }
}

TEST_CASE("implicit, strong excitation: the paper's phase structure, exact final stick", "[implicit]") {
  const Scene scene = paper_scene("strong", {"solver.scheme=implicit"});
  const double mu = two_block_model(scene).mu;
  const Report report = run(scene);
  const auto& phases = report.phases;
  REQUIRE(phases.size() >= 4);
  CHECK(phases.front().state == Phase::stick);
  CHECK(phases.front().t_end > 0.1);
  CHECK(phases.front().t_end < 1.0);
  CHECK(phases[1].state != Phase::stick);
  REQUIRE(phases.back().state == Phase::stick);
  const double t_star = phases.back().t_start;
  CHECK(t_star > 4.0);
  CHECK(t_star < 14.0);
  // Located switching instants lie between grid points.
  bool off_grid = false;
  for (const auto& p : phases) off_grid |= std::abs(std::remainder(p.t_start, scene.solver.h)) > 1e-9;
  CHECK(off_grid);

  const auto states = trajectory(scene);
  double c = std::nan("");
  for (std::size_t i = 1; i < states.size(); ++i) {
    const StructureState& s = states[i];
    REQUIRE(two_block_model(scene).gap0 + s.x[1] - s.x[0] > 0.0);
    REQUIRE(std::abs(s.link_force[0]) <= mu);
    if (s.link_phase[0] == Phase::stick) REQUIRE(s.v[0] == s.v[1]);  // stick holds exactly: no chatter
    // In slip, q sits on the limit, except in the step where the slip reverses (its average).
    if (s.link_phase[0] != Phase::stick && states[i - 1].link_phase[0] == s.link_phase[0]) {
      REQUIRE(std::abs(s.link_force[0]) == mu);
      REQUIRE((s.link_force[0] > 0) == (s.link_phase[0] == Phase::slip_right));
    }
    if (s.t > t_star + 2 * scene.solver.h) {
      if (std::isnan(c)) c = s.x[0] - s.x[1];
      REQUIRE(s.x[0] - s.x[1] == Approx(c).margin(1e-14));  // frozen (to rounding)
      REQUIRE(std::abs(s.link_force[0]) < mu);
    }
  }
  CHECK(std::abs(c) > 1e-3);
  CHECK(report.link_energy(0) > 0.0);
}

TEST_CASE("implicit: second order on the strong scene (peaks, gap, friction energy, energy residual)", "[implicit][order]") {
  // Successive differences over h = 0.004, 0.002, 0.001 give the observed order without a
  // reference solution; the residual of the energy balance is itself an error.
  std::vector<Report> r;
  for (const char* h : {"0.004", "0.002", "0.001"})
    r.push_back(run(paper_scene("strong", {"solver.scheme=implicit", std::string("solver.h=") + h})));
  auto order = [&](auto get) { return order_of(std::abs(get(r[0]) - get(r[1])), std::abs(get(r[1]) - get(r[2]))); };
  const double p_x1 = order([](const Report& x) { return x.peak("A.x1").max_abs; });
  const double p_gap = order([](const Report& x) { return x.contacts.at(0).min_gap; });
  const double p_friction = order([](const Report& x) { return x.link_energy(0); });
  const double p_residual = order_of(std::abs(r[0].energy.residual), std::abs(r[2].energy.residual)) / 2.0;
  INFO("orders: x1 " << p_x1 << ", gap " << p_gap << ", friction " << p_friction << ", residual " << p_residual);
  CHECK(p_x1 > 1.7);
  CHECK(p_gap > 1.7);
  CHECK(p_friction > 1.7);
  CHECK(p_residual > 1.7);
  // And already accurate: relative change from h = 0.002 to 0.001 below 1e-5.
  CHECK(std::abs(r[1].peak("A.x1").max_abs - r[2].peak("A.x1").max_abs) < 1e-5 * r[2].peak("A.x1").max_abs);
  CHECK(std::abs(r[1].link_energy(0) - r[2].link_energy(0)) < 1e-5 * r[2].link_energy(0));
}

TEST_CASE("observed orders on the smooth (stick-only) weak scene: implicit 2, implicit-gl and paper 1", "[implicit][order]") {
  auto x16 = [](const char* scheme, const char* h) {
    return run(paper_scene("weak", {std::string("solver.scheme=") + scheme, std::string("solver.h=") + h})).last_value("A.x1");
  };
  for (auto [scheme, expected] : {std::pair{"implicit", 2.0}, {"implicit-gl", 1.0}, {"paper", 1.0}}) {
    const double a = x16(scheme, "0.004"), b = x16(scheme, "0.002"), c = x16(scheme, "0.001");
    const double p = order_of(std::abs(a - b), std::abs(b - c));
    INFO(scheme << ": x(16) = " << a << ", " << b << ", " << c << "; order " << p);
    CHECK(p == Approx(expected).margin(0.15));
  }
}

TEST_CASE("implicit, elastic rods without damper: second order against the closed form", "[implicit][analytic]") {
  Model model;
  model.mu = 0.0;
  model.rod1 = Rod::Elastic();
  model.rod2 = Rod::Elastic();
  const DecayingSine ground(1.5, 1.5, 0.5);
  std::vector<double> errors;
  for (double h : {0.02, 0.01, 0.005}) {
    test::StateRecorder recorder;
    SolverOptions options;
    options.h = h;
    simulate_as_structure(options, model, ground, recorder);
    double e = 0.0;
    for (const StructureState& s : recorder.states) {
      e = std::max(e, std::abs(s.x[0] - sdof_decaying_sine(1.0, 1.5, 1.5, 0.5, s.t)));
      e = std::max(e, std::abs(s.x[1] - sdof_decaying_sine(std::sqrt(model.rho * model.eps), 1.5, 1.5, 0.5, s.t)));
    }
    errors.push_back(e);
  }
  CHECK(order_of(errors[0], errors[1]) == Approx(2.0).margin(0.1));
  CHECK(order_of(errors[1], errors[2]) == Approx(2.0).margin(0.1));
  CHECK(errors.back() < 1e-4);
}

TEST_CASE("implicit stays stable and accurate where the paper scheme must stop", "[implicit][stability]") {
  const std::vector<std::string> stiff = {"model.rod1.order=0.9", "model.rod1.tau_x=100", "model.rod1.tau_f=1e-4"};
  auto with = [&](const char* scheme, const char* h) {
    auto o = stiff;
    o.push_back(std::string("solver.scheme=") + scheme);
    o.push_back(std::string("solver.h=") + h);
    return paper_scene("strong", o);
  };
  CHECK_THROWS_AS(run(with("paper", "0.1")), NumericalError);
  const Report coarse = run(with("implicit", "0.1"));
  const Report fine = run(with("implicit", "0.001"));
  CHECK(std::isfinite(coarse.peak("A.x1").max_abs));
  CHECK(coarse.peak("A.x1").max_abs == Approx(fine.peak("A.x1").max_abs).epsilon(0.05));
  CHECK(std::abs(coarse.energy.residual) < 0.01 * coarse.energy.input);
}

TEST_CASE("shortcuts agree with the general path: mu = 0 and elastic rods", "[implicit][shortcuts]") {
  auto run = [](std::vector<std::string> o, bool elastic_rod2 = false) {
    if (elastic_rod2) o.push_back("model.rod2.elastic=true");
    const Scene scene = paper_scene("strong", o);
    test::StateRecorder r;
    adjoin::run(scene, {&r});
    return r.states;
  };
  // mu = 0 skips the damper logic; a vanishing slip force goes through it.
  const auto free = run({"model.mu=0"});
  const auto tiny = run({"model.mu=1e-13"});
  REQUIRE(free.size() == tiny.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < free.size(); ++i) worst = std::max({worst, std::abs(free[i].x[0] - tiny[i].x[0]), std::abs(free[i].x[1] - tiny[i].x[1])});
  CHECK(worst < 1e-10);
  CHECK(worst > 0.0);  // really two different paths

  // An elastic rod carries no history; a fractional one with tau_x -> tau_f tends to it.
  const auto elastic = run({"model.mu=0"}, true);
  const auto nearly = run({"model.rod2.tau_x=0.2000000001", "model.mu=0"});
  worst = 0.0;
  for (std::size_t i = 0; i < elastic.size(); ++i) worst = std::max(worst, std::abs(elastic[i].x[1] - nearly[i].x[1]));
  CHECK(worst < 1e-8);
  CHECK(worst > 0.0);
}
