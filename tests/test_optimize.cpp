// `adjoin optimize` (SPEC §9; study/optimize.hpp, io/optimize_study.hpp, src/cli/optimize.cpp):
// the optimiser finds a cheap 1-D sweep's minimum with fewer runs, a placement enumeration
// equals the same scenes run by hand, a Pareto front is non-dominated and reaches both
// single-objective optima, and a rerun takes every design from the cache.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/optimize_study.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/study/optimize.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/sweep.hpp"
#include "adjoin/study/sweep_columns.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;
using adjoin::test::run_cli;
using adjoin::test::slurp;
using adjoin::test::write_temp;
namespace fs = std::filesystem;

namespace {

// A record of 3 s at dt = 0.01 s [m/s^2], two columns "t a".
fs::path record_file(const std::string& name, double frequency, double factor) {
  std::string text;
  char line[96];
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.01 * i;
    const double a = factor * (3.0 * std::sin(2.0 * M_PI * frequency * t) * std::exp(-0.8 * t) + 0.7 * std::sin(17.0 * t));
    std::snprintf(line, sizeof line, "%.17g %.17g\n", t, a);
    text += line;
  }
  return write_temp(name, text);
}

// Two small elastic frames (3 and 2 storeys) joined at floor 2 by a friction damper, on r1:
// a run takes milliseconds. Over slip forces 1 kN .. 150 kN the mean of A's peak storey drift
// under r1 and r2 has its smallest value near 41 kN.
struct Cheap {
  fs::path r1 = record_file("opt-r1.txt", 2.0, 1.0);
  fs::path r2 = record_file("opt-r2.txt", 1.3, 1.4);
  fs::path scene = write_temp("opt-scene.toml",
                              "name = \"cheap\"\n[model]\nunits = \"SI\"\n"
                              "[building.A]\nstoreys = 3\nmass = 1.0e4\nstiffness = 2.0e6\ndamping = { model = \"modal\", ratio = 0.02 }\n"
                              "[building.B]\nstoreys = 2\nmass = 1.0e4\nstiffness = 8.0e6\ndamping = { model = \"modal\", ratio = 0.02 }\n"
                              "[[link]]\nfloors = [2, 2]\ntype = \"friction\"\nslip_force = 1.0e4\n"
                              "[ground]\nsource = \"record\"\nfile = \"" + r1.string() + "\"\nunits = \"m/s2\"\n"
                              "[solver]\nh = 0.01\nt_end = 4.0\nerror_estimate = false\n");
  std::string head() const {
    return "[optimize]\nscene = \"" + scene.string() + "\"\nsuite = [\"" + r1.string() + "\", \"" + r2.string() + "\"]\nunits = \"m/s2\"\n";
  }
};

constexpr double kLow = 1.0e3, kHigh = 1.5e5;
constexpr std::size_t kGrid = 149;  // 1 kN apart

// The mean over r1, r2 of a column of a sweep over the slip force, by axis value.
std::map<double, double> grid_means(const Cheap& c, const std::string& column) {
  const fs::path file = write_temp("opt-grid.toml", "base = \"" + c.scene.string() + "\"\n[[axis]]\nkey = \"link.1.slip_force\"\nfrom = " +
                                                        std::to_string(kLow) + "\nto = " + std::to_string(kHigh) + "\nn = " +
                                                        std::to_string(kGrid) + "\n[[motion]]\nname = \"r1\"\n[[motion]]\nname = \"r2\"\n"
                                                        "set = {\"ground.file\" = \"" + c.r2.string() + "\"}\n");
  const SweepSpec spec = load_sweep(file);
  const SweepTable table = sweep_table(spec, run_sweep(spec));
  std::size_t col = 0;
  while (table.columns[col].name != column) ++col;
  std::map<double, double> mean;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const double x = kLow + (kHigh - kLow) * static_cast<double>(i / 2) / static_cast<double>(kGrid - 1);
    mean[x] += std::stod(table.rows[i][col]) / 2.0;
  }
  return mean;
}

OptimizeOutcome optimise(const std::string& name, const std::string& text, const fs::path& dir = {}) {
  const OptimizeStudy study = load_optimize_study(write_temp(name, text));
  OptimizeRequest request;
  request.jobs = 2;
  request.dir = dir;
  return run_optimize_study(study, request);
}

}  // namespace

TEST_CASE("optimize: statistics over a suite and the non-dominated filter", "[optimize]") {
  const std::vector<double> v{4.0, 1.0, 3.0, 2.0};
  CHECK(suite_statistic(v, Statistic::mean) == 2.5);
  CHECK(suite_statistic(v, Statistic::median) == 2.5);
  CHECK(suite_statistic(v, Statistic::max) == 4.0);
  CHECK(suite_statistic(v, Statistic::p84) == Approx(1.0 + 3.0 * 0.84));  // position 0.84 x 3 = 2.52 -> 3.52
  // (1,5) (2,3) (3,4: dominated by (2,3)) (4,1) (2,3 again: kept once).
  const auto front = non_dominated({{1, 5}, {2, 3}, {3, 4}, {4, 1}, {2, 3}});
  CHECK(front == std::vector<std::size_t>{0, 1, 3});
}

TEST_CASE("optimize: bobyqa finds the minimum of a 1-D slip force sweep in fewer runs", "[optimize]") {
  const Cheap c;
  const auto grid = grid_means(c, "A.drift_max");
  REQUIRE(grid.size() == kGrid);
  auto best = grid.begin();
  for (auto it = grid.begin(); it != grid.end(); ++it)
    if (it->second < best->second) best = it;
  const OptimizeOutcome out = optimise("opt-1d.toml", c.head() + "variables = [{key = \"link.1.slip_force\", min = 1.0e3, max = 1.5e5}]\n"
                                                                  "objective = {edp = \"A.drift_max\", statistic = \"mean\"}\n"
                                                                  "method = \"bobyqa\"\ntolerance = 1e-3\nmax_evaluations = 60\n");
  REQUIRE(out.result.best);
  const Evaluation& e = out.result.evaluations[*out.result.best];
  INFO("grid minimum " << best->second << " at " << best->first << "; optimiser " << e.values.objectives[0] << " at " << e.x[0]
                       << " in " << out.result.evaluations.size() << " designs");
  // The optimiser's design is at least as good as the grid's best (it may fall between grid
  // points), and within two grid steps of it.
  CHECK(e.values.objectives[0] <= best->second * (1.0 + 1e-3));
  CHECK(std::abs(e.x[0] - best->first) <= 2.0 * (kHigh - kLow) / (kGrid - 1));
  // Fewer runs than the grid: a fifth of them at most.
  CHECK(out.runs == 2 * out.result.evaluations.size());
  CHECK(out.result.evaluations.size() * 5 < kGrid);
}

TEST_CASE("optimize: a placement enumeration equals the scenes run by hand with --set", "[optimize]") {
  const Cheap c;
  const OptimizeOutcome out = optimise("opt-place.toml", c.head() + "placements = [{key = \"link.1.floors\", values = [[1, 1], [2, 2]]},\n"
                                                                     "  {key = \"link.1.slip_force\", values = [2.0e4, 5.0e4]}]\n"
                                                                     "objective = {edp = \"A.drift_max\", statistic = \"max\"}\n");
  REQUIRE(out.result.evaluations.size() == 4);
  // By hand: each placement and record through load_building_scene + run(), A.drift_max read
  // from the channel cells, the max over the records, the smallest over the placements.
  const std::vector<std::string> floors{"[1, 1]", "[2, 2]"}, forces{"20000.0", "50000.0"};
  double brute = HUGE_VAL;
  std::size_t brute_choice = 0;
  for (std::size_t f = 0; f < 2; ++f)
    for (std::size_t s = 0; s < 2; ++s) {
      double worst = 0.0;
      for (const fs::path& r : {c.r1, c.r2}) {
        const RunSpec scene = load_building_scene(c.scene, {"link.1.floors=" + floors[f], "link.1.slip_force=" + forces[s],
                                                            "ground.source=\"record\"", "ground.file=\"" + r.string() + "\"",
                                                            "ground.scale=1", "ground.units=\"m/s2\""});
        const Report report = run(scene);
        const auto columns = building_channel_columns(scene.structure);
        const auto cells = building_channel_cells(scene.structure, scene, report);
        for (std::size_t k = 0; k < columns.size(); ++k)
          if (columns[k].name == "A.drift_max") worst = std::max(worst, std::stod(cells[k]));
      }
      const std::size_t choice = 2 * f + s;
      const auto& e = out.result.evaluations[choice];
      REQUIRE(e.choice == choice);
      CHECK(e.values.objectives[0] == worst);  // bit for bit
      if (worst < brute) brute = worst, brute_choice = choice;
    }
  REQUIRE(out.result.best);
  CHECK(*out.result.best == brute_choice);
}

TEST_CASE("optimize: a two-objective Pareto front is non-dominated and reaches both single optima", "[optimize]") {
  const Cheap c;
  const std::string common = c.head() + "variables = [{key = \"link.1.slip_force\", min = 1.0e3, max = 1.5e5}]\n"
                                        "method = \"cobyla\"\ntolerance = 1e-3\nmax_evaluations = 40\n";
  const std::string drift = "{edp = \"A.drift_max\", statistic = \"mean\"}", force = "{edp = \"link1.force_max\", statistic = \"mean\"}";
  const OptimizeOutcome front = optimise("opt-front.toml", common + "objectives = [" + drift + ", " + force + "]\npareto_points = 5\n");
  const OptimizeOutcome f1 = optimise("opt-f1.toml", common + "objective = " + drift + "\n");
  const OptimizeOutcome f2 = optimise("opt-f2.toml", common + "objective = " + force + "\n");
  const auto& ev = front.result.evaluations;
  const auto& pareto = front.result.pareto;
  REQUIRE(pareto.size() >= 3);
  // No design evaluated dominates a point of the front.
  for (std::size_t i : pareto)
    for (const auto& e : ev) {
      const auto& a = e.values.objectives;
      const auto& b = ev[i].values.objectives;
      CHECK_FALSE((a[0] <= b[0] && a[1] <= b[1] && (a[0] < b[0] || a[1] < b[1])));
    }
  // Its ends: the single-objective optima, within the tolerance's effect on the objective.
  const double best1 = f1.result.evaluations[*f1.result.best].values.objectives[0];
  const double best2 = f2.result.evaluations[*f2.result.best].values.objectives[0];
  CHECK(ev[pareto.front()].values.objectives[0] <= best1 * (1.0 + 1e-3));
  CHECK(ev[pareto.back()].values.objectives[1] <= best2 * (1.0 + 1e-3));
  // And the front is a trade: f1 rises while f2 falls along it.
  CHECK(ev[pareto.back()].values.objectives[0] > ev[pareto.front()].values.objectives[0]);
  CHECK(ev[pareto.back()].values.objectives[1] < ev[pareto.front()].values.objectives[1]);
}

TEST_CASE("optimize: a rerun with the same --out takes every design from the cache", "[optimize]") {
  const Cheap c;
  const fs::path study = write_temp("opt-resume.toml", c.head() + "variables = [{key = \"link.1.slip_force\", min = 1.0e3, max = 1.5e5}]\n"
                                                                  "objective = {edp = \"A.drift_max\", statistic = \"p84\"}\n"
                                                                  "constraints = [{edp = \"link1.force_max\", statistic = \"max\", max = 6.0e4}]\n"
                                                                  "method = \"neldermead\"\nmax_evaluations = 25\n");
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / "opt-resume-out";
  fs::remove_all(dir);
  const auto first = run_cli("optimize " + study.string() + " --out " + dir.string() + " -q -j 2");
  REQUIRE(first.status == 0);
  const auto a = nlohmann::json::parse(slurp(dir / "optimum.json"));
  const std::string csv = slurp(dir / "evaluations.csv");
  const auto second = run_cli("optimize " + study.string() + " --out " + dir.string() + " -q -j 2");
  REQUIRE(second.status == 0);
  const auto b = nlohmann::json::parse(slurp(dir / "optimum.json"));
  CHECK(a["runs_now"].get<std::size_t>() == 2 * a["evaluations"].get<std::size_t>());
  CHECK(b["runs_now"] == 0);
  CHECK(b["from_cache"] == a["evaluations"]);
  CHECK(b["variables"] == a["variables"]);
  CHECK(b["objective"] == a["objective"]);
  CHECK(b["history"] == a["history"]);
  CHECK(slurp(dir / "evaluations.csv") == csv);
  CHECK(fs::exists(dir / "optimum.png"));
  // A changed study (another limit) does not reuse the cache.
  write_temp("opt-resume.toml", slurp(study).replace(slurp(study).find("6.0e4"), 5, "5.0e4"));
  REQUIRE(run_cli("optimize " + study.string() + " --out " + dir.string() + " -q -j 2").status == 0);
  const auto d = nlohmann::json::parse(slurp(dir / "optimum.json"));
  CHECK(d["from_cache"] == 0);
}

TEST_CASE("optimize: the example studies read and check", "[optimize]") {
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(ADJOIN_SOURCE_DIR) / "examples" / "studies")) {
    INFO(entry.path());
    const OptimizeStudy study = load_optimize_study(entry.path());
    CHECK(study.records.size() >= 9);  // records/real/peer and records/real/smc, or records/real/suite
    ++n;
  }
  CHECK(n == 6);
}

TEST_CASE("optimize: a fragility objective equals adjoin ida and adjoin fragility on the design's scene", "[optimize]") {
  // Six records (each its own frequencies and size) at six PGA stripes: the event's counts rise
  // with the IM without separating the runs, so the lognormal fit exists.
  std::vector<fs::path> records;
  std::string suite, files;
  for (int k = 0; k < 6; ++k) {
    std::string text;
    char line[96];
    for (int i = 0; i <= 300; ++i) {
      const double t = 0.01 * i;
      const double a = (0.8 + 0.15 * k) * (3.0 * std::sin(2.0 * M_PI * (1.0 + 0.35 * k) * t) * std::exp(-0.8 * t) +
                                           0.7 * std::sin((13.0 + k) * t));
      std::snprintf(line, sizeof line, "%.17g %.17g\n", t, a);
      text += line;
    }
    records.push_back(write_temp("opt-q" + std::to_string(k) + ".txt", text));
    suite += (k ? ", \"" : "\"") + records.back().string() + "\"";
    files += " " + records.back().string();
  }
  const Cheap c;
  const OptimizeOutcome out = optimise("opt-fragility.toml", "[optimize]\nscene = \"" + c.scene.string() + "\"\nsuite = [" + suite +
                                                                 "]\nunits = \"m/s2\"\nim = \"pga\"\nlevels = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]\n"
                                                                 "placements = [{key = \"link.1.slip_force\", values = [4.0e4]}]\n"
                                                                 "objective = {event = \"A.drift_max > 0.06\", probability_at = 0.3}\n");
  REQUIRE(out.result.evaluations.size() == 1);
  REQUIRE(out.runs == 36);
  // The same runs by hand: the scene with that slip force, `adjoin ida` stripes, `adjoin fragility --at`.
  std::string text = slurp(c.scene);
  text.replace(text.find("slip_force = 1.0e4"), 18, "slip_force = 4.0e4");
  const fs::path scene = write_temp("opt-scene-40k.toml", text);
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / "opt-fragility-ida";
  fs::remove_all(dir);
  REQUIRE(run_cli("ida " + scene.string() + " --suite" + files + " --units m/s2 --im pga --levels 0.1,0.2,0.3,0.4,0.5,0.6 "
                  "--edp A.drift_max -q --out " + dir.string()).status == 0);
  REQUIRE(run_cli("fragility " + (dir / "ida.csv").string() + " --event \"A.drift_max > 0.06\" --at 0.3 --bootstrap 0 --out " +
                  (dir / "f.json").string()).status == 0);
  const auto f = nlohmann::json::parse(slurp(dir / "f.json"));
  REQUIRE(f["fitted"] == true);
  const double p = f["at"]["probability"].get<double>();
  CHECK(p > 0.0);
  CHECK(p < 1.0);
  CHECK(out.result.evaluations[0].values.objectives[0] == p);  // bit for bit
}
