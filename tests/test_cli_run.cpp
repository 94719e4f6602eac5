// `adjoin run` keeps the SPEC §3 contracts: summary.json keys and values, the timeseries.csv
// header and rows, and agreement with the library run it reports.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"
#include "state_recorder.hpp"
#include "needs_program.hpp"

using namespace adjoin;

TEST_CASE("adjoin run writes summary.json and timeseries.csv per the SPEC", "[cli]") {
  const std::string scene_file = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml";
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "run-strong";
  std::filesystem::remove_all(dir);
  const auto r = test::run_cli("run '" + scene_file + "' --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("phases") != std::string::npos);
  CHECK(r.out.find("min gap") != std::string::npos);
  CHECK(r.out.find("energy") != std::string::npos);

  // The library's own run of the same scene, to compare against.
  const Scene scene = load_scene(scene_file);
  test::StateRecorder recorder;
  const Report report = run(scene, {&recorder});

  const auto j = nlohmann::json::parse(test::slurp(dir / "summary.json"));
  CHECK(j["scene"] == "paper-strong");
  CHECK(j["units"] == "dimensionless");
  CHECK(j["solver"]["scheme"] == "paper");
  CHECK(j["solver"]["history"] == "direct");
  CHECK(j["solver"]["h"] == 0.002);
  CHECK(j["solver"]["steps"] == 8000);
  CHECK(j["solver"]["wall_seconds"].get<double>() > 0.0);
  REQUIRE(j["phases"].size() == report.phases.size());
  for (std::size_t i = 0; i < report.phases.size(); ++i) {
    CHECK(j["phases"][i]["state"] == to_string(report.phases[i].state));
    CHECK(j["phases"][i]["t_start"] == report.phases[i].t_start);
    CHECK(j["phases"][i]["t_end"] == report.phases[i].t_end);
  }
  for (const char* key : {"x1", "x2", "f1", "f2", "q"}) {
    REQUIRE(j["peaks"].contains(key));
    CHECK(j["peaks"][key].contains("max_abs"));
    CHECK(j["peaks"][key].contains("t"));
  }
  CHECK(j["peaks"]["x1"]["max_abs"] == report.peak("A.x1").max_abs);
  CHECK(j["peaks"]["q"]["max_abs"].get<double>() == Approx(0.3));
  for (const char* key : {"t", "x1", "x2", "v1", "v2", "f1", "f2", "q"}) CHECK(j["final"].contains(key));
  CHECK(j["final"]["t"] == Approx(16.0));
  CHECK(j["pounding"]["min_gap"] == report.contacts.at(0).min_gap);
  CHECK(j["pounding"]["contact"] == false);
  CHECK(j["pounding"]["t_first_contact"].is_null());
  for (const char* key : {"input", "kinetic", "rod1", "rod2", "friction", "residual"})
    CHECK(j["energy"].contains(key));

  // timeseries.csv: the exact header, one row per grid point, values that read back.
  std::istringstream csv(test::slurp(dir / "timeseries.csv"));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase");
  std::size_t rows = 0;
  double worst = 0.0;
  while (std::getline(csv, line)) {
    const StructureState& s = recorder.states.at(rows);
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string field; std::getline(fields, field, ',');) f.push_back(field);
    REQUIRE(f.size() == 11);
    const double expected[] = {s.t, s.x[0], s.x[1], s.v[0], s.v[1], s.storey_force[0], s.storey_force[1], s.link_force[0], s.ag, 2.0 + s.x[1] - s.x[0]};
    for (std::size_t k = 0; k < 10; ++k) worst = std::max(worst, std::abs(std::stod(f[k]) - expected[k]));
    REQUIRE(f[10] == to_string(s.link_phase[0]));
    ++rows;
  }
  CHECK(rows == 8001);
  CHECK(worst == 0.0);  // shortest round-trip formatting loses nothing
  // No temporary files are left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    CHECK(entry.path().filename().string().find(".tmp") == std::string::npos);
}

TEST_CASE("output.every thins the time series and keeps the last point", "[cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "run-every";
  std::filesystem::remove_all(dir);
  const auto r = test::run_cli(std::string("run ") + ADJOIN_SOURCE_DIR +
                               "/records/scenes/paper-weak.toml --set output.every=3 -q --out '" + dir.string() + "'");
  REQUIRE(r.status == 0);
  CHECK(r.out.empty());  // --quiet
  std::istringstream csv(test::slurp(dir / "timeseries.csv"));
  std::string line, last;
  std::size_t rows = 0;
  std::getline(csv, line);
  while (std::getline(csv, line)) { ++rows; last = line; }
  CHECK(rows == 8000 / 3 + 2);  // m = 0, 3, ..., 7998, and 8000
  CHECK(std::stod(last.substr(0, last.find(','))) == Approx(16.0));
}

TEST_CASE("r3 watch: a long two-block run shows its estimate and progress on a terminal, never in a pipe", "[cli][progress]") {
  // ADJOIN_PROGRESS_AFTER=0: every run timed (0.25 s) shows its progress, so that a test can
  // be short. si-record's rods keep a direct history: 60,000 steps take about 1 s (more than
  // the 0.25 s timed first).
  test::needs_program("script");
  const std::string scene_file = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/si-record.toml";
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "r3-two-block-progress";
  std::filesystem::remove_all(dir);
  const std::string settings =
      " --set solver.h=5e-4 --set output.timeseries=false --set solver.error_estimate=false --out '" + dir.string() + "'";
  const std::string run = std::string("'") + ADJOIN_CLI + "' run '" + scene_file + "'" + settings;
  const auto terminal = dir.string() + ".tty";
  // script(1) runs the command on a pseudo-terminal and copies what it shows to its stdout.
  const std::string on_tty = "ADJOIN_PROGRESS_AFTER=0 script -qec \"" + run + "\" /dev/null > '" + terminal + "' 2>&1";
  REQUIRE(std::system(on_tty.c_str()) == 0);
  const std::string shown = test::slurp(terminal);
  INFO(shown);
  CHECK(shown.find("run 1: 60000 steps of h = 0.0005 s, about") != std::string::npos);
  CHECK(shown.find("/60000 steps") != std::string::npos);
  CHECK(shown.find("ETA") != std::string::npos);
  std::filesystem::remove(terminal);
  // The same run with stderr to a file (a pipe, a log): nothing of it.
  const auto piped = test::run_cli("run '" + scene_file + "'" + settings);
  CHECK(piped.status == 0);
  CHECK(piped.err.find("steps") == std::string::npos);
  CHECK(piped.err.find("ETA") == std::string::npos);
  // --quiet on a terminal: nothing either.
  const std::string quiet = "ADJOIN_PROGRESS_AFTER=0 script -qec \"" + run + " --quiet\" /dev/null > '" + terminal + "' 2>&1";
  REQUIRE(std::system(quiet.c_str()) == 0);
  CHECK(test::slurp(terminal).find("ETA") == std::string::npos);
  std::filesystem::remove(terminal);
  std::filesystem::remove_all(dir);
}
