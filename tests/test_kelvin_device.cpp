// The Kelvin storey device (a viscoelastic damper: a spring k in parallel with a linear dashpot
// c, src/structure/devices/kelvin.cpp), the element that shows a new device is one file and one
// row of ADJOIN_DEVICE_KINDS: the same trajectory as a frame with the spring k_storey + k and a
// dashpot device c; its free vibration against the damped oscillator's closed form; the work it
// dissipates in the energy balance; its keys in a scene, the builder and their messages.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "building_scene_error.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/builder.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run.hpp"
#include "state_recorder.hpp"

using namespace adjoin;
using namespace adjoin::structure;

namespace {

using Recorder = adjoin::test::StateRecorder;

StoreyDevice device(DeviceType type, std::vector<int> storeys, double k, double c) {
  StoreyDevice d;
  d.type = type;
  d.storeys = std::move(storeys);
  d.k = k;
  d.c = c;
  return d;
}

// A frame of `floors` floors of mass m with storey springs k_storey and 5 % modal damping.
Structure frame(int floors, double k_storey) {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::VectorXd::Constant(floors, 4.0e4);
  s.a.springs = Eigen::VectorXd::Constant(floors, k_storey);
  s.a.damping.model = DampingModel::modal;
  s.a.damping.ratio = 0.05;
  return s;
}

// One floor of mass m held only by a Kelvin device (k, c).
Structure kelvin_alone(double m, double k, double c) {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::VectorXd::Constant(1, m);
  s.a.springs = Eigen::VectorXd::Zero(1);
  s.a.devices = {device(DeviceType::kelvin, {1}, k, c)};
  return s;
}

constexpr const char* kScene = R"(name = "kelvin"
[model]
units = "SI"
[building.A]
storeys = 2
mass = 4.0e4
stiffness = 5.0e6
[[building.A.device]]
storeys = [1, 2]
type = "kelvin"
stiffness = 2.0e6
c = 1.5e5
[ground]
source = "decaying-sine"
u0 = 0.05
omega = 6.0
k = 0.3
[solver]
h = 0.005
t_end = 4.0
)";

std::string scene_error(const std::string& from, const std::string& to) {
  return test::building_scene_error(kScene, from, to, "kelvin.toml");
}

}  // namespace

TEST_CASE("a Kelvin device is a spring plus a linear dashpot: the same trajectory as the frame with both", "[kelvin]") {
  const double k_storey = 5.0e6, k_d = 2.0e6, c = 1.5e5;
  Structure kelvin = frame(3, k_storey), twin = frame(3, k_storey + k_d);
  kelvin.a.devices = {device(DeviceType::kelvin, {1, 2, 3}, k_d, c)};
  twin.a.devices = {device(DeviceType::dashpot, {1, 2, 3}, 0.0, c)};
  // Its spring counts in the static stiffness (the periods) and its dashpot in the device damping.
  CHECK(kelvin.a.static_stiffness() == twin.a.static_stiffness());
  CHECK(dashpot_matrix(kelvin.a) == dashpot_matrix(twin.a));
  CHECK_FALSE(kelvin.a.yields());
  const DecayingSine ground(0.05, 6.0, 0.3);
  StructureSolverOptions o;
  o.h = 0.005;
  o.t_end = 4.0;
  Recorder with_kelvin, with_twin;
  simulate_structure(o, kelvin, ground, with_kelvin);
  simulate_structure(o, twin, ground, with_twin);
  REQUIRE(with_kelvin.states.size() == with_twin.states.size());
  REQUIRE(with_kelvin.states.size() == 801);
  double peak = 0.0;
  for (std::size_t i = 0; i < with_kelvin.states.size(); ++i) {
    const StructureState &a = with_kelvin.states[i], &b = with_twin.states[i];
    INFO("t = " << a.t);
    CHECK(a.x == b.x);
    CHECK(a.v == b.v);
    CHECK(a.storey_force == b.storey_force);
    peak = std::max(peak, a.x.cwiseAbs().maxCoeff());
  }
  CHECK(peak > 1e-3);  // (the frame moved: a trajectory of zeros would compare equal too)
}

TEST_CASE("a mass on a Kelvin device vibrates freely as the damped oscillator, at order 2", "[kelvin]") {
  const double m = 1.0e4, k = 4.0e5, zeta = 0.05, v0 = 0.5;
  const double w = std::sqrt(k / m), c = 2.0 * zeta * std::sqrt(k * m), wd = w * std::sqrt(1.0 - zeta * zeta);
  auto x_exact = [&](double t) { return v0 / wd * std::exp(-zeta * w * t) * std::sin(wd * t); };
  const Structure s = kelvin_alone(m, k, c);
  const DecayingSine still(0.0, 1.0, 0.0);
  std::vector<double> errors;
  for (double h : {0.01, 0.005, 0.0025}) {
    StructureSolverOptions o;
    o.h = h;
    o.t_end = 5.0;
    o.v0 = Eigen::VectorXd::Constant(1, v0);
    Recorder r;
    simulate_structure(o, s, still, r);
    double e = 0.0;
    for (const auto& st : r.states) e = std::max(e, std::abs(st.x[0] - x_exact(st.t)));
    errors.push_back(e);
  }
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2] << " m of an amplitude " << v0 / wd);
  CHECK(errors[2] < 1e-3 * v0 / wd);
  CHECK(std::log2(errors[0] / errors[1]) == Approx(2.0).margin(0.1));
  CHECK(std::log2(errors[1] / errors[2]) == Approx(2.0).margin(0.1));
}

TEST_CASE("the work a Kelvin device dissipates in free vibration is the mass's kinetic energy", "[kelvin]") {
  const double m = 1.0e4, k = 4.0e5, c = 2.0 * 0.05 * std::sqrt(k * m), v0 = 0.5, e0 = 0.5 * m * v0 * v0;
  std::vector<double> errors;
  for (double h : {0.01, 0.005, 0.0025}) {
    BuildingRunOptions o;
    o.h = h;
    o.t_end = 60.0;  // (e^(-zeta w t) = 6e-9: the energy left is 4e-17 of it)
    o.error_estimate = false;
    RunSpec spec = building_run_spec(kelvin_alone(m, k, c), decaying_sine_ground(0.0, 1.0, 0.0), o);
    spec.solver.v0 = Eigen::VectorXd::Constant(1, v0);
    const Report r = run(spec);
    CHECK(r.energy.buildings.at(0).kinetic < 1e-12 * e0);
    errors.push_back(std::abs(r.energy.buildings.at(0).storeys.at(0) - e0));
  }
  // The storey's work (its spring's energy, 0 at rest, and its dashpot's dissipated work) is
  // the trapezoidal integral of the grid's power: at order 2.
  INFO("errors of the device's work " << errors[0] << " " << errors[1] << " " << errors[2] << " J of " << e0);
  CHECK(errors[2] < 1e-6 * e0);
  CHECK(std::log2(errors[0] / errors[1]) == Approx(2.0).margin(0.1));
  CHECK(std::log2(errors[1] / errors[2]) == Approx(2.0).margin(0.1));
}

TEST_CASE("a Kelvin device in a scene: its keys, its energy balance, its messages", "[kelvin]") {
  const RunSpec spec = parse_building_scene(kScene, std::filesystem::path(ADJOIN_TEST_TMP) / "kelvin.toml");
  REQUIRE(spec.structure.a.devices.size() == 1);
  const StoreyDevice& d = spec.structure.a.devices[0];
  CHECK(d.type == DeviceType::kelvin);
  CHECK(d.k == 2.0e6);
  CHECK(d.c == 1.5e5);
  CHECK(d.storeys == std::vector<int>{1, 2});
  // The builder makes the same device from the same keys.
  const Building b = BuildingBuilder('A', 2).mass(4.0e4).stiffness(5.0e6).device(DeviceType::kelvin, {1, 2}, {{"stiffness", 2.0e6}, {"c", 1.5e5}}).build();
  CHECK(b.devices.at(0).k == d.k);
  CHECK(b.devices.at(0).c == d.c);
  // Its work closes the energy balance: the residual at the scheme's order, far below the input.
  const Report r = run(spec);
  CHECK(r.energy.input > 1.0);
  CHECK(std::abs(r.energy.residual) < 1e-4 * r.energy.input);
  // Messages name the key and what was expected.
  CHECK_THAT(scene_error("c = 1.5e5\n", ""), Catch::Contains("device[1]") && Catch::Contains("missing key c"));
  CHECK_THAT(scene_error("c = 1.5e5", "c = -1"), Catch::Contains("kelvin.toml:12: building.A.device[1].c: expected a positive"));
  CHECK_THAT(scene_error("c = 1.5e5", "c = 1.5e5\nalpha = 0.5"), Catch::Contains("alpha") && Catch::Contains("unknown key; expected one of c, stiffness, storeys, type"));
  CHECK_THROWS_WITH(BuildingBuilder('A', 2).mass(4.0e4).device(DeviceType::kelvin, {1}, {{"stiffness", 2.0e6}}),
                    Catch::Contains("building.A.device[1].c") && Catch::Contains("missing"));
  CHECK_THROWS_WITH(BuildingBuilder('A', 2).mass(4.0e4).device(DeviceType::kelvin, {1}, {{"stiffness", 2.0e6}, {"c", 1.0}, {"alpha", 0.5}}),
                    Catch::Contains("building.A.device[1].alpha"));
}
