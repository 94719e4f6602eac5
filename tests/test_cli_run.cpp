// `adjoin run` keeps the SPEC §3 contracts: summary.json keys and values, the timeseries.csv
// header and rows, and agreement with the library run it reports.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "adjoin/io/scene.hpp"
#include "adjoin/observe/time_series.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"

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
  TimeSeriesRecorder recorder;
  const RunReport report = run_scene(scene, &recorder);

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
  CHECK(j["peaks"]["x1"]["max_abs"] == report.peaks.x1.max_abs);
  CHECK(j["peaks"]["q"]["max_abs"].get<double>() == Approx(0.3));
  for (const char* key : {"t", "x1", "x2", "v1", "v2", "f1", "f2", "q"}) CHECK(j["final"].contains(key));
  CHECK(j["final"]["t"] == Approx(16.0));
  CHECK(j["pounding"]["min_gap"] == report.pounding->min_gap);
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
    const State& s = recorder.states().at(rows);
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string field; std::getline(fields, field, ',');) f.push_back(field);
    REQUIRE(f.size() == 11);
    const double expected[] = {s.t, s.x1, s.x2, s.v1, s.v2, s.f1, s.f2, s.q, s.ag, 2.0 + s.x2 - s.x1};
    for (std::size_t k = 0; k < 10; ++k) worst = std::max(worst, std::abs(std::stod(f[k]) - expected[k]));
    REQUIRE(f[10] == to_string(s.phase));
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
