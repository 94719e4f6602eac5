// Scene files: the SPEC keys, --set overrides, SI scaling, and every kind of bad input giving
// a clear error (file:line or --set, the key, what is expected) and exit status 2.
#include <catch2/catch.hpp>
#include <cmath>

#include "adjoin/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/observe/time_series.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"

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

int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

}  // namespace

TEST_CASE("the paper-strong scene reads back as the paper's parameters", "[scene]") {
  const Scene s = parse_scene(kStrong, "paper-strong.toml");
  CHECK(s.name == "paper-strong");
  CHECK(s.model.rho == 0.5);
  CHECK(s.model.eps == 2.0);
  CHECK(s.model.mu == 0.3);
  CHECK(s.model.gap0 == 2.0);
  CHECK(s.model.rod1.order == 0.23);
  CHECK(s.model.rod1.tau_x == 1.183);
  CHECK(s.model.rod1.tau_f == 0.004);
  CHECK(s.model.rod2.order == 0.53);
  CHECK(s.model.rod2.tau_x == 4.0);
  CHECK(s.model.rod2.tau_f == 0.2);
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
  CHECK(s.model.rod2.tau_f == 0.25);
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
  CHECK(a.model.rho == Approx(b.model.rho));
  CHECK(a.model.mu == Approx(b.model.mu).epsilon(1e-14));
  CHECK(a.model.gap0 == Approx(b.model.gap0).epsilon(1e-14));
  CHECK(a.model.rod1.tau_x == Approx(b.model.rod1.tau_x).epsilon(1e-14));
  CHECK(a.model.rod2.tau_f == Approx(b.model.rod2.tau_f).epsilon(1e-14));
  CHECK(a.solver.steps() == b.solver.steps());
  TimeSeriesRecorder ra, rb;
  run_scene(a, &ra);
  run_scene(b, &rb);
  REQUIRE(ra.states().size() == rb.states().size());
  double worst = 0.0;
  for (std::size_t i = 0; i < ra.states().size(); ++i) {
    worst = std::max(worst, std::abs(ra.states()[i].x1 - rb.states()[i].x1));
    worst = std::max(worst, std::abs(ra.states()[i].x2 - rb.states()[i].x2));
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
  CHECK(error_of(kStrong, {"solver.history=fast"}).find("solver.history = \"fast\" must be \"direct\" or \"fft\"") != std::string::npos);
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
