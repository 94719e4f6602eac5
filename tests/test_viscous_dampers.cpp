// Nonlinear viscous dampers (F = c |v|^alpha sign v, solver/viscous_step.hpp): a mass held only
// by one, launched at v0, against the closed form (finite-time stop, stroke, the energy it
// dissipates) at order 2; a frame with such dampers in its storeys and between two buildings
// under a ground motion, at order 2 against a run 16 times finer, with its energy balance;
// with a friction damper beside them (the two local solves in turn); the laws' mean force; a
// dashpot link's energy in summary.json against c times the integral of v^2 from the time series.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../src/solver/viscous_step.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"
#include "state_recorder.hpp"

using namespace adjoin;
using namespace adjoin::structure;

namespace {

using Recorder = adjoin::test::StateRecorder;

// One floor of mass m on a storey with only a viscous damper (and a spring so soft, 1e-6 N/m,
// that over the run its force stays below 1e-6 N against the damper's 1e6 N).
Structure damper_alone(double m, double c, double alpha) {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::VectorXd::Constant(1, m);
  s.a.springs = Eigen::VectorXd::Constant(1, 1e-6);
  StoreyDevice d;
  d.type = DeviceType::dashpot;
  d.storeys = {1};
  d.c = c;
  d.alpha = alpha;
  s.a.devices = {d};
  return s;
}

}  // namespace

TEST_CASE("a viscous law's step mean is the exact mean over a linear velocity", "[viscous]") {
  const detail::ViscousLaw law{2.0, 0.4};
  // Through zero: the integral of c |w|^alpha sign w over w from -0.3 to 0.5 (w linear in t).
  const double exact = 2.0 * (std::pow(0.5, 1.4) - std::pow(0.3, 1.4)) / (1.4 * 0.8);
  CHECK(law.mean(-0.3, 0.5) == Approx(exact).epsilon(1e-14));
  // Close ends (the series branch) against a 20-digit quadrature-free value: the difference
  // quotient in long double.
  const long double a = 0.7L, b = 0.7L + 1e-4L;
  const long double q = 2.0L * (std::pow(b, 1.4L) - std::pow(a, 1.4L)) / (1.4L * (b - a));
  CHECK(law.mean(0.7, 0.7 + 1e-4) == Approx(static_cast<double>(q)).epsilon(1e-13));
  // alpha = 1: the trapezoidal rule's mean.
  CHECK(detail::ViscousLaw{3.0, 1.0}.mean(0.2, -0.6) == Approx(3.0 * (0.2 - 0.6) / 2.0).epsilon(1e-15));
}

TEST_CASE("a mass held by a nonlinear viscous damper stops in finite time as the closed form says", "[viscous]") {
  const double m = 1e6, v0 = 1.0, alpha = 0.4, t_star = 1.0;
  const double c = m * std::pow(v0, 1.0 - alpha) / ((1.0 - alpha) * t_star);  // stops at t* = 1 s
  const double stroke = m * std::pow(v0, 2.0 - alpha) / ((2.0 - alpha) * c);
  auto v_exact = [&](double t) {
    const double r = std::pow(v0, 1.0 - alpha) - (1.0 - alpha) * c * t / m;
    return r > 0.0 ? std::pow(r, 1.0 / (1.0 - alpha)) : 0.0;
  };
  auto x_exact = [&](double t) { return m * (std::pow(v0, 2.0 - alpha) - std::pow(v_exact(t), 2.0 - alpha)) / ((2.0 - alpha) * c); };
  const Structure s = damper_alone(m, c, alpha);
  const DecayingSine still(0.0, 1.0, 0.0);
  std::vector<double> x_err, v_err, v_err_before;
  for (double h : {0.02, 0.01, 0.005}) {
    StructureSolverOptions o;
    o.h = h;
    o.t_end = 1.5;
    o.v0 = Eigen::VectorXd::Constant(1, v0);
    Recorder r;
    simulate_structure(o, s, still, r);
    double ex = 0.0, ev = 0.0, ev_before = 0.0;
    for (const auto& st : r.states) {
      ex = std::max(ex, std::abs(st.x[0] - x_exact(st.t)));
      ev = std::max(ev, std::abs(st.v[0] - v_exact(st.t)));
      if (st.t <= 0.8 * t_star) ev_before = std::max(ev_before, std::abs(st.v[0] - v_exact(st.t)));
    }
    x_err.push_back(ex);
    v_err.push_back(ev);
    v_err_before.push_back(ev_before);
    // At rest after t*: the stroke, and the force gone.
    CHECK(r.states.back().x[0] == Approx(stroke).epsilon(1e-3));
    // (no sawtooth about rest: the backward-Euler step after the velocity turns)
    CHECK(std::abs(r.states.back().v[0]) < 1e-12);
  }
  INFO("x errors " << x_err[0] << " " << x_err[1] << " " << x_err[2] << ", v errors " << v_err[0] << " " << v_err[1] << " "
                   << v_err[2] << ", before the stop " << v_err_before[0] << " " << v_err_before[1] << " " << v_err_before[2]);
  // The displacement at order 2 throughout; the velocity at order 2 before the stop and, near it
  // (v ~ (t* - t)^(1/(1-alpha)), whose second derivative is unbounded), at order 1/(1-alpha) = 5/3.
  for (int i = 0; i < 2; ++i) {
    CHECK(std::log2(x_err[i] / x_err[i + 1]) == Approx(2.0).margin(0.1));
    CHECK(std::log2(v_err_before[i] / v_err_before[i + 1]) == Approx(2.0).margin(0.1));
    CHECK(std::log2(v_err[i] / v_err[i + 1]) == Approx(1.0 / (1.0 - alpha)).margin(0.15));
  }
}

TEST_CASE("the work a stopping nonlinear viscous damper dissipates is the mass's kinetic energy", "[viscous]") {
  const double m = 1e6, v0 = 1.0, alpha = 0.4;
  const double c = m / (1.0 - alpha);  // stops at t* = 1 s
  std::vector<double> errors;
  for (double h : {0.02, 0.01, 0.005}) {
    BuildingRunOptions o;
    o.h = h;
    o.t_end = 1.5;
    o.error_estimate = false;
    RunSpec spec = building_run_spec(damper_alone(m, c, alpha), decaying_sine_ground(0.0, 1.0, 0.0), o);
    spec.solver.v0 = Eigen::VectorXd::Constant(1, v0);
    const Report r = run(spec);
    // (the spring's share, 1e-6 N/m over 0.375 m, is 7e-8 J)
    errors.push_back(std::abs(r.energy.buildings.at(0).storeys.at(0) - 0.5 * m * v0 * v0));
    CHECK(r.energy.buildings.at(0).kinetic < 1e-12);
  }
  INFO("errors of the damper's work " << errors[0] << " " << errors[1] << " " << errors[2] << " J of " << 0.5 * m * v0 * v0);
  CHECK(errors[0] < 1e-3 * 0.5 * m * v0 * v0);
  CHECK(std::log2(errors[0] / errors[1]) > 1.6);
  CHECK(std::log2(errors[1] / errors[2]) > 1.6);
}

namespace {

const std::filesystem::path kScene = std::filesystem::path(ADJOIN_SOURCE_DIR) / "records/scenes/buildings/two-frames.toml";

// The README's two frames under 8 s of Newhall, with nonlinear viscous dampers: alpha = 0.35 in
// A's first two storeys, an alpha = 0.4 link at floors [3, 3] instead of the friction damper
// (or, with `with_friction`, beside it on the same floors: where it sticks it locks the viscous
// damper, and at its onsets the two share the force).
RunSpec viscous_frames(bool with_friction) {
  RunSpec spec = load_building_scene(kScene, {"solver.t_end=8", "output.timeseries=false", "solver.error_estimate=false"});
  StoreyDevice d;
  d.type = DeviceType::dashpot;
  d.storeys = {1, 2};
  d.c = 5e4;
  d.alpha = 0.35;
  spec.structure.a.devices.push_back(d);
  Link l;
  l.type = LinkType::dashpot;
  l.c = 1.3e5;
  l.alpha = 0.4;
  l.floor_a = l.floor_b = 3;
  if (with_friction) spec.structure.links.push_back(l);
  else spec.structure.links.at(0) = l;
  return spec;
}

// Each building's top floor, at every grid point.
class Roofs final : public StructureObserver {
 public:
  void observe(const StructureState& s) override {
    t.push_back(s.t);
    a.push_back(s.x[4]);
    v.push_back(s.v[4]);
  }
  std::vector<double> t, a, v;
};

// Max |coarse - fine| over the coarse grid (the fine grid refines it by `ratio`).
double max_difference(const std::vector<double>& coarse, const std::vector<double>& fine, std::size_t ratio) {
  double e = 0.0;
  for (std::size_t i = 0; i < coarse.size(); ++i) e = std::max(e, std::abs(coarse[i] - fine[i * ratio]));
  return e;
}

void check_order_two(bool with_friction) {
  RunSpec spec = viscous_frames(with_friction);
  spec.solver.h = 0.004 / 16;
  Roofs reference;
  run(spec, {&reference});
  std::vector<double> ex, ev, residual;
  double link_energy = 0.0;
  for (int r : {1, 2, 4}) {
    spec.solver.h = 0.004 / r;
    Roofs roofs;
    const Report rep = run(spec, {&roofs});
    ex.push_back(max_difference(roofs.a, reference.a, 16 / r));
    ev.push_back(max_difference(roofs.v, reference.v, 16 / r));
    residual.push_back(std::abs(rep.energy.residual) / rep.energy.input);
    // Steps where a friction damper's onset and the viscous damper on its floors flipped each
    // other and the step took the mean: a few per onset at most.
    CHECK(rep.solver.viscous_split_steps <= rep.solver.steps / 100);
    link_energy = rep.energy.links.back();
  }
  INFO("roof x errors " << ex[0] << " " << ex[1] << " " << ex[2] << ", v errors " << ev[0] << " " << ev[1] << " " << ev[2]
                        << ", relative energy residuals " << residual[0] << " " << residual[1] << " " << residual[2]);
  CHECK(link_energy > 0.0);  // a damper dissipates
  for (int i = 0; i < 2; ++i) {
    CHECK(std::log2(ex[i] / ex[i + 1]) > 1.8);
    CHECK(std::log2(ev[i] / ev[i + 1]) > 1.7);
    CHECK(std::log2(residual[i] / residual[i + 1]) > 1.7);
  }
}

}  // namespace

TEST_CASE("two frames with nonlinear viscous dampers converge at order 2, their energy balance too", "[viscous]") {
  check_order_two(false);
}

TEST_CASE("nonlinear viscous dampers beside a friction damper: the two solved in turn, order 2", "[viscous]") {
  check_order_two(true);
}

namespace {

// The two frames of SPEC §5 joined at floor 3 by a dashpot link F = c |v|^alpha sign v and by a
// spring link at floor 2, under the first 8 s of Newhall, every step in the time series.
std::string dashpot_link_scene(double alpha) {
  return "name = \"dashpot-link\"\n[model]\nunits = \"SI\"\n"
         "[building.A]\nstoreys = 5\nmass = 45.0e3\nstiffness = 5.482e6\ndamping = { model = \"modal\", ratio = 0.05 }\n"
         "[building.B]\nstoreys = 3\nmasses = [60.0e3, 60.0e3, 50.0e3]\nperiod = 0.5\n"
         "[[link]]\nfloors = [3, 3]\ntype = \"dashpot\"\nc = 4.0e5\nalpha = " + std::to_string(alpha) + "\n"
         "[[link]]\nfloors = [2, 2]\ntype = \"spring\"\nstiffness = 1.0e5\n"
         "[ground]\nsource = \"record\"\nfile = \"" + std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN1044_DirRot2.AT2\"\n"
         "[solver]\nh = 0.002\nt_end = 8.0\n[output]\ntimeseries = true\nevery = 1\n";
}

// Runs the scene with the CLI; its summary.json and the columns of its timeseries.csv.
struct CliRun {
  nlohmann::json summary;
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    REQUIRE(it != names.end());
    return static_cast<std::size_t>(it - names.begin());
  }
};

CliRun run_with_cli(const std::string& name, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path scene = test::write_temp(name + ".toml", text);
  const fs::path out = fs::path(ADJOIN_TEST_TMP) / (name + "_out");
  fs::remove_all(out);
  const auto r = test::run_cli("run '" + scene.string() + "' --out '" + out.string() + "' --quiet");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CliRun run;
  run.summary = nlohmann::json::parse(test::slurp(out / "summary.json"));
  std::istringstream csv(test::slurp(out / "timeseries.csv"));
  std::string line, cell;
  while (std::getline(csv, line) && (line.empty() || line[0] == '#')) {}
  std::istringstream header(line);
  while (std::getline(header, cell, ',')) run.names.push_back(cell);
  while (std::getline(csv, line)) {
    std::istringstream values(line);
    std::vector<double> row;
    while (std::getline(values, cell, ',')) row.push_back(std::stod(cell));
    run.rows.push_back(row);
  }
  return run;
}

}  // namespace

TEST_CASE("every link reports the energy dissipated in it: a dashpot's is c times the integral of v^2", "[viscous][summary][cli]") {
  const CliRun linear = run_with_cli("dashpot_link_1", dashpot_link_scene(1.0));
  const auto& links = linear.summary["links"];
  REQUIRE(links.size() == 2);
  CHECK(links[0]["type"] == "dashpot");
  CHECK(links[0]["c"].get<double>() == 4.0e5);
  CHECK(links[0]["alpha"].get<double>() == 1.0);
  const double energy = links[0]["energy"];
  CHECK(energy > 0.0);
  CHECK(energy == Approx(linear.summary["energy"]["links"][0].get<double>()).epsilon(1e-12));  // its part of the balance
  // c times the integral of v^2, v from the time series' strokes by central differences.
  const std::size_t t = linear.column("t"), s = linear.column("link1.stroke");
  double integral = 0.0;
  for (std::size_t n = 1; n < linear.rows.size(); ++n) {
    const double dt = linear.rows[n][t] - linear.rows[n - 1][t], ds = linear.rows[n][s] - linear.rows[n - 1][s];
    integral += ds * ds / dt;
  }
  INFO("energy " << energy << " J, c int v^2 dt " << 4.0e5 * integral << " J");
  CHECK(4.0e5 * integral == Approx(energy).epsilon(2e-3));
  // A spring dissipates nothing: its work is what it holds.
  CHECK(links[1]["type"] == "spring");
  CHECK(links[1]["energy"].get<double>() == 0.0);
  CHECK(linear.summary["energy"]["links"][1].get<double>() != 0.0);

  const CliRun nonlinear = run_with_cli("dashpot_link_04", dashpot_link_scene(0.4));
  CHECK(nonlinear.summary["links"][0]["alpha"].get<double>() == Approx(0.4).epsilon(1e-15));
  CHECK(nonlinear.summary["links"][0]["energy"].get<double>() ==
        Approx(nonlinear.summary["energy"]["links"][0].get<double>()).epsilon(1e-12));
  CHECK(nonlinear.summary["links"][0]["energy"].get<double>() > 0.0);
}
