// The paper's scheme on the paper's two scenes and on a case with a closed-form solution.
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <map>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/observe/energy.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/study/run.hpp"
#include "scene_helpers.hpp"

using namespace adjoin;
using adjoin::test::paper_scene;
using adjoin::test::trajectory;

namespace {

// Exact response of x'' + w^2 x = u0 W^2 e^{-k t} sin(W t) from rest.
double sdof_decaying_sine(double w, double u0, double W, double k, double t) {
  using C = std::complex<double>;
  const C s(-k, W);
  const C a = u0 * W * W / (s * s + w * w);  // particular solution Im(a e^{st})
  const double c1 = -a.imag();
  const double c2 = -(a * s).imag() / w;
  return (a * std::exp(s * t)).imag() + c1 * std::cos(w * t) + c2 * std::sin(w * t);
}

}  // namespace

TEST_CASE("weak excitation: stick throughout, x1 == x2, |q| < mu", "[paper]") {
  const Scene scene = paper_scene("weak");
  const Report report = run(scene);
  REQUIRE(report.phases.size() == 1);
  CHECK(report.phases[0].state == Phase::stick);
  CHECK(report.phases[0].t_end == Approx(16.0));

  double max_q = 0.0, max_x = 0.0;
  for (const StructureState& s : trajectory(scene)) {
    REQUIRE(s.x[0] == s.x[1]);  // stuck blocks move as one: exactly
    REQUIRE(s.v[0] == s.v[1]);
    max_q = std::max(max_q, std::abs(s.link_force[0]));
    max_x = std::max(max_x, std::abs(s.x[0]));
  }
  CHECK(max_q < two_block_model(scene).mu);
  CHECK(max_q > 0.5 * two_block_model(scene).mu);  // the damper is loaded, just not enough to slip
  CHECK(max_x > 0.05);                  // and the blocks do move
  CHECK(report.contacts.at(0).min_gap > 0.0);
  CHECK(report.link_energy(0) == 0.0);
}

TEST_CASE("strong excitation: short stick, alternating slips, final stick", "[paper]") {
  const Scene scene = paper_scene("strong");
  const double mu = two_block_model(scene).mu;
  const Report report = run(scene);
  const auto& phases = report.phases;
  REQUIRE(phases.size() >= 4);

  // A short stick at the start while q grows to mu.
  CHECK(phases.front().state == Phase::stick);
  CHECK(phases.front().t_end > 0.1);
  CHECK(phases.front().t_end < 1.0);
  // Then slips right and left alternate (the first slip is towards the growing q).
  CHECK(phases[1].state != Phase::stick);
  int slips = 0, reversals = 0;
  for (std::size_t i = 1; i + 1 < phases.size(); ++i) {
    if (phases[i].state != Phase::stick) ++slips;
    if (phases[i].state != Phase::stick && phases[i + 1].state != Phase::stick &&
        phases[i].state != phases[i + 1].state)
      ++reversals;
  }
  CHECK(slips >= 3);
  CHECK(reversals >= 2);
  // The last phase is a stick that holds to the end.
  const PhaseInterval last = phases.back();
  REQUIRE(last.state == Phase::stick);
  CHECK(last.t_start > 4.0);
  CHECK(last.t_start < 14.0);
  CHECK(last.t_end == Approx(16.0));

  const auto states = trajectory(scene);
  const double t_star = last.t_start;
  double c = 0.0, q_before = 0.0, q_at = 0.0, max_f = 0.0, late_f = 0.0;
  bool have_c = false;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const StructureState& s = states[i];
    REQUIRE(two_block_model(scene).gap0 + s.x[1] - s.x[0] > 0.0);  // no pounding
    max_f = std::max({max_f, std::abs(s.storey_force[0]), std::abs(s.storey_force[1])});
    if (s.t > 14.0) late_f = std::max({late_f, std::abs(s.storey_force[0]), std::abs(s.storey_force[1])});
    if (s.link_phase[0] != Phase::stick) {
      REQUIRE(std::abs(s.link_force[0]) == mu);  // q sits on the friction limit while slipping
      REQUIRE((s.link_force[0] > 0) == (s.link_phase[0] == Phase::slip_right));
    }
    if (s.t >= t_star - 1e-12) {
      if (!have_c) { c = s.x[0] - s.x[1]; have_c = true; q_at = s.link_force[0]; q_before = states[i - 1].link_force[0]; }
      REQUIRE(s.x[0] - s.x[1] == Approx(c).margin(1e-12));  // x1 - x2 frozen
      REQUIRE(std::abs(s.link_force[0]) < mu);                       // strictly inside the friction cone
    }
  }
  CHECK(std::abs(c) > 1e-3);                 // the blocks stick apart, not together
  CHECK(std::abs(q_before) == mu);           // q jumps at t*
  CHECK(std::abs(q_at - q_before) > 1e-3);
  CHECK(late_f < 0.2 * max_f);               // forces decay
  CHECK(report.contacts.at(0).min_gap > 0.0);
  CHECK_FALSE(report.contacts.at(0).contact);
  CHECK(report.link_energy(0) > 0.0);
}

TEST_CASE("strong excitation: the energy residual shrinks with h", "[paper][energy]") {
  // The paper's scheme switches phases on the grid: entering stick sets block 2's velocity to
  // block 1's (x2 = x1 - c), an O(h) velocity jump whose energy error depends on where in the
  // step the relative velocity crossed zero. So the residual is O(h) but not monotone from one
  // h to the next; we check the O(h) bound on a ladder and the decrease over a factor of 8.
  std::map<std::string, double> residual;
  for (const char* h : {"0.004", "0.002", "0.001", "0.0005"}) {
    const Report r = run(paper_scene("strong", {std::string("solver.h=") + h}));
    residual[h] = std::abs(r.energy.residual) / r.energy.input;
    INFO("h = " << h << ": relative residual " << residual[h]);
    CHECK(residual[h] < 0.02 * std::stod(h));
    CHECK(r.energy.input > 7.0);  // the scene does put energy in
  }
  CHECK(residual["0.0005"] < residual["0.004"] / 4.0);
}

TEST_CASE("elastic rods, no damper: central differences match the closed-form SDOF response", "[paper][analytic]") {
  Model model;
  model.mu = 0.0;
  model.rod1 = Rod::Elastic();
  model.rod2 = Rod::Elastic();
  const double u0 = 1.5, W = 1.5, k = 0.5;
  const DecayingSine ground(u0, W, k);
  const double w1 = 1.0, w2 = std::sqrt(model.rho * model.eps);

  std::vector<double> errors;
  for (double h : {0.01, 0.005, 0.0025}) {
    test::StateRecorder recorder;
    SolverOptions options;
    options.h = h;
    options.t_end = 16.0;
    simulate_as_structure(options, model, ground, recorder);
    double error = 0.0;
    for (const StructureState& s : recorder.states) {
      error = std::max(error, std::abs(s.x[0] - sdof_decaying_sine(w1, u0, W, k, s.t)));
      error = std::max(error, std::abs(s.x[1] - sdof_decaying_sine(w2, u0, W, k, s.t)));
    }
    errors.push_back(error);
  }
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2]);
  // Central differences are second order: halving h quarters the error.
  for (std::size_t i = 1; i < errors.size(); ++i)
    CHECK(std::log2(errors[i - 1] / errors[i]) == Approx(2.0).margin(0.1));
  CHECK(errors.back() < 1e-4);
}

TEST_CASE("beyond its stability bound the paper scheme stops and names the step it needs", "[paper][stability]") {
  // A stiff rod: tau_x / tau_f = 1e6 at order 0.9.
  const std::vector<std::string> stiff = {"model.rod1.order=0.9", "model.rod1.tau_x=100", "model.rod1.tau_f=1e-4"};
  auto with_h = [&](double h) {
    auto o = stiff;
    o.push_back("solver.h=" + std::to_string(h));
    return paper_scene("strong", o);
  };
  double bound = 0.0;
  try {
    run(with_h(0.1));
    FAIL("expected a NumericalError");
  } catch (const NumericalError& e) {
    const std::string message = e.what();
    INFO(message);
    const auto at = message.find("need h < ");
    REQUIRE(at != std::string::npos);
    bound = std::stod(message.substr(at + 9));
    CHECK(message.find("solver.h") != std::string::npos);
  }
  REQUIRE(bound > 0.0);
  REQUIRE(bound < 0.1);
  // The stated bound is sharp: just inside it the response stays small, just outside it blows up.
  Scene inside = with_h(0.97 * bound);
  const Report ok = run(inside);
  CHECK(ok.peak("A.x1").max_abs < 0.1);
  Scene outside = with_h(1.05 * bound);
  outside.solver.stability_check = false;
  CHECK_THROWS_AS(run(outside), NumericalError);
}
