// Scene files: the SPEC keys, --set overrides, SI scaling, and every kind of bad input giving
// a clear error (file:line or --set, the key, what is expected) and exit status 2.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"
#include "state_recorder.hpp"

using namespace adjoin;

namespace {

const std::string kStrong = test::slurp(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml");

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// The InputError message for a scene text.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, "bad.toml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("expected an InputError");
  return {};
}

std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// Writes `text` to a file of this test process's scratch folder; its path.
std::string scratch_file(const std::string& name, const std::string& text) {
  const std::string path = std::string(ADJOIN_TEST_TMP) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

}  // namespace

TEST_CASE("the paper-strong scene reads back as the paper's parameters", "[scene]") {
  const Scene s = parse_scene(kStrong, "paper-strong.toml");
  CHECK(s.name == "paper-strong");
  CHECK(two_block_model(s).rho == 0.5);
  CHECK(two_block_model(s).eps == 2.0);
  CHECK(two_block_model(s).mu == 0.3);
  CHECK(two_block_model(s).gap0 == 2.0);
  CHECK(two_block_model(s).rod1.order == 0.23);
  CHECK(two_block_model(s).rod1.tau_x == 1.183);
  CHECK(two_block_model(s).rod1.tau_f == 0.004);
  CHECK(two_block_model(s).rod2.order == 0.53);
  CHECK(two_block_model(s).rod2.tau_x == 4.0);
  CHECK(two_block_model(s).rod2.tau_f == 0.2);
  CHECK(s.solver.h == 0.002);
  CHECK(s.solver.steps() == 8000);
  CHECK(s.solver.scheme == Scheme::paper);
  CHECK(s.output.timeseries);
  const auto* sine = dynamic_cast<const DecayingSine*>(s.ground.get());
  REQUIRE(sine);
  CHECK(sine->u0() == 1.5);
  CHECK(sine->omega() == 1.5);
  CHECK(sine->k() == 0.5);
}

TEST_CASE("overrides (--set) replace any key by dotted path, with TOML values", "[scene]") {
  const Scene s = parse_scene(kStrong, "x.toml",
                              {"solver.h=0.001", "model.rod2.tau_f=0.25", "name=renamed", "output.timeseries=false"});
  CHECK(s.solver.h == 0.001);
  CHECK(two_block_model(s).rod2.tau_f == 0.25);
  CHECK(s.name == "renamed");
  CHECK_FALSE(s.output.timeseries);
  // An override can add a key the file lacks.
  const Scene t = parse_scene(replace(kStrong, "[output]\ntimeseries = true\n", ""), "x.toml", {"output.every=10"});
  CHECK(t.output.every == 10);
}

TEST_CASE("an SI scene and its dimensionless twin give the same trajectory", "[scene][units]") {
  // m1 = 2e5 kg, k1 = 8e6 N/m: T0 = sqrt(m1/k1) = 0.158 s, X0 = m1 g / k1 = 0.245 m.
  const double m1 = 2.0e5, k1 = 8.0e6, g = kStandardGravity;
  const double T0 = std::sqrt(m1 / k1), X0 = m1 * g / k1;
  const std::string si = R"(
name = "si-twin"
[model]
units = "SI"
m1 = 2.0e5
m2 = 4.0e5
k1 = 8.0e6
k2 = 1.6e7
slip_force = )" + num(0.3 * m1 * g) + R"(
gap0 = )" + num(2.0 * X0) + R"(
[model.rod1]
order = 0.23
tau_x = )" + num(1.183 * std::pow(T0, 0.23)) + R"(
tau_f = )" + num(0.004 * std::pow(T0, 0.23)) + R"(
[model.rod2]
order = 0.53
tau_x = )" + num(4.0 * std::pow(T0, 0.53)) + R"(
tau_f = )" + num(0.2 * std::pow(T0, 0.53)) + R"(
[ground]
source = "decaying-sine"
u0 = )" + num(1.5 * X0) + R"(
omega = )" + num(1.5 / T0) + R"(
k = )" + num(0.5 / T0) + R"(
[solver]
scheme = "paper"
h = )" + num(0.002 * T0) + R"(
t_end = )" + num(16.0 * T0) + "\n";
  const Scene a = parse_scene(si, "si.toml");
  const Scene b = parse_scene(kStrong, "paper-strong.toml");
  CHECK(a.scales.si);
  CHECK(a.scales.time == Approx(T0));
  CHECK(a.scales.length == Approx(X0));
  CHECK(two_block_model(a).rho == Approx(two_block_model(b).rho));
  CHECK(two_block_model(a).mu == Approx(two_block_model(b).mu).epsilon(1e-14));
  CHECK(two_block_model(a).gap0 == Approx(two_block_model(b).gap0).epsilon(1e-14));
  CHECK(two_block_model(a).rod1.tau_x == Approx(two_block_model(b).rod1.tau_x).epsilon(1e-14));
  CHECK(two_block_model(a).rod2.tau_f == Approx(two_block_model(b).rod2.tau_f).epsilon(1e-14));
  CHECK(a.solver.steps() == b.solver.steps());
  test::StateRecorder ra, rb;
  run(a, {&ra});
  run(b, {&rb});
  REQUIRE(ra.states.size() == rb.states.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < ra.states.size(); ++i) {
    worst = std::max(worst, std::abs(ra.states[i].x[0] - rb.states[i].x[0]));
    worst = std::max(worst, std::abs(ra.states[i].x[1] - rb.states[i].x[1]));
  }
  // The twin's inputs went through SI and back: equal up to rounding, amplified a little by
  // the grid-based phase switching.
  CHECK(worst < 1e-9);
}

TEST_CASE("thermodynamic and physical restrictions are enforced with the key, value and rule", "[scene][errors]") {
  std::string e = error_of(replace(kStrong, "tau_x = 1.183", "tau_x = 0.001"));
  CHECK(e.find("model.rod1.tau_x = 0.001 must be greater than tau_f = 0.004 (second law)") != std::string::npos);
  CHECK(e.rfind("bad.toml:" + std::to_string(line_of(kStrong, "tau_x = 1.183")) + ":", 0) == 0);

  e = error_of(kStrong, {"model.rod2.tau_f=-1"});
  CHECK(e.find("model.rod2.tau_f = -1 must be positive (second law)") != std::string::npos);
  CHECK(e.rfind("--set model.rod2.tau_f=-1:", 0) == 0);

  CHECK(error_of(kStrong, {"model.rod1.order=1"}).find("model.rod1.order = 1 must lie strictly between 0 and 1") != std::string::npos);
  CHECK(error_of(kStrong, {"model.rod2.order=0"}).find("model.rod2.order = 0 must lie strictly between 0 and 1") != std::string::npos);
  CHECK(error_of(kStrong, {"model.rod1.tau_x=0.004"}).find("model.rod1.elastic = true") != std::string::npos);
  CHECK(error_of(kStrong, {"model.rho=0"}).find("model.rho = 0 must be positive") != std::string::npos);
  CHECK(error_of(kStrong, {"model.eps=-2"}).find("model.eps = -2 must be positive") != std::string::npos);
  CHECK(error_of(kStrong, {"model.mu=-0.1"}).find("model.mu = -0.1 must be zero or positive") != std::string::npos);
  CHECK(error_of(kStrong, {"solver.h=0"}).find("solver.h = 0 must be a positive number") != std::string::npos);
  CHECK(error_of(kStrong, {"solver.t_end=-1"}).find("solver.t_end = -1 must be a positive number") != std::string::npos);
  CHECK(error_of(kStrong, {"output.every=0"}).find("output.every = 0 must be 1 or more") != std::string::npos);
}

TEST_CASE("unknown keys name the nearest known one, types and sections are checked", "[scene][errors]") {
  std::string e = error_of(replace(kStrong, "tau_x = 4.0", "taux = 4.0"));
  CHECK(e.find("unknown key model.rod2.taux; did you mean model.rod2.tau_x?") != std::string::npos);
  CHECK(e.rfind("bad.toml:" + std::to_string(line_of(kStrong, "tau_x = 4.0")) + ":", 0) == 0);
  CHECK(error_of(kStrong, {"solver.step=0.1"}).find("did you mean solver.h") == std::string::npos);
  CHECK(error_of(kStrong, {"solver.hh=0.1"}).find("unknown key solver.hh; did you mean solver.h?") != std::string::npos);
  CHECK(error_of(replace(kStrong, "[solver]", "[solvr]")).find("unknown section [solvr]; did you mean solver?") != std::string::npos);
  CHECK(error_of(kStrong, {"model.rho=\"half\""}).find("model.rho must be a number") != std::string::npos);
  CHECK(error_of(kStrong, {"output.timeseries=1"}).find("output.timeseries must be true or false") != std::string::npos);
  CHECK(error_of(kStrong, {"output.every=1.5"}).find("output.every must be an integer") != std::string::npos);
  CHECK(error_of(replace(kStrong, "scheme = \"paper\"", "scheme = \"papr\"")).find("solver.scheme = \"papr\" is not a scheme") != std::string::npos);
  CHECK(error_of(kStrong, {"solver.history=fast"}).find("solver.history = \"fast\" must be \"direct\", \"fft\" or \"soe\"") != std::string::npos);
  CHECK(error_of(kStrong, {"ground.source=sine"}).find("did you mean \"decaying-sine\"?") != std::string::npos);
  CHECK(error_of(kStrong, {"model.m1=1000"}).find("model.m1 belongs to SI scenes") != std::string::npos);
  CHECK(error_of(kStrong, {"model.units=imperial"}).find("model.units = \"imperial\" must be \"dimensionless\" or \"SI\"") != std::string::npos);

  const std::string no_ground = kStrong.substr(0, kStrong.find("[ground]")) + kStrong.substr(kStrong.find("[solver]"));
  CHECK(error_of(no_ground).find("missing section [ground]") != std::string::npos);
  CHECK(error_of(replace(kStrong, "rho = 0.5", "")).find("missing key model.rho") != std::string::npos);
  CHECK(error_of("model = [1, 2\n").find("bad.toml:") == 0);
  CHECK(error_of("model = [1, 2\n").find("not valid TOML") != std::string::npos);
  CHECK(error_of(kStrong, {"no_equals_sign"}).find("expected KEY=VALUE") != std::string::npos);
}

TEST_CASE("the adjoin program exits 2 with error: for bad scenes and 3 for numerical failure", "[scene][cli]") {
  struct Case { std::string name, text, expect; };
  const std::vector<Case> cases = {
      {"second-law.toml", replace(kStrong, "tau_x = 1.183", "tau_x = 0.001"), "must be greater than tau_f"},
      {"unknown.toml", replace(kStrong, "mu = 0.3", "muu = 0.3"), "did you mean model.mu?"},
      {"type.toml", replace(kStrong, "eps = 2.0", "eps = \"two\""), "model.eps must be a number"},
      {"section.toml", replace(kStrong, "[model.rod1]", "[model.rodd1]"), "unknown section [model.rodd1]"},
  };
  for (const auto& c : cases) {
    const auto file = test::write_temp(c.name, c.text);
    const auto r = test::run_cli("run '" + file.string() + "' --out '" + file.string() + ".out'");
    INFO(c.name << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(r.err.find(c.expect) != std::string::npos);
    CHECK(r.err.find(c.name) != std::string::npos);  // names the file
    CHECK_FALSE(std::filesystem::exists(file.string() + ".out/summary.json"));
  }
  const auto missing = test::run_cli("run /nonexistent/scene.toml");
  CHECK(missing.status == 2);
  CHECK(missing.err.find("/nonexistent/scene.toml") != std::string::npos);
  const auto bad_set = test::run_cli(std::string("run ") + ADJOIN_SOURCE_DIR + "/records/scenes/paper-strong.toml --set solver.hh=1");
  CHECK(bad_set.status == 2);
  CHECK(bad_set.err.find("--set solver.hh=1") != std::string::npos);

  // Numerical failure: exit 3, a message with what to change, and no output written.
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "unstable";
  std::filesystem::remove_all(dir);
  const auto r = test::run_cli(std::string("run ") + ADJOIN_SOURCE_DIR +
                               "/records/scenes/paper-strong.toml --set model.rod1.order=0.9 --set model.rod1.tau_x=100 "
                               "--set model.rod1.tau_f=1e-4 --set solver.h=0.1 --out '" +
                               dir.string() + "'");
  CHECK(r.status == 3);
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK(r.err.find("set solver.h below") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "summary.json"));
  CHECK_FALSE(std::filesystem::exists(dir / "timeseries.csv"));
}

TEST_CASE("[model.contact] reads a contact law at the gap model.gap0, dimensionless as given", "[scene][contact]") {
  const std::string implicit = replace(kStrong, "scheme = \"paper\"", "scheme = \"implicit\"");
  Scene s = parse_scene(implicit, "x.toml");
  CHECK(two_block_model(s).contact.model == structure::ContactModel::none);  // absent: today's behaviour
  s = parse_scene(implicit + "\n[model.contact]\nmodel = \"linear\"\nstiffness = 500.0\nrestitution = 0.65\ntension_cut = true\n", "x.toml");
  CHECK(two_block_model(s).contact.model == structure::ContactModel::linear);
  CHECK(two_block_model(s).contact.stiffness == 500.0);  // in units of k1
  CHECK(two_block_model(s).contact.restitution == 0.65);
  CHECK(two_block_model(s).contact.tension_cut);
  CHECK(std::isnan(two_block_model(s).contact.damping));
  // --set builds the table and edits it; a model drops the keys it does not take, and
  // restitution and damping replace each other.
  s = parse_scene(implicit, "x.toml", {"model.contact.model=jankowski", "model.contact.stiffness=1000", "model.contact.damping=0.2"});
  CHECK(two_block_model(s).contact.model == structure::ContactModel::jankowski);
  CHECK(two_block_model(s).contact.stiffness == 1000.0);  // in units of k1 / X0^(1/2)
  CHECK(two_block_model(s).contact.damping == 0.2);
  const std::string file = scratch_file("contact-scene.toml",
                                              implicit + "\n[model.contact]\nmodel = \"linear\"\nstiffness = 500.0\ndamping = 0.1\n");
  s = load_scene(file, {"model.contact.restitution=0.8"});
  CHECK(two_block_model(s).contact.restitution == 0.8);
  CHECK(std::isnan(two_block_model(s).contact.damping));
  s = load_scene(file, {"model.contact.model=impact", "model.contact.restitution=0.5"});
  CHECK(two_block_model(s).contact.model == structure::ContactModel::impact);
  CHECK(two_block_model(s).contact.restitution == 0.5);
  s = load_scene(file, {"model.contact.model=hertz"});
  CHECK(two_block_model(s).contact.model == structure::ContactModel::hertz);
  CHECK(two_block_model(s).contact.stiffness == 500.0);
  CHECK(two_block_model(load_scene(file, {"model.contact.model=none"})).contact.model == structure::ContactModel::none);
}

TEST_CASE("[model.contact] of an SI scene: stiffness in N/m or N/m^1.5, scaled by k1 or F0 / X0^1.5", "[scene][contact][units]") {
  // m1 = 2e5 kg, k1 = 8e6 N/m: X0 = m1 g / k1 = 0.24516625 m, F0 = m1 g = 1961330 N.
  const std::string si = test::slurp(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/si-record.toml");
  const std::string record = std::string(ADJOIN_SOURCE_DIR) + "/records/synthetic/cp-ec8b-seed1.txt";
  const std::string scene = replace(replace(si, "../synthetic/cp-ec8b-seed1.txt", record), "[model.rod1]", "[model.contact]\nmodel = \"linear\"\nstiffness = 4.0e8\nrestitution = 0.65\n\n[model.rod1]");
  const std::string file = scratch_file("si-contact.toml", scene);
  Scene s = load_scene(file);
  CHECK(two_block_model(s).contact.model == structure::ContactModel::linear);
  CHECK(two_block_model(s).contact.stiffness == Approx(50.0).epsilon(1e-14));  // 4e8 / 8e6
  CHECK(two_block_model(s).contact.restitution == 0.65);
  s = load_scene(file, {"model.contact.model=hertz", "model.contact.stiffness=2.0e9"});
  // F0 / X0^1.5 = 1961330 / 0.24516625^1.5 = 16156959.8168 N/m^1.5.
  CHECK(two_block_model(s).contact.stiffness == Approx(123.78566405282965).epsilon(1e-12));
  s = load_scene(file, {"model.contact.model=jankowski", "model.contact.stiffness=2.0e9", "model.contact.damping=0.25"});
  CHECK(two_block_model(s).contact.stiffness == Approx(123.78566405282965).epsilon(1e-12));
  CHECK(two_block_model(s).contact.damping == 0.25);  // dimensionless in both unit systems
}

TEST_CASE("[model.contact] mistakes name the key and what is expected", "[scene][contact][errors]") {
  const std::string implicit = replace(kStrong, "scheme = \"paper\"", "scheme = \"implicit\"");
  const std::string table = implicit + "\n[model.contact]\n";
  const int line = line_of(table, "[model.contact]") + 1;  // the first key
  const auto at = [&](int offset) { return "bad.toml:" + std::to_string(line + offset) + ": "; };
  CHECK(error_of(table + "stiffness = 10.0\n").rfind(at(0) + "model.contact.stiffness: a key of a contact law, but the contact has no model: set model.contact.model", 0) == 0);
  CHECK(error_of(table + "model = \"soft\"\n").rfind(at(0) + "model.contact.model = \"soft\" must be one of", 0) == 0);
  CHECK(error_of(table + "model = \"linear\"\nrestitution = 0.5\n").find("model.contact: missing key stiffness: the linear model needs its contact stiffness k (a positive number, in units of k1)") != std::string::npos);
  CHECK(error_of(table + "model = \"hertz\"\n").find("in units of k1 / X0^(1/2)") != std::string::npos);
  CHECK(error_of(table + "model = \"hertzdamp\"\nstiffness = 10.0\n").find("model.contact: missing key restitution or damping") != std::string::npos);
  CHECK(error_of(table + "model = \"linear\"\nstiffness = 10.0\nrestitution = 0.5\ndamping = 0.1\n").rfind(at(3) + "model.contact.damping: give restitution or damping, not both", 0) == 0);
  CHECK(error_of(table + "model = \"impact\"\n").find("model.contact: missing key restitution: the impact model") != std::string::npos);
  CHECK(error_of(table + "model = \"impact\"\nrestitution = 0.5\nstiffness = 10.0\n").rfind(at(2) + "model.contact.stiffness: the impact model (Newton's law) has no stiffness", 0) == 0);
  CHECK(error_of(table + "model = \"impact\"\nrestitution = 0.5\ndamping = 0.1\n").rfind(at(2) + "model.contact.damping: the impact model", 0) == 0);
  CHECK(error_of(table + "model = \"hertz\"\nstiffness = 10.0\nrestitution = 0.5\n").rfind(at(2) + "model.contact.restitution: the hertz model is elastic", 0) == 0);
  CHECK(error_of(table + "model = \"jankowski\"\nstiffness = 10.0\nrestitution = 0.5\ntension_cut = true\n").rfind(at(3) + "model.contact.tension_cut: only the linear model", 0) == 0);
  CHECK(error_of(table + "model = \"linear\"\nstiffness = 10.0\nrestitution = 0.5\ntension_cut = \"yes\"\n").find("model.contact.tension_cut must be true or false") != std::string::npos);
  CHECK(error_of(table + "model = \"linear\"\nstiffness = 0.0\nrestitution = 0.5\n").rfind(at(1) + "model.contact.stiffness: expected a positive contact stiffness (in units of k1)", 0) == 0);
  CHECK(error_of(table + "model = \"linear\"\nstiffness = 10.0\nrestitution = 1.5\n").find("model.contact.restitution: expected a coefficient of restitution e with 0 < e <= 1") != std::string::npos);
  CHECK(error_of(table + "model = \"linear\"\nstiffness = 10.0\ndamping = 1.0\n").find("model.contact.damping: expected the damping ratio zeta, 0 <= zeta < 1") != std::string::npos);
  CHECK(error_of(table + "model = \"linear\"\nstiffnes = 10.0\n").find("unknown key model.contact.stiffnes; did you mean model.contact.stiffness?") != std::string::npos);
  // A bad value from --set is blamed on the --set.
  CHECK(error_of(implicit, {"model.contact.model=impact", "model.contact.restitution=0"}).rfind("--set model.contact.restitution=0: model.contact.restitution: expected", 0) == 0);
  CHECK(error_of(implicit, {"model.contact.model=linear"}).rfind("--set model.contact.model=linear: model.contact: missing key stiffness", 0) == 0);
  // The paper's explicit scheme has no contact forces.
  const std::string e = error_of(kStrong, {"model.contact.model=impact", "model.contact.restitution=0.5"});
  CHECK(e.rfind("bad.toml:" + std::to_string(line_of(kStrong, "scheme = \"paper\"")) + ": solver.scheme = \"paper\": the contact laws need the implicit scheme", 0) == 0);
  // With a law the blocks may not start inside each other.
  CHECK(error_of(implicit, {"model.contact.model=impact", "model.contact.restitution=0.5", "model.gap0=-0.1"}).find("model.gap0 = -0.1 is negative: with a contact law") != std::string::npos);
  CHECK(error_of(implicit, {"model.contact=3"}).find("model.contact must be a table ([model.contact])") != std::string::npos);
}
