// The typed builder (structure/builder.hpp, study/builder.hpp) and the channel recorder
// (observe/channel_recorder.hpp): a structure built in code is the one its scene file
// describes and runs to the same peaks; the engineering rules give hand-computed values; a
// bad value is named by its field path, with the words the scene reader uses.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/observe/channel_recorder.hpp"
#include "adjoin/structure/builder.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run.hpp"

using namespace adjoin;
using structure::StructureBuilder;

namespace {

const std::string kScene = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";
const std::string kRecord = std::string(ADJOIN_SOURCE_DIR) + "/records/real/peer/RSN1044_DirRot2.AT2";

// The structure of two-frames.toml, in code.
structure::Structure two_frames() {
  StructureBuilder s;
  s.building('A', 5).mass(45.0e3).stiffness(5.482e6).modal_damping(0.05).zener({1, 2}, {1.0e6, 0.5, 0.2, 0.01});
  s.building('B', 3).masses({60.0e3, 60.0e3, 50.0e3}).period(0.5).rayleigh_damping(0.05, 1, 2);
  s.friction_link_ratio(3, 3, 0.05, 'B');
  s.contact(3, 3, 0.05);
  return s.build();
}

void check_same_building(const structure::Building& a, const structure::Building& b) {
  CHECK(a.name == b.name);
  CHECK(a.masses == b.masses);
  CHECK(a.springs == b.springs);  // the same rules on the same values: bit for bit
  REQUIRE(a.devices.size() == b.devices.size());
  for (std::size_t i = 0; i < a.devices.size(); ++i) {
    CHECK(a.devices[i].type == b.devices[i].type);
    CHECK(a.devices[i].storeys == b.devices[i].storeys);
    CHECK(a.devices[i].zener.k == b.devices[i].zener.k);
    CHECK(a.devices[i].zener.order == b.devices[i].zener.order);
    CHECK(a.devices[i].zener.tau_x == b.devices[i].zener.tau_x);
    CHECK(a.devices[i].zener.tau_f == b.devices[i].zener.tau_f);
  }
  CHECK(a.damping.model == b.damping.model);
  CHECK(a.damping.ratio == b.damping.ratio);
  CHECK(a.damping.mode_i == b.damping.mode_i);
  CHECK(a.damping.mode_j == b.damping.mode_j);
}

// The FieldError `make` throws.
template <class F>
FieldError field_error(F make) {
  try {
    make();
  } catch (const FieldError& e) {
    return e;
  }
  FAIL("no FieldError thrown");
  return FieldError("", "");
}

}  // namespace

TEST_CASE("builder: the two-frame example built in code is its scene's structure, run, and peaks", "[builder]") {
  const BuildingScene scene = load_building_scene(kScene);
  BuildingRunOptions o;
  o.name = "two-frames";
  o.h = 0.002;
  o.t_end = 45.0;
  const RunSpec spec = building_run_spec(two_frames(), record_ground(kRecord), o);

  const structure::Structure& a = scene.structure;
  const structure::Structure& b = spec.structure;
  check_same_building(a.a, b.a);
  REQUIRE(a.b);
  REQUIRE(b.b);
  check_same_building(*a.b, *b.b);
  REQUIRE(a.links.size() == 1);
  REQUIRE(b.links.size() == 1);
  CHECK(a.links[0].type == b.links[0].type);
  CHECK(a.links[0].slip_force == b.links[0].slip_force);
  CHECK(a.links[0].floor_a == b.links[0].floor_a);
  CHECK(a.links[0].floor_b == b.links[0].floor_b);
  REQUIRE(a.contacts.size() == 1);
  REQUIRE(b.contacts.size() == 1);
  CHECK(a.contacts[0].gap == b.contacts[0].gap);
  CHECK(a.contacts[0].law.model == b.contacts[0].law.model);
  CHECK(a.contacts[0].floor_a == b.contacts[0].floor_a);
  CHECK(spec.solver.h == scene.solver.h);
  CHECK(spec.solver.t_end == scene.solver.t_end);
  CHECK(spec.solver.history == scene.solver.history);
  CHECK(spec.solver.restart == scene.solver.restart);
  CHECK(spec.accuracy.h_rule == scene.accuracy.h_rule);
  CHECK(spec.accuracy.t_end_rule == scene.accuracy.t_end_rule);
  CHECK(spec.ground->duration() == scene.ground->duration());
  CHECK(spec.ground->ag(12.345) == scene.ground->ag(12.345));

  const Report from_file = run(scene);
  const Report in_code = run(spec);
  REQUIRE(from_file.peaks.size() == in_code.peaks.size());
  REQUIRE(from_file.peaks.size() > 20);
  for (std::size_t i = 0; i < from_file.peaks.size(); ++i) {
    INFO(from_file.peaks[i].channel);
    CHECK(in_code.peaks[i].channel == from_file.peaks[i].channel);
    CHECK(in_code.peaks[i].peak.max_abs == Approx(from_file.peaks[i].peak.max_abs).epsilon(1e-12).margin(0.0));
    CHECK(in_code.peaks[i].peak.t == from_file.peaks[i].peak.t);
  }
  REQUIRE(in_code.links.size() == 1);
  CHECK(in_code.links[0].force_max == Approx(from_file.links[0].force_max).epsilon(1e-12));
  CHECK(in_code.links[0].switches == from_file.links[0].switches);
  CHECK(in_code.contacts[0].min_gap == Approx(from_file.contacts[0].min_gap).epsilon(1e-12));
}

TEST_CASE("builder: a period with storey devices, links of every type and a contact law are the scene's", "[builder]") {
  const std::string text = R"(name = "t"
[model]
units = "SI"
[building.A]
storeys = 6
mass = 80.0e3
period = 0.8
damping = { model = "modal", ratio = 0.02 }
[[building.A.device]]
storeys = [1, 2, 3]
type = "zener"
stiffness = 2.0e7
order = 0.5
tau_x = 0.15
tau_f = 0.01
[[building.A.device]]
storeys = [4]
type = "dashpot"
c = 3.0e5
[building.B]
storeys = 2
masses = [50.0e3, 40.0e3]
stiffnesses = [4.0e7, 3.0e7]
[[link]]
floors = [2, 2]
type = "friction"
slip_force = 2.5e4
[[link]]
floors = [1, 1]
type = "dashpot"
c = 1.0e5
[[link]]
floors = [2, 1]
type = "spring"
stiffness = 1.0e6
[[link]]
floors = [3, 2]
type = "zener"
stiffness = 1.0e6
order = 0.4
tau_x = 0.3
tau_f = 0.02
[[contact]]
floors = [2, 2]
gap = 0.03
model = "hertzdamp"
stiffness = 2.0e9
restitution = 0.65
)";
  const structure::Structure file = parse_structure(text, "t.toml");
  StructureBuilder s;
  s.building('A', 6).mass(80.0e3).period(0.8).modal_damping(0.02).zener({1, 2, 3}, {2.0e7, 0.5, 0.15, 0.01}).dashpot({4}, 3.0e5);
  s.building('B', 2).masses({50.0e3, 40.0e3}).stiffnesses({4.0e7, 3.0e7});
  s.friction_link(2, 2, 2.5e4).dashpot_link(1, 1, 1.0e5).spring_link(2, 1, 1.0e6).zener_link(3, 2, {1.0e6, 0.4, 0.3, 0.02});
  s.contact(2, 2, 0.03).model(structure::ContactModel::hertzdamp).stiffness(2.0e9).restitution(0.65);
  const structure::Structure code = s.build();
  check_same_building(file.a, code.a);
  CHECK(code.a.devices[1].c == 3.0e5);
  REQUIRE(file.b);
  check_same_building(*file.b, *code.b);
  REQUIRE(code.links.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    INFO("link " << i + 1);
    CHECK(code.links[i].type == file.links[i].type);
    CHECK(code.links[i].floor_a == file.links[i].floor_a);
    CHECK(code.links[i].floor_b == file.links[i].floor_b);
    CHECK(code.links[i].slip_force == file.links[i].slip_force);
    CHECK(code.links[i].c == file.links[i].c);
    CHECK(code.links[i].k == file.links[i].k);
    CHECK(code.links[i].zener.k == file.links[i].zener.k);
    CHECK(code.links[i].zener.order == file.links[i].zener.order);
    CHECK(code.links[i].zener.tau_x == file.links[i].zener.tau_x);
    CHECK(code.links[i].zener.tau_f == file.links[i].zener.tau_f);
  }
  const structure::ContactLaw& a = file.contacts[0].law;
  const structure::ContactLaw& b = code.contacts[0].law;
  CHECK(b.model == a.model);
  CHECK(b.stiffness == a.stiffness);
  CHECK(b.restitution == a.restitution);
  CHECK(std::isnan(b.damping) == std::isnan(a.damping));
  CHECK(b.damping_parameter() == a.damping_parameter());
  CHECK(b.tension_cut == a.tension_cut);
  CHECK(code.contacts[0].gap == file.contacts[0].gap);
  // The period holds with the devices' relaxed stiffness: the spring found is below the
  // devices-free one.
  CHECK(structure::building_modes(code.a).periods[0] == Approx(0.8).epsilon(1e-10));
  CHECK(code.a.springs[0] < structure::BuildingBuilder('A', 6).mass(80.0e3).period(0.8).build().springs[0]);
}

TEST_CASE("builder: the step and horizon rules give what a scene without solver.h and t_end gets", "[builder]") {
  const BuildingScene scene = load_building_scene(kScene, {}, {"solver.h", "solver.t_end"});
  BuildingRunOptions o;
  o.name = "two-frames";
  const RunSpec spec = building_run_spec(two_frames(), record_ground(kRecord), o);
  CHECK(spec.solver.h == scene.solver.h);
  CHECK(spec.solver.t_end == scene.solver.t_end);
  CHECK(spec.accuracy.h_rule == scene.accuracy.h_rule);
  CHECK(spec.accuracy.t_end_rule == scene.accuracy.t_end_rule);
  REQUIRE(spec.accuracy.tolerance);
  CHECK(*spec.accuracy.tolerance == kBuildingDefaultTolerance);
  CHECK(*spec.accuracy.tolerance == *scene.accuracy.tolerance);
  CHECK(spec.accuracy.h_rule.find("the default: 3 significant digits") != std::string::npos);
  // The step is no coarser than the record's samples, and the horizon outlasts the record.
  CHECK(spec.solver.h <= spec.ground->sample_interval());
  CHECK(spec.solver.t_end > spec.ground->duration());
}

TEST_CASE("builder: the grounds are a scene's grounds", "[builder][ground]") {
  const std::string structure = "name = \"g\"\n[model]\nunits = \"SI\"\n[building.A]\nstoreys = 1\nmass = 1e4\nstiffness = 1e6\n";
  const BuildingScene sine = parse_building_scene(
      structure + "[ground]\nsource = \"decaying-sine\"\nu0 = 0.05\nomega = 8.0\nk = 0.3\n[solver]\nh = 0.01\nt_end = 2.0\n", "g.toml");
  const auto code = decaying_sine_ground(0.05, 8.0, 0.3);
  CHECK(code->describe() == sine.ground->describe());
  for (double t : {0.0, 0.1, 0.37, 1.9}) CHECK(code->ag(t) == sine.ground->ag(t));

  const BuildingScene scaled = parse_building_scene(
      structure + "[ground]\nsource = \"record\"\nfile = \"" + kRecord + "\"\nscale_pga = 0.3\n[solver]\nh = 0.01\nt_end = 2.0\n", "g.toml");
  const auto record = record_ground(kRecord, 0.3);
  CHECK(record->describe() == scaled.ground->describe());
  CHECK(record->duration() == scaled.ground->duration());
  CHECK(record->sample_interval() == scaled.ground->sample_interval());
  double pga = 0.0;
  for (int i = 0; i * record->sample_interval() < record->duration(); ++i) {
    const double t = i * record->sample_interval();
    CHECK(record->ag(t) == scaled.ground->ag(t));
    pga = std::max(pga, std::abs(record->ag(t)));
  }
  CHECK(pga == Approx(0.3).epsilon(1e-9));  // a_g in g, scaled to 0.3 g
}

TEST_CASE("builder: period to stiffness for shear buildings, by hand", "[builder][rules]") {
  const double m = 40.0e3, T = 0.6, omega = 2.0 * std::numbers::pi / T;
  // One storey: omega^2 = k / m.
  const structure::Building one = structure::BuildingBuilder('A', 1).mass(m).period(T).build();
  CHECK(one.springs[0] == Approx(m * omega * omega).epsilon(1e-12));
  // Two equal storeys and floors: K = k [2 -1; -1 1], M = m I, omega_1^2 = (3 - sqrt 5) / 2 k / m.
  const structure::Building two = structure::BuildingBuilder('A', 2).mass(m).period(T).build();
  const double k2 = m * omega * omega * 2.0 / (3.0 - std::sqrt(5.0));
  CHECK(two.springs[0] == Approx(k2).epsilon(1e-12));
  CHECK(two.springs[1] == two.springs[0]);
  // With a spring device of 1e6 N/m the storey spring found makes up the rest: k + 1e6 = m omega^2.
  const structure::Building with_device = structure::BuildingBuilder('A', 1).mass(m).period(T).spring({1}, 1.0e6).build();
  CHECK(with_device.springs[0] == Approx(m * omega * omega - 1.0e6).epsilon(1e-10));
}

TEST_CASE("builder: a slip ratio is a fraction of the named building's weight", "[builder][rules]") {
  StructureBuilder s;
  s.building('A', 1).mass(10.0e3).stiffness(1.0e6);
  s.building('B', 3).masses({60.0e3, 60.0e3, 50.0e3}).stiffness(2.0e6);
  s.friction_link_ratio(1, 3, 0.05, 'B').friction_link_ratio(1, 1, 0.1, 'A').friction_link(1, 2, 1234.5);
  const structure::Structure built = s.build();
  // 0.05 x 170 t x g = 8500 kg x 9.80665 m/s^2.
  CHECK(built.links[0].slip_force == Approx(83356.525).epsilon(1e-12));
  CHECK(built.links[1].slip_force == Approx(0.1 * 10.0e3 * 9.80665).epsilon(1e-15));
  CHECK(built.links[2].slip_force == 1234.5);
  CHECK(built.links[2].floor_b == 2);
}

TEST_CASE("builder: a bad value is named by its field path", "[builder][errors]") {
  using structure::BuildingBuilder;
  CHECK(field_error([] { BuildingBuilder('A', 2).masses({1.0e3, -1.0}); }).field() == "building.A.masses[2]");
  CHECK(field_error([] { BuildingBuilder('A', 0); }).field() == "building.A.storeys");
  CHECK(field_error([] { BuildingBuilder('B', 3).stiffnesses({1e6, 1e6}); }).field() == "building.B.stiffnesses");
  CHECK(field_error([] { BuildingBuilder('A', 2).modal_damping(1.5); }).field() == "building.A.damping.ratio");
  CHECK(field_error([] { BuildingBuilder('A', 2).rayleigh_damping(0.05, 1, 3); }).field() == "building.A.damping.modes");
  CHECK(field_error([] { BuildingBuilder('A', 2).mass(1e3).zener({1}, {1e6, 0.5, 0.2, 0.01}).zener({2}, {1e6, 0.5, 0.01, 0.2}); })
            .field() == "building.A.device[2].tau_x");
  CHECK(field_error([] { BuildingBuilder('A', 2).mass(1e3).dashpot({1, 3}, 1e4); }).field() == "building.A.device[1].storeys");
  const FieldError twice = field_error([] { BuildingBuilder('A', 2).mass(1e3).spring({2}, 1e6).spring({1, 1}, 1e6); });
  CHECK(twice.field() == "building.A.device[2].storeys");
  CHECK(twice.problem() == "1 is listed twice; list each storey once");
  CHECK(field_error([] { BuildingBuilder('A', 2).mass(1e3).build(); }).field() == "building.A");  // no stiffness
  CHECK(field_error([] { BuildingBuilder('A', 2).mass(1e3).period(1e-9).build(); }).field() == "building.A.period");

  const auto pair = [] {
    StructureBuilder s;
    s.building('A', 5).mass(1e4).stiffness(1e7);
    s.building('B', 3).mass(1e4).stiffness(1e7);
    return s;
  };
  CHECK(field_error([&] { pair().friction_link(1, 1, 1e3).friction_link(2, 2, 0.0); }).field() == "link[2].slip_force");
  CHECK(field_error([&] { pair().friction_link_ratio(1, 1, 0.05, 'C'); }).field() == "link[1].of");
  CHECK(field_error([&] { pair().dashpot_link(6, 1, 1e3).build(); }).field() == "link[1].floors");
  CHECK(field_error([&] { pair().contact(1, 1, -0.01); }).field() == "contact[1].gap");
  CHECK(field_error([&] {
          auto s = pair();
          s.contact(1, 1, 0.01).model(structure::ContactModel::linear).stiffness(1e9).restitution(1.5);
          s.build();
        }).field() == "contact[1].restitution");
  CHECK(field_error([&] {
          auto s = pair();
          s.contact(1, 1, 0.01).model(structure::ContactModel::impact).stiffness(1e9).restitution(0.5);
          s.build();
        }).field() == "contact[1].stiffness");
  const FieldError e = field_error([] { BuildingBuilder('A', 1).masses({1.0e3}).period(0.5).spring({1}, 1e9).build(); });
  CHECK(e.field() == "building.A.period");
  CHECK(std::string(e.what()) == e.field() + ": " + e.problem());

  const auto no_ground = [] { building_run_spec(two_frames(), nullptr); };
  CHECK(field_error(no_ground).field() == "ground");
  BuildingRunOptions both;
  both.h = 0.01;
  both.tolerance = 1e-4;
  CHECK(field_error([&] { building_run_spec(two_frames(), decaying_sine_ground(0.01, 6.0, 0.1), both); }).field() == "solver.tolerance");
  BuildingRunOptions negative;
  negative.h = -0.01;
  CHECK(field_error([&] { building_run_spec(two_frames(), decaying_sine_ground(0.01, 6.0, 0.1), negative); }).field() == "solver.h");
  CHECK(field_error([] { record_ground(kRecord, -0.3); }).field() == "ground.scale_pga");
}

TEST_CASE("builder: the scene reader and the builder word a rule's problem alike", "[builder][errors]") {
  // Masses of 1e12 kg per floor and a 1 ms period ask for a storey spring beyond 1e15 N/m.
  const std::string text =
      "name = \"t\"\n[model]\nunits = \"SI\"\n[building.A]\nstoreys = 2\nmass = 1e12\nperiod = 0.001\n";
  std::string from_file;
  try {
    parse_structure(text, "t.toml");
  } catch (const InputError& e) {
    from_file = e.what();
  }
  const FieldError e = field_error([] { structure::BuildingBuilder('A', 2).mass(1e12).period(0.001).build(); });
  REQUIRE(!from_file.empty());
  CHECK(from_file == "t.toml:7: building.A.period: " + e.problem());
  CHECK(e.problem().find("is outside the supported") != std::string::npos);
}

TEST_CASE("builder: bilinear storeys by yield force or by yield drift ratio are the scene reader's", "[builder][hysteresis]") {
  // B's springs come from its period: the drift ratio's forces are taken from them.
  const std::string text =
      "name = \"t\"\n[model]\nunits = \"SI\"\n[building.A]\nstoreys = 3\nmasses = [6e4, 6e4, 5e4]\nperiod = 0.5\n"
      "heights = [4.0, 3.5, 3.0]\nhysteresis = { model = \"bilinear\", yield_drift_ratio = 0.01, hardening = 0.03 }\n";
  const structure::Structure from_file = parse_structure(text, "t.toml");
  StructureBuilder s;
  s.building('A', 3).masses({6e4, 6e4, 5e4}).period(0.5).heights({4.0, 3.5, 3.0}).bilinear_drift_ratio(0.01, 0.03);
  const structure::Building b = s.build().a;
  CHECK(b.hysteresis.model == structure::HysteresisModel::bilinear);
  CHECK(b.hysteresis.yield_forces == from_file.a.hysteresis.yield_forces);  // bit for bit
  CHECK(b.hysteresis.hardening == 0.03);
  CHECK(b.hysteresis.yield_forces[0] == Approx(b.springs[0] * 0.01 * 4.0).epsilon(1e-15));
  CHECK(b.hysteresis.yield_forces[2] == Approx(b.springs[2] * 0.01 * 3.0).epsilon(1e-15));

  using structure::BuildingBuilder;
  const structure::Building forces = BuildingBuilder('A', 2).mass(1e4).stiffness(1e7).bilinear_per_storey({2e5, 1e5}, 0.05).build();
  CHECK(forces.hysteresis.yield_forces == Eigen::Vector2d(2e5, 1e5));
  CHECK(BuildingBuilder('A', 2).mass(1e4).stiffness(1e7).bilinear(3e5).build().hysteresis.yield_forces == Eigen::Vector2d(3e5, 3e5));
  CHECK(field_error([] { BuildingBuilder('A', 2).mass(1e4).stiffness(1e7).bilinear_drift_ratio(0.01).build(); }).field() ==
        "building.A.hysteresis.yield_drift_ratio");  // no heights
  CHECK(field_error([] { BuildingBuilder('A', 2).bilinear_per_storey({1e5, 0.0}); }).field() == "building.A.hysteresis.yield_forces[2]");
  CHECK(field_error([] { BuildingBuilder('A', 2).bilinear(1e5, 1.0); }).field() == "building.A.hysteresis.hardening");
  CHECK(field_error([] { BuildingBuilder('A', 2).bilinear_drift_ratio(-0.01); }).field() == "building.A.hysteresis.yield_drift_ratio");
}

TEST_CASE("builder: Bouc-Wen storeys, yielding devices and an isolated base are the scene's, run, and peaks", "[builder][hysteresis][base]") {
  // A: Bouc-Wen storeys by drift ratio (with a shape that is not the default), a bilinear brace
  // and a Bouc-Wen damper; B: bilinear storeys by force, on a friction pendulum.
  const std::string text = R"(name = "t"
[model]
units = "SI"
[building.A]
storeys = 4
mass = 40.0e3
period = 0.6
height = 3.2
damping = { model = "modal", ratio = 0.03 }
hysteresis = { model = "bouc-wen", yield_drift_ratio = 0.004, hardening = 0.05, n = 1.5, beta = 0.6, gamma = 0.4 }
[[building.A.device]]
storeys = [1, 2]
type = "bilinear"
stiffness = 2.0e7
yield_force = 4.0e4
hardening = 0.02
[[building.A.device]]
storeys = [3]
type = "bouc-wen"
stiffness = 1.0e7
yield_force = 2.0e4
n = 3.0
[building.B]
storeys = 3
masses = [60.0e3, 60.0e3, 50.0e3]
stiffnesses = [9.0e7, 8.0e7, 7.0e7]
hysteresis = { model = "bilinear", yield_forces = [2.0e5, 1.8e5, 1.5e5], hardening = 0.03 }
[building.B.base]
mass = 60.0e3
model = "friction-pendulum"
friction = 0.06
radius = 2.5
[[link]]
floors = [3, 3]
type = "dashpot"
c = 2.0e5
alpha = 0.5
[ground]
source = "decaying-sine"
u0 = 0.08
omega = 6.0
k = 0.2
[solver]
h = 0.005
t_end = 8.0
)";
  const BuildingScene scene = parse_building_scene(text, "t.toml");
  StructureBuilder s;
  s.building('A', 4).mass(40.0e3).period(0.6).height(3.2).modal_damping(0.03)
      .bouc_wen_drift_ratio(0.004, 0.05, {1.5, 0.6, 0.4})
      .bilinear_device({1, 2}, 2.0e7, 4.0e4, 0.02)
      .bouc_wen_device({3}, 1.0e7, 2.0e4, 0.0, {3.0, 0.5, 0.5});
  s.building('B', 3).masses({60.0e3, 60.0e3, 50.0e3}).stiffnesses({9.0e7, 8.0e7, 7.0e7})
      .bilinear_per_storey({2.0e5, 1.8e5, 1.5e5}, 0.03).friction_pendulum(60.0e3, 0.06, 2.5);
  s.dashpot_link(3, 3, 2.0e5, 0.5);
  BuildingRunOptions o;
  o.name = "t";
  o.h = 0.005;
  o.t_end = 8.0;
  const RunSpec spec = building_run_spec(s.build(), decaying_sine_ground(0.08, 6.0, 0.2), o);

  const structure::Structure& file = scene.structure;
  const structure::Structure& code = spec.structure;
  check_same_building(file.a, code.a);
  REQUIRE(file.b);
  check_same_building(*file.b, *code.b);
  for (const auto& [f, c] : {std::pair{&file.a, &code.a}, std::pair{&*file.b, &*code.b}}) {
    INFO("building " << f->name);
    CHECK(c->hysteresis.model == f->hysteresis.model);
    CHECK(c->hysteresis.yield_forces == f->hysteresis.yield_forces);  // bit for bit
    CHECK(c->hysteresis.hardening == f->hysteresis.hardening);
    CHECK(c->hysteresis.n == f->hysteresis.n);
    CHECK(c->hysteresis.beta == f->hysteresis.beta);
    CHECK(c->hysteresis.gamma == f->hysteresis.gamma);
    CHECK(c->heights == f->heights);
    for (std::size_t i = 0; i < f->devices.size(); ++i) {
      CHECK(c->devices[i].k == f->devices[i].k);
      CHECK(c->devices[i].yield_force == f->devices[i].yield_force);
      CHECK(c->devices[i].hardening == f->devices[i].hardening);
      CHECK(c->devices[i].n == f->devices[i].n);
      CHECK(c->devices[i].beta == f->devices[i].beta);
      CHECK(c->devices[i].gamma == f->devices[i].gamma);
    }
    REQUIRE(c->base.has_value() == f->base.has_value());
  }
  CHECK(code.a.hysteresis.model == structure::HysteresisModel::bouc_wen);
  CHECK(code.a.hysteresis.n == 1.5);
  CHECK(code.a.devices[0].type == structure::DeviceType::bilinear);
  CHECK(code.a.devices[1].type == structure::DeviceType::bouc_wen);
  CHECK(code.a.devices[1].n == 3.0);
  REQUIRE(code.b->base);
  CHECK(code.b->base->model == structure::BaseModel::friction_pendulum);
  CHECK(code.b->base->mass == file.b->base->mass);
  CHECK(code.b->base->friction == file.b->base->friction);
  CHECK(code.b->base->radius == 2.5);
  CHECK(code.b->base_stiffness() == Approx((60.0e3 + 170.0e3) * kStandardGravity / 2.5).epsilon(1e-15));

  const Report from_file = run(scene);
  const Report in_code = run(spec);
  REQUIRE(from_file.peaks.size() == in_code.peaks.size());
  for (std::size_t i = 0; i < from_file.peaks.size(); ++i) {
    INFO(from_file.peaks[i].channel);
    CHECK(in_code.peaks[i].channel == from_file.peaks[i].channel);
    CHECK(in_code.peaks[i].peak.max_abs == Approx(from_file.peaks[i].peak.max_abs).epsilon(1e-12).margin(0.0));
    CHECK(in_code.peaks[i].peak.t == from_file.peaks[i].peak.t);
  }
  // The run did what the test is about: A's storeys yielded, B's base slid.
  REQUIRE(in_code.yield.size() == from_file.yield.size());
  REQUIRE(!in_code.yield.empty());
  CHECK(in_code.yield[0].storeys[0].yielded);
  CHECK(in_code.yield[0].storeys[0].plastic_work == Approx(from_file.yield[0].storeys[0].plastic_work).epsilon(1e-12));
  REQUIRE(in_code.bases.size() == 1);
  REQUIRE(from_file.bases.size() == 1);
  CHECK(in_code.bases[0].building == 'B');
  CHECK(in_code.bases[0].switches > 0);
  CHECK(in_code.bases[0].max_abs > 1e-3);
  CHECK(in_code.bases[0].max_abs == Approx(from_file.bases[0].max_abs).epsilon(1e-12));
  CHECK(in_code.bases[0].residual == Approx(from_file.bases[0].residual).epsilon(1e-12).margin(1e-15));
  CHECK(in_code.bases[0].switches == from_file.bases[0].switches);
  CHECK(in_code.bases[0].energy == Approx(from_file.bases[0].energy).epsilon(1e-12));
}

TEST_CASE("builder: a bad Bouc-Wen, yielding device or base value is named by its field path", "[builder][errors][base]") {
  using structure::BuildingBuilder;
  CHECK(field_error([] { BuildingBuilder('A', 2).bouc_wen(1e5, 0.0, {0.5, 0.5, 0.5}); }).field() == "building.A.hysteresis.n");
  CHECK(field_error([] { BuildingBuilder('A', 2).bouc_wen(1e5, 0.0, {2.0, 0.5, -0.5}); }).field() == "building.A.hysteresis.gamma");
  CHECK(field_error([] { BuildingBuilder('A', 2).bouc_wen(1e5, 0.0, {2.0, -0.5, 0.5}); }).field() == "building.A.hysteresis.beta");
  CHECK(field_error([] { BuildingBuilder('A', 2).bouc_wen_per_storey({1e5}); }).field() == "building.A.hysteresis.yield_forces");
  CHECK(field_error([] { BuildingBuilder('A', 2).bilinear_per_storey({}); }).field() == "building.A.hysteresis.yield_forces");
  CHECK(field_error([] { BuildingBuilder('A', 2).bouc_wen(1e5, -0.1); }).field() == "building.A.hysteresis.hardening");
  CHECK(field_error([] { BuildingBuilder('A', 2).mass(1e4).stiffness(1e7).bouc_wen_drift_ratio(0.01).build(); }).field() ==
        "building.A.hysteresis.yield_drift_ratio");  // no heights
  CHECK(field_error([] { BuildingBuilder('A', 2).bilinear_device({1}, 1e7, 0.0); }).field() == "building.A.device[1].yield_force");
  CHECK(field_error([] { BuildingBuilder('A', 2).spring({1}, 1e6).bilinear_device({2}, -1e7, 1e4); }).field() ==
        "building.A.device[2].stiffness");
  CHECK(field_error([] { BuildingBuilder('A', 2).bilinear_device({1}, 1e7, 1e4, 1.0); }).field() == "building.A.device[1].hardening");
  CHECK(field_error([] { BuildingBuilder('A', 2).bouc_wen_device({1}, 1e7, 1e4, 0.0, {25.0, 0.5, 0.5}); }).field() ==
        "building.A.device[1].n");
  CHECK(field_error([] { BuildingBuilder('A', 2).bouc_wen_device({3}, 1e7, 1e4); }).field() == "building.A.device[1].storeys");
  CHECK(field_error([] { BuildingBuilder('B', 2).flat_slider(0.0, 0.05); }).field() == "building.B.base.mass");
  CHECK(field_error([] { BuildingBuilder('B', 2).flat_slider(5e4, 1.0); }).field() == "building.B.base.friction");
  CHECK(field_error([] { BuildingBuilder('B', 2).friction_pendulum(5e4, 0.05, 0.0); }).field() == "building.B.base.radius");
  CHECK(field_error([] { BuildingBuilder('B', 2).friction_pendulum(5e4, -0.05, 2.0); }).field() == "building.B.base.friction");

  // The words are the scene reader's: one rule, two callers.
  const std::string scene = "name = \"t\"\n[model]\nunits = \"SI\"\n[building.A]\nstoreys = 2\nmass = 1e4\nstiffness = 1e7\n"
                            "[building.A.base]\nmass = 5e4\nmodel = \"flat-slider\"\nfriction = 1.5\n";
  std::string from_file;
  try {
    parse_structure(scene, "t.toml");
  } catch (const InputError& e) {
    from_file = e.what();
  }
  const FieldError e = field_error([] { BuildingBuilder('A', 2).flat_slider(5e4, 1.5); });
  CHECK(from_file == "t.toml:11: building.A.base.friction: " + e.problem());
  CHECK(e.problem().find("(0, 1)") != std::string::npos);
}

TEST_CASE("builder: a channel recorder keeps the times and the asked channels as arrays", "[builder][recorder]") {
  BuildingRunOptions o;
  o.h = 0.005;
  o.t_end = 4.0;
  o.error_estimate = false;
  const RunSpec spec = building_run_spec(two_frames(), decaying_sine_ground(0.05, 8.0, 0.3), o);
  ChannelRecorder recorder({"A.shear1", "link1.force", "A.x5"});
  ChannelRecorder every_tenth({"A.x5"}, 10);
  const Report report = run(spec, {&recorder});
  run(spec, {&every_tenth});
  const std::size_t rows = spec.solver.steps() + 1;
  REQUIRE(static_cast<std::size_t>(recorder.times().size()) == rows);
  CHECK(recorder.values().rows() == static_cast<Eigen::Index>(rows));
  CHECK(recorder.values().cols() == 3);
  CHECK(recorder.names() == std::vector<std::string>{"A.shear1", "link1.force", "A.x5"});
  CHECK(recorder.times()[0] == 0.0);
  CHECK(recorder.times()[static_cast<Eigen::Index>(rows) - 1] == Approx(4.0).epsilon(1e-12));
  CHECK(recorder.times()[10] == Approx(0.05).epsilon(1e-12));
  // Sampled peaks are the largest recorded samples.
  for (const char* name : {"A.shear1", "link1.force"}) {
    INFO(name);
    const auto peak = std::find_if(report.peaks.begin(), report.peaks.end(), [&](const ChannelPeak& p) { return p.channel == name; });
    REQUIRE(peak != report.peaks.end());
    CHECK(recorder.column(name).cwiseAbs().maxCoeff() == Approx(peak->peak.max_abs).epsilon(1e-12));
    CHECK(peak->peak.max_abs > 0.0);
  }
  // Every tenth grid point, the same values.
  REQUIRE(every_tenth.times().size() == static_cast<Eigen::Index>((rows - 1) / 10 + 1));
  for (Eigen::Index r = 0; r < every_tenth.times().size(); ++r) {
    CHECK(every_tenth.times()[r] == recorder.times()[10 * r]);
    CHECK(every_tenth.values()(r, 0) == recorder.values()(10 * r, 2));
  }
  // No names: every channel of the structure.
  ChannelRecorder all;
  run(spec, {&all});
  CHECK(all.names().size() == structure::channels(spec.structure).size());
  CHECK(field_error([&] {
          ChannelRecorder bad({"A.x5", "A.x9"});
          run(spec, {&bad});
        }).field() == "channels[2]");
}
