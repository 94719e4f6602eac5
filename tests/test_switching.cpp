// The implicit schemes' reported values at the scheme's order (issue: every reported number at
// order 2, no spurious switches): q at every grid point, switching instants of every kind, the
// time of the minimum gap at a kink, and the switch count on stiff and record-driven cases.
// Targets come from the exact solution of the weak scene and from much finer runs.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/study/linear_reference.hpp"
#include "scene_helpers.hpp"

using namespace adjoin;
using adjoin::test::paper_scene;
using adjoin::test::trajectory;

namespace {

// Least-squares slope of log2(error) against -log2(h) over a ladder halving h each rung.
double fitted_order(const std::vector<double>& errors) {
  const std::size_t n = errors.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i), y = -std::log2(errors[i]);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::vector<std::string> implicit_fft(double h) {
  return {"solver.scheme=implicit", "solver.history=fft", "solver.h=" + std::to_string(h)};
}

}  // namespace

TEST_CASE("weak scene: q at every grid point and final.q converge at order 2 to the exact solution", "[switching][exact]") {
  const Scene base = paper_scene("weak");
  const auto* sine = dynamic_cast<const DecayingSine*>(base.ground.get());
  REQUIRE(sine);
  const LinearReference exact(two_block_model(base), sine->u0(), sine->omega(), sine->k(), true);
  std::vector<double> max_q_error, final_q_error, threshold_error;
  // mu*: the smallest mu that never slips = max |q| of the exact solution, found on a 1e-3 grid
  // and refined by golden-section search around it.
  double t_best = 0.0, exact_threshold = 0.0;
  for (double t = 0.0; t <= 16.0; t += 1e-3)
    if (std::abs(exact.at(t).link_force) > exact_threshold) { exact_threshold = std::abs(exact.at(t).link_force); t_best = t; }
  double lo = t_best - 1e-3, hi = t_best + 1e-3;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 60; ++i) {
    const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
    (std::abs(exact.at(a).link_force) > std::abs(exact.at(b).link_force) ? hi : lo) = (std::abs(exact.at(a).link_force) > std::abs(exact.at(b).link_force) ? b : a);
  }
  exact_threshold = std::max(exact_threshold, std::abs(exact.at(0.5 * (lo + hi)).link_force));
  for (double h : {0.004, 0.002, 0.001, 0.0005}) {
    const std::vector<StructureState> states = trajectory(paper_scene("weak", implicit_fft(h)));
    double worst = 0.0;
    for (std::size_t m = 0; m < states.size(); m += 5) worst = std::max(worst, std::abs(states[m].link_force[0] - exact.at(states[m].t).link_force));
    max_q_error.push_back(worst);
    final_q_error.push_back(std::abs(states.back().link_force[0] - exact.at(16.0).link_force));
    // The run's mu*: its reported peak |q| (refined between samples while stuck).
    threshold_error.push_back(std::abs(run(paper_scene("weak", implicit_fft(h))).peak("link1.force").max_abs - exact_threshold));
  }
  INFO("q errors " << max_q_error[0] << " " << max_q_error[3] << "; final " << final_q_error[0] << " " << final_q_error[3]
                   << "; mu* " << threshold_error[0] << " " << threshold_error[3]);
  CHECK(fitted_order(max_q_error) == Approx(2.0).margin(0.15));
  CHECK(fitted_order(final_q_error) == Approx(2.0).margin(0.2));
  CHECK(final_q_error[1] < 1e-7);  // h = 0.002: was 6.2e-6 when q was the step's average
  CHECK(fitted_order(threshold_error) > 1.8);
}

TEST_CASE("strong scene: every switching instant and t_min_gap at order 2", "[switching]") {
  const Report reference = run(paper_scene("strong", implicit_fft(3.125e-5)));
  REQUIRE(reference.phases.size() == 8);
  const std::vector<double> ladder = {4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4};
  std::vector<std::vector<double>> switch_errors(reference.phases.size());
  std::vector<double> gap_time_errors, peak_time_errors;
  for (double h : ladder) {
    const Report r = run(paper_scene("strong", implicit_fft(h)));
    REQUIRE(r.phases.size() == reference.phases.size());
    for (std::size_t i = 1; i < r.phases.size(); ++i) {
      CHECK(r.phases[i].state == reference.phases[i].state);
      switch_errors[i].push_back(std::abs(r.phases[i].t_start - reference.phases[i].t_start));
    }
    gap_time_errors.push_back(std::abs(r.contacts.at(0).t_min_gap - reference.contacts.at(0).t_min_gap));
    peak_time_errors.push_back(std::abs(r.peak("A.x1").t - reference.peak("A.x1").t));
  }
  for (std::size_t i = 1; i < switch_errors.size(); ++i) {
    INFO("switch " << i << " (" << to_string(reference.phases[i].state) << " at " << reference.phases[i].t_start
                   << "): errors " << switch_errors[i].front() << " ... " << switch_errors[i].back());
    CHECK(fitted_order(switch_errors[i]) > 1.8);
    // h = 1e-3: the first stick -> slip was 1.6e-4 off on the grid. The largest error now is
    // the onset after the short stick at 8.20 (4.8e-6, regular at order 2): the stick force
    // barely reaches mu there (it grazes the cone with slope 0.09), so its O(h^2) error is
    // divided by a small slope.
    CHECK(switch_errors[i][2] < 1e-5);
  }
  INFO("t_min_gap errors " << gap_time_errors.front() << " ... " << gap_time_errors.back());
  CHECK(fitted_order(gap_time_errors) > 1.8);  // was first order (0.18 h): the minimum sits on a reversal
  CHECK(fitted_order(peak_time_errors) > 1.8);
}

TEST_CASE("a mode stiff against the step does not make the damper chatter", "[switching][stiff]") {
  // The true motion has 10 switches (11 phases) in both cases; the trapezoidal mechanics alone
  // gave 22 and 128 at these steps.
  struct Case { const char* rho; double h; };
  for (const Case c : {Case{"1e5", 0.002}, Case{"1e4", 0.02}}) {
    const std::size_t truth =
        run(paper_scene("strong", {"solver.scheme=implicit", "solver.history=fft", "model.rho=" + std::string(c.rho),
                                         "solver.h=" + std::to_string(c.h / 16)}))
            .phases.size();
    CHECK(truth == 11);
    for (double h : {c.h, c.h / 2, c.h / 4}) {
      const Report r = run(paper_scene(
          "strong", {"solver.scheme=implicit", "solver.history=fft", "model.rho=" + std::string(c.rho), "solver.h=" + std::to_string(h)}));
      INFO("rho = " << c.rho << ", h = " << h);
      CHECK(r.phases.size() == truth);
      CHECK(std::abs(r.energy.residual) < 1e-3 * r.energy.input);
    }
  }
}

TEST_CASE("a record scene with hundreds of switches: the same count at h, h/2, h/4 and 16x finer", "[switching][record]") {
  const std::string scene = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/si-record.toml";
  const std::string record = std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN1044_DirRot2.AT2";
  auto phases = [&](double h, const char* slip_force) {
    const Scene s = load_scene(scene, {"ground.file=\"" + record + "\"", std::string("model.slip_force=") + slip_force,
                                       "solver.t_end=40", "solver.history=fft", "solver.h=" + std::to_string(h)},
                               {"ground.units", "ground.scale_pga"});
    return run(s).phases;
  };
  const std::size_t finest = phases(0.002 / 16, "5e3").size();
  CHECK(finest == 158);  // 157 switches
  for (double h : {0.002, 0.001, 0.0005}) {
    INFO("h = " << h);
    CHECK(phases(h, "5e3").size() == finest);
  }
  // Slip force 2e5 N: at h = 0.002 a stick of 1.1 ms was reported where the motion reverses
  // directly (the stick force at the crossing is 1.0044 mu). Now the phases are those of a run
  // 16x finer, state by state, and no stick is shorter than a step unless the fine run has it.
  const auto fine = phases(0.002 / 16, "2e5");
  for (double h : {0.002, 0.001, 0.0005}) {
    INFO("slip force 2e5 N, h = " << h);
    const auto coarse = phases(h, "2e5");
    REQUIRE(coarse.size() == fine.size());
    for (std::size_t i = 0; i < fine.size(); ++i) {
      CHECK(coarse[i].state == fine[i].state);
      CHECK(coarse[i].t_start == Approx(fine[i].t_start).margin(0.01));
    }
  }
}
