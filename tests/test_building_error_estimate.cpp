// study/building_error_estimate: a building run's estimate of its own error is honest (within a
// factor 3 of the true error, measured against a run 64 times finer), a run to a tolerance meets
// it on the true error, switches the companion run does not find alike are not estimated, and
// the run's files carry the estimate.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/run_files.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/timeseries_csv.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/study/error_estimate.hpp"

using namespace adjoin;

namespace {

// Two linear frames (springs, 5 % modal damping) under a decaying sine, smooth in time (a
// record's piecewise-linear ground adds errors irregular in h): A 3 storeys, T1 = 0.8 s; B 2
// storeys, T1 = 0.5 s; joined at floor 2 by `link`. `solver` is the [solver] section's body.
BuildingScene frames(const std::string& link, const std::string& solver) {
  const std::string text =
      "name = \"linear-frames\"\n[model]\nunits = \"SI\"\n"
      "[building.A]\nstoreys = 3\nmass = 1.0e4\nperiod = 0.8\ndamping = { model = \"modal\", ratio = 0.05 }\n"
      "[building.B]\nstoreys = 2\nmass = 1.0e4\nperiod = 0.5\ndamping = { model = \"modal\", ratio = 0.05 }\n" +
      link + "[ground]\nsource = \"decaying-sine\"\nu0 = 0.02\nomega = 6.0\nk = 0.3\n[solver]\nt_end = 6.0\n" + solver;
  return parse_building_scene(text, "linear-frames.toml");
}
BuildingScene frames(const std::string& link, double h) { return frames(link, "h = " + std::to_string(h) + "\n"); }

// A linear link (the whole system linear), and a friction damper that sticks and slips about
// 17 times in the 6 s.
const std::string kSpring = "[[link]]\nfloors = [2, 2]\ntype = \"spring\"\nstiffness = 2.0e5\n";
const std::string kFriction = "[[link]]\nfloors = [2, 2]\ntype = \"friction\"\nslip_force = 800.0\n";

const double kReferenceDivisor = 64.0;  // the reference run's step is h / 64: its error 4096 x smaller

const Peak& peak_of(const Report& r, const std::string& channel) {
  const auto it = std::find_if(r.peaks.begin(), r.peaks.end(), [&](const ChannelPeak& p) { return p.channel == channel; });
  REQUIRE(it != r.peaks.end());
  return it->peak;
}

struct Compared {
  std::string what;
  double estimated, actual;
  double value = 0.0;  // the reported value (0 for instants and sampled maxima)
};

// Within a factor 3 both ways, or both below `floor`: the reference's own accuracy, or 1e-7 of
// the value, where errors of several phases cancel and no estimate from two runs resolves them.
bool within3(const Compared& c, double floor) {
  const double below = std::max(floor, 1e-7 * std::abs(c.value));
  if (c.actual < below && c.estimated < below) return true;
  return c.estimated <= 3.0 * c.actual && c.estimated >= c.actual / 3.0;
}

}  // namespace

TEST_CASE("linear frames: every estimated error is within a factor 3 of the true error", "[building_error_estimate]") {
  for (double h : {0.02, 0.01, 0.005, 0.0025}) {
    INFO("h = " << h);
    const BuildingScene scene = frames(kSpring, h);
    const Report r = run(scene);
    const Report ref = run(frames(kSpring, h / kReferenceDivisor));
    const ErrorEstimate e = estimate_error(scene, r);
    REQUIRE(e.available);
    CHECK(e.order == 2);
    CHECK(e.companion_h == Approx(2 * h).epsilon(1e-9));
    // The refined channels: x and drift of each floor, the link's stroke (not the sampled
    // accelerations, shears and link force).
    std::vector<std::string> names;
    for (const auto& pe : e.peaks) names.push_back(pe.channel);
    CHECK(names == std::vector<std::string>{"A.x1", "A.x2", "A.x3", "A.drift1", "A.drift2", "A.drift3", "B.x1", "B.x2",
                                            "B.drift1", "B.drift2", "link1.stroke"});
    std::vector<Compared> all;
    double worst = 0.0;
    for (const auto& pe : e.peaks) {
      const Peak& p = peak_of(r, pe.channel);
      const Peak& q = peak_of(ref, pe.channel);
      all.push_back({pe.channel, pe.error.max_abs, std::abs(p.max_abs - q.max_abs), q.max_abs});
      all.push_back({pe.channel + ".t", pe.error.t, std::abs(p.t - q.t)});
      worst = std::max(worst, pe.error.max_abs / p.max_abs);
    }
    CHECK(e.max_relative_peak == worst);
    // The link's maxima are the largest samples: their errors are O(h^2) but not a power of h
    // (where the peak falls between samples); here they too are within a factor 3 (the
    // farthest: force_max at h = 0.005, estimated 2.9 times the error).
    all.push_back({"link1.force_max", e.links[0].force_max, std::abs(r.links[0].force_max - ref.links[0].force_max)});
    all.push_back({"link1.stroke_max", e.links[0].stroke_max, std::abs(r.links[0].stroke_max - ref.links[0].stroke_max)});
    for (const auto& c : all) {
      INFO(c.what << ": estimated " << c.estimated << ", actual " << c.actual);
      CHECK(within3(c, 1e-12));
    }
  }
}

TEST_CASE("one friction damper: the roofs' peaks and the friction energy are estimated within a factor 3",
          "[building_error_estimate]") {
  for (double h : {0.02, 0.01, 0.005, 0.0025}) {
    INFO("h = " << h);
    const BuildingScene scene = frames(kFriction, h);
    const Report r = run(scene);
    const Report ref = run(frames(kFriction, h / kReferenceDivisor));
    REQUIRE(r.links[0].switches > 10);  // it sticks and slips
    const ErrorEstimate e = estimate_error(scene, r);
    REQUIRE(e.available);
    std::vector<Compared> all;
    for (const char* roof : {"A.x3", "B.x2"}) {
      const auto pe = std::find_if(e.peaks.begin(), e.peaks.end(), [&](const ChannelPeakError& p) { return p.channel == roof; });
      REQUIRE(pe != e.peaks.end());
      const Peak& p = peak_of(r, roof);
      const Peak& q = peak_of(ref, roof);
      all.push_back({std::string(roof), pe->error.max_abs, std::abs(p.max_abs - q.max_abs), q.max_abs});
      all.push_back({std::string(roof) + ".t", pe->error.t, std::abs(p.t - q.t)});
    }
    all.push_back({"friction energy", e.links[0].energy, std::abs(r.links[0].energy - ref.links[0].energy),
                   ref.links[0].energy});
    for (const auto& c : all) {
      INFO(c.what << ": estimated " << c.estimated << ", actual " << c.actual);
      CHECK(within3(c, 1e-12));
    }
  }
}

TEST_CASE("switches the companion run counts otherwise are reported as not estimated, with the counts",
          "[building_error_estimate]") {
  int mismatched = 0, matched = 0;
  for (double h : {0.02, 0.01, 0.005, 0.0025}) {
    INFO("h = " << h);
    const BuildingScene scene = frames(kFriction, h);
    const Report r = run(scene);
    // The companion's count, from a run of our own at 2h (6 s / h is even: exactly 2h) with the
    // run's own restart decision, as the estimate's companion takes it.
    BuildingScene twice = frames(kFriction, 2 * h);
    twice.solver.restart = takes_restarts(scene.solver, scene.structure, *scene.ground)
                               ? StructureSolverOptions::Restart::always
                               : StructureSolverOptions::Restart::never;
    const std::size_t companion = run(twice).links[0].switches;
    const ErrorEstimate e = estimate_error(scene, r);
    REQUIRE(e.available);
    const LinkError& le = e.links[0];
    CHECK(le.switches_matched == (companion == r.links[0].switches));
    if (le.switches_matched) {
      ++matched;
      CHECK(le.switches.size() == r.links[0].switches);
      CHECK(le.switches_note.empty());
    } else {
      ++mismatched;
      CHECK(le.switches.empty());
      CHECK(le.switches_note == "the companion run found " + std::to_string(companion) + " switches, this run " +
                                    std::to_string(r.links[0].switches) + "; instants not estimated");
      // The rest is still estimated.
      CHECK(le.energy > 0.0);
      CHECK(e.max_relative_peak > 0.0);
    }
  }
  CHECK(mismatched >= 1);  // both paths were taken
  CHECK(matched >= 1);
}

TEST_CASE("run_to_tolerance meets 1e-4 on the true error of every estimated peak", "[building_error_estimate]") {
  for (const std::string& link : {kSpring, kFriction}) {
    INFO((link == kSpring ? "spring link" : "friction link"));
    const BuildingScene scene = frames(link, 0.05);  // the first rung: h = 0.05 s
    const TolerantRun t = run_to_tolerance(scene, 1e-4);
    CHECK(t.met);
    CHECK(t.estimate.max_relative_peak <= 1e-4);
    CHECK(t.ladder.size() >= 2);
    CHECK(t.ladder.front() == 0.05);
    CHECK(t.ladder.back() == t.h);
    CHECK(t.report.solver.steps == static_cast<std::size_t>(std::ceil(6.0 / t.h * (1 - 1e-12))));
    const Report ref = run(frames(link, t.h / kReferenceDivisor));
    for (const auto& pe : t.estimate.peaks) {
      const Peak& p = peak_of(t.report, pe.channel);
      const Peak& q = peak_of(ref, pe.channel);
      INFO(pe.channel << ": " << p.max_abs << " against " << q.max_abs);
      CHECK(std::abs(p.max_abs - q.max_abs) <= 1e-4 * q.max_abs);
    }
  }
  CHECK_THROWS_AS(run_to_tolerance(frames(kSpring, 0.05), 0.0), InputError);
}

TEST_CASE("a building run's files carry its error estimate, and a tolerance chooses the step", "[building_error_estimate]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / "building-error-estimate";
  fs::remove_all(dir);
  auto summary = [](const fs::path& d) {
    std::ifstream in(d / "summary.json");
    return nlohmann::json::parse(in);
  };

  // A given step: the run as before, and its estimate, the same as estimate_error's.
  const BuildingScene given = frames(kFriction, "h = 0.005\n");
  RunFiles files = run_to_folder(given, dir / "given");
  REQUIRE(files.estimate);
  CHECK_FALSE(files.tolerant);
  nlohmann::json j = summary(dir / "given");
  CHECK(j["solver"]["h"].get<double>() == 0.005);
  CHECK_FALSE(j["solver"].contains("tolerance"));
  const auto& section = j["error_estimate"];
  CHECK(section["available"].get<bool>());
  CHECK(section["companion_h"].get<double>() == Approx(0.01));
  CHECK(section["max_relative_peak"].get<double>() == estimate_error(given, files.report).max_relative_peak);
  CHECK(section["peaks"].size() == files.estimate->peaks.size());
  CHECK(section["peaks"]["A.x3"]["max_abs"].get<double>() > 0.0);
  CHECK(section["links"][0].contains("energy"));
  CHECK(section["worst_channel"].get<std::string>() == files.estimate->worst_channel);
  const std::string brief = brief_report(given, files.report, &*files.estimate);
  CHECK(brief.find("error estimate (companion h = 0.01 s): peaks") != std::string::npos);
  CHECK(brief.find(files.estimate->worst_channel) != std::string::npos);

  // solver.error_estimate = false: no companion, no section.
  const BuildingScene quiet = frames(kFriction, "h = 0.005\nerror_estimate = false\n");
  files = run_to_folder(quiet, dir / "quiet");
  CHECK_FALSE(files.estimate);
  CHECK_FALSE(summary(dir / "quiet").contains("error_estimate"));

  // solver.tolerance instead of solver.h: the ladder from the shortest fundamental period / 200,
  // the chosen step reported; the time series is the kept rung's.
  BuildingScene tolerant = frames(kSpring, "tolerance = 1e-4\n");
  CHECK(tolerant.solver.h == Approx(0.5 / 200).epsilon(1e-6));
  CHECK(tolerant.accuracy.h_rule.find("chosen for solver.tolerance = 0.0001") == 0);
  tolerant.output.timeseries = true;
  tolerant.output.every = 1;  // (with a chosen step the default is a row every 1/200 s)
  files = run_to_folder(tolerant, dir / "tolerant");
  REQUIRE(files.tolerant);
  j = summary(dir / "tolerant");
  CHECK(j["solver"]["tolerance"].get<double>() == 1e-4);
  CHECK(j["solver"]["tolerance_met"].get<bool>());
  CHECK(j["solver"]["h"].get<double>() == files.tolerant->h);
  CHECK(j["solver"]["steps_tried"].size() == files.tolerant->ladder.size());
  CHECK(j["error_estimate"]["max_relative_peak"].get<double>() <= 1e-4);
  std::ifstream csv(dir / "tolerant" / "timeseries.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  CHECK(lines == files.report.solver.steps + 2);  // the header, then every grid point of the kept run

  // Neither solver.h nor solver.tolerance: the building scenes' default tolerance, 1e-3.
  const BuildingScene neither = frames(kSpring, "");
  REQUIRE(neither.accuracy.tolerance);
  CHECK(*neither.accuracy.tolerance == 1e-3);
  CHECK(neither.accuracy.h_rule.find("(the default") != std::string::npos);
}
