// What a run reports, as the scene's [output] asks: in-run response spectra (in the scene's
// units), the streamed energy history, and parts left out when not asked.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "adjoin/io/scene.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;

namespace {

const std::string kStrong = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml";

std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace

TEST_CASE("in-run spectra of a dimensionless scene and of its SI twin agree through the scales", "[outputs][spectra]") {
  const double m1 = 2.0e5, k1 = 8.0e6;
  const Scales si = Scales::SI(m1, k1);
  const Scene dimensionless = load_scene(kStrong, {"solver.scheme=implicit", "output.spectra.periods=[0.5, 2.0, 6.0]"});
  // The same physical system in SI: every input scaled by T0 and X0.
  const double T0 = si.time, X0 = si.length, g = kStandardGravity;
  const std::string text = "name = \"twin\"\n[model]\nunits = \"SI\"\nm1 = " + num(m1) + "\nm2 = " + num(2 * m1) +
                           "\nk1 = " + num(k1) + "\nk2 = " + num(2 * k1) + "\nslip_force = " + num(0.3 * m1 * g) +
                           "\ngap0 = " + num(2 * X0) + "\n[model.rod1]\norder = 0.23\ntau_x = " + num(1.183 * std::pow(T0, 0.23)) +
                           "\ntau_f = " + num(0.004 * std::pow(T0, 0.23)) + "\n[model.rod2]\norder = 0.53\ntau_x = " +
                           num(4.0 * std::pow(T0, 0.53)) + "\ntau_f = " + num(0.2 * std::pow(T0, 0.53)) +
                           "\n[ground]\nsource = \"decaying-sine\"\nu0 = " + num(1.5 * X0) + "\nomega = " + num(1.5 / T0) +
                           "\nk = " + num(0.5 / T0) + "\n[solver]\nscheme = \"implicit\"\nh = " + num(0.002 * T0) +
                           "\nt_end = " + num(16.0 * T0) + "\n[output.spectra]\nperiods = [" + num(0.5 * T0) + ", " +
                           num(2.0 * T0) + ", " + num(6.0 * T0) + "]\n";
  const Scene twin = parse_scene(text, "twin.toml");
  const Report a = run(dimensionless), b = run(twin);
  REQUIRE(a.spectra.size() == 3);
  REQUIRE(b.spectra.size() == 3);
  for (std::size_t s = 0; s < 3; ++s) {
    CHECK(a.spectra[s].signal == b.spectra[s].signal);
    for (std::size_t i = 0; i < 3; ++i) {
      const SpectralValues& x = a.spectra[s].spectrum.at(0, i);
      const SpectralValues& y = b.spectra[s].spectrum.at(0, i);
      INFO(a.spectra[s].signal << " T = " << x.period);
      CHECK(y.period == Approx(x.period * si.time).epsilon(1e-12));
      CHECK(y.sd == Approx(x.sd * si.length).epsilon(1e-9));
      CHECK(y.sv == Approx(x.sv * si.velocity).epsilon(1e-9));
      CHECK(y.sa == Approx(x.sa).epsilon(1e-9));  // in g both
      CHECK(y.psa == Approx(x.psa).epsilon(1e-9));
    }
  }
}

TEST_CASE("the rigid oscillator's SA is the block's peak absolute acceleration", "[outputs][spectra]") {
  const Report r = run(load_scene(kStrong, {"solver.scheme=implicit", "output.spectra.periods=[0.0]"}));
  REQUIRE(r.spectra.size() == 3);
  CHECK(r.spectra[0].spectrum.at(0, 0).sa == Approx(r.peak("ag").max_abs).epsilon(1e-12));
  CHECK(r.spectra[1].spectrum.at(0, 0).sa == Approx(r.peak("A.a1_abs").max_abs).epsilon(1e-12));
  CHECK(r.spectra[2].spectrum.at(0, 0).sa == Approx(r.peak("B.a1_abs").max_abs).epsilon(1e-12));
  // The damper and rods filter the ground: in-structure spectra differ from the ground's.
  CHECK(r.peak("A.a1_abs").max_abs != Approx(r.peak("ag").max_abs));
}

// A scene's reader refuses unknown signal names; a spec edited in code is checked by run() itself
// (a two-block run keeps the ground's and the two floors' accelerations only).
TEST_CASE("a two-block spec made in code with a signal it does not keep is refused by run()", "[outputs][spectra]") {
  Scene scene = load_scene(kStrong, {"solver.scheme=implicit", "output.spectra.periods=[0.0]", "output.timeseries=false"});
  REQUIRE(scene.output.spectra);
  scene.output.spectra->signals = {"ground", "A.x1"};
  CHECK_THROWS_WITH(run(scene), Catch::Contains("output.spectra.signals: \"A.x1\" is not a signal of a two-block run"));
  // The kept signals in any order: each spectrum is its own signal's (at T = 0, SA is the
  // signal's peak; B's floor and the ground differ, as the test above shows).
  scene.output.spectra->signals = {"B.a1_abs", "ground"};
  const Report r = run(scene);
  REQUIRE(r.spectra.size() == 2);
  CHECK(r.spectra[0].signal == "B.a1_abs");
  CHECK(r.spectra[0].spectrum.at(0, 0).sa == Approx(r.peak("B.a1_abs").max_abs).epsilon(1e-12));
  CHECK(r.spectra[1].spectrum.at(0, 0).sa == Approx(r.peak("ag").max_abs).epsilon(1e-12));
}

TEST_CASE("what is not asked is not computed: summary parts are null, nothing extra is kept", "[outputs]") {
  const Scene scene = load_scene(kStrong, {"output.phases=false", "output.pounding=false", "output.energy=false", "output.timeseries=false"});
  const Report r = run(scene);
  CHECK(r.phases.empty());
  CHECK(r.energy.buildings.empty());
  CHECK(r.spectra.empty());
  CHECK(r.peak("A.x1").max_abs > 1.0);  // peaks still asked
  const auto j = nlohmann::json::parse(summary_json(scene, r));
  CHECK(j["phases"].is_null());
  CHECK(j["pounding"].is_null());
  CHECK(j["energy"].is_null());
  CHECK(j["peaks"]["x1"]["max_abs"].get<double>() == r.peak("A.x1").max_abs);
}

TEST_CASE("energy.csv: the streamed balance closes row by row and ends at the summary's values", "[outputs][energy]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "energy-history";
  std::filesystem::remove_all(dir);
  const auto r = test::run_cli("run '" + kStrong + "' --set solver.scheme=implicit --set output.energy_history=true -q --out '" + dir.string() + "'");
  REQUIRE(r.status == 0);
  std::istringstream csv(test::slurp(dir / "energy.csv"));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "t,input,kinetic,rod1,rod2,friction,residual");
  std::vector<double> last;
  std::size_t rows = 0;
  double previous_friction = 0.0;
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::vector<double> v;
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
    REQUIRE(v.size() == 7);
    REQUIRE(v[6] == Approx(v[1] - (v[2] + v[3] + v[4] + v[5])).margin(1e-12));
    REQUIRE(v[5] >= previous_friction - 1e-15);  // friction only dissipates
    previous_friction = v[5];
    last = v;
    ++rows;
  }
  CHECK(rows == 8001);
  const auto j = nlohmann::json::parse(test::slurp(dir / "summary.json"));
  CHECK(last[1] == Approx(j["energy"]["input"].get<double>()).epsilon(1e-14));
  CHECK(last[5] == Approx(j["energy"]["friction"].get<double>()).epsilon(1e-14));
  CHECK(std::abs(last[6]) < 1e-5 * last[1]);
}

TEST_CASE("spectra.csv is written when [output.spectra] is present, bad spectra keys exit 2", "[outputs][spectra][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "run-spectra";
  std::filesystem::remove_all(dir);
  const auto r = test::run_cli("run '" + kStrong + "' --set output.spectra.damping=[0.02,0.05] -q --out '" + dir.string() + "'");
  REQUIRE(r.status == 0);
  const std::string csv = test::slurp(dir / "spectra.csv");
  CHECK(csv.rfind("signal,period,damping,sd,sv,sa,psv,psa\n", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 3 * 2 * 100);  // 3 signals x 2 dampings x 100 periods
  const auto bad = test::run_cli("run '" + kStrong + "' --set output.spectra.signals=[\"roof\"]");
  CHECK(bad.status == 2);
  CHECK(bad.err.find("output.spectra.signals") != std::string::npos);
  const auto bad_damping = test::run_cli("run '" + kStrong + "' --set output.spectra.damping=[1.5]");
  CHECK(bad_damping.status == 2);
}
