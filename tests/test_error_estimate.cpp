// study/error_estimate: each run's estimate of its own error is honest (within a factor 3 of
// the true error, measured against a much finer run, for every estimated quantity but the
// exceptions named with their reasons), and a run to a tolerance meets it.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "adjoin/io/run_files.hpp"
#include "adjoin/structure/two_block.hpp"
#include "adjoin/study/error_estimate.hpp"
#include "scene_helpers.hpp"

using namespace adjoin;
using adjoin::test::paper_scene;

namespace {

struct Compared {
  std::string what;
  double estimated, actual;
  double value = 0.0;  // the reported value (0 for instants)
};

// Every estimated quantity of `r` with its estimate and its true error against `ref`.
std::vector<Compared> compare(const Report& r, const ErrorEstimate& e, const Report& ref) {
  std::vector<Compared> out;
  auto peak = [&](const char* name, const Peak& p, const Peak& pr, const PeakError& pe) {
    out.push_back({std::string(name) + ".max_abs", pe.max_abs, std::abs(p.max_abs - pr.max_abs), pr.max_abs});
    out.push_back({std::string(name) + ".t", pe.t, std::abs(p.t - pr.t)});
  };
  // The estimate names the peaks by the 1 + 1 structure's channels (x1 = A.x1, ...).
  auto error_of = [&](const char* name) {
    for (const auto& p : e.peaks)
      if (p.channel == structure::two_block_channel(name)) return p.error;
    FAIL("no estimate of " << name);
    return PeakError{};
  };
  peak("x1", r.peak("A.x1"), ref.peak("A.x1"), error_of("x1"));
  peak("x2", r.peak("B.x1"), ref.peak("B.x1"), error_of("x2"));
  peak("drift", r.peak("link1.stroke"), ref.peak("link1.stroke"), error_of("drift"));
  peak("f1", r.peak("A.shear1"), ref.peak("A.shear1"), error_of("f1"));
  peak("f2", r.peak("B.shear1"), ref.peak("B.shear1"), error_of("f2"));
  peak("q", r.peak("link1.force"), ref.peak("link1.force"), error_of("q"));
  out.push_back({"min_gap", e.min_gap, std::abs(r.contacts.at(0).min_gap - ref.contacts.at(0).min_gap), ref.contacts.at(0).min_gap});
  out.push_back({"t_min_gap", e.t_min_gap, std::abs(r.contacts.at(0).t_min_gap - ref.contacts.at(0).t_min_gap)});
  out.push_back({"friction", e.friction, std::abs(r.link_energy(0) - ref.link_energy(0)), ref.link_energy(0)});
  REQUIRE(e.switches_matched);
  REQUIRE(r.phases.size() == ref.phases.size());
  for (std::size_t i = 1; i < r.phases.size(); ++i)
    out.push_back({"switch " + std::to_string(i), e.switches[i - 1], std::abs(r.phases[i].t_start - ref.phases[i].t_start)});
  return out;
}

// A quantity a test allows outside a factor 3, with the reason and the weaker bound it meets:
// the estimate is never below the true error divided by `max_under` (overestimates are safe).
struct Exception {
  std::string what;
  double max_under;
  std::string reason;
};

// Honest estimates: every estimated quantity within a factor 3 of its true error both ways,
// but the exceptions the test names with their reasons. Richardson from two runs assumes the
// error is C h^p; where it is not yet (an instant found by interpolation depends on where the
// event falls between grid points; an error that changes sign between h and 2h), two runs can
// be fooled, and the test must say where.
// Both below `floor` (the reference's own accuracy; q's exact limit mu) counts as agreement,
// and so, for a value, do both below 1e-7 of it (a tenth of the default tolerance): there a
// value's error is the sum of contributions from several phases that cancel (the record
// scene's minimum gap sits on a stick plateau whose stroke carries the errors of the slips
// before it, 1e-8 m each, which nearly cancel), and no estimate from two runs resolves a
// cancellation; nor does any tolerance the tool offers need it to.
void check_honest(const std::vector<Compared>& all, double floor, const std::vector<Exception>& exceptions = {}) {
  int checked = 0;
  for (const auto& c : all) {
    INFO(c.what << ": estimated " << c.estimated << ", actual " << c.actual);
    const double below = std::max(floor, 1e-7 * std::abs(c.value));
    if (c.actual < below && c.estimated < below) continue;
    ++checked;
    const auto exception =
        std::find_if(exceptions.begin(), exceptions.end(), [&](const Exception& e) { return e.what == c.what; });
    if (exception == exceptions.end()) {
      CHECK(c.estimated >= c.actual / 3.0);
      CHECK(c.estimated <= 3.0 * c.actual);
    } else {
      INFO("a named exception: " << exception->reason);
      CHECK(c.estimated >= c.actual / exception->max_under);
    }
  }
  CHECK(checked >= 15);
}

// The record scene's quantities outside a factor 3 at h = 0.0025 or 0.00125 (all of the strong
// scene's are within it, at every step tried).
const std::vector<Exception> kRecordExceptions = {
    {"x1.t", 10.0,
     "a peak instant, found by interpolation between steps: its error depends on where the peak falls between grid "
     "points, not C h^2 (h = 0.00125: estimated 1.2e-6, actual 6.7e-6)"},
    {"x2.t", 10.0, "the same instant as x1.t (their errors are equal)"},
    {"f1.t", 3.0, "a peak instant as x1.t, here overestimated, the safe side (h = 0.00125: 1.6e-5 for 3.0e-6)"},
    {"switch 4", 3.0,
     "a switching instant whose error is not yet C h^2 at the companion's step 0.005: overestimated, the safe side "
     "(h = 0.0025: 8.2e-4 for 7.6e-5)"},
    {"friction", 3.0,
     "its true error falls a hundredfold from h = 0.0025 to 0.00125 (4.9e-8, then 4.7e-10; C h^2 gives fourfold): "
     "it passes near zero, and the estimate at 0.00125 is 35 times the error, the safe side"},
};

}  // namespace

TEST_CASE("strong scene: the estimated errors are within a factor 3 of the true errors", "[error_estimate]") {
  const std::vector<std::string> implicit = {"solver.scheme=implicit", "solver.history=fft"};
  auto with = [&](double h) {
    auto o = implicit;
    o.push_back("solver.h=" + std::to_string(h));
    return paper_scene("strong", o);
  };
  const Report ref = run(with(3.125e-5));
  for (double h : {2e-3, 1e-3, 5e-4}) {
    INFO("h = " << h);
    const Scene scene = with(h);
    const Report r = run(scene);
    const ErrorEstimate e = estimate_error(scene, r);
    REQUIRE(e.available);
    CHECK(e.order == 2);
    CHECK(e.companion_h == Approx(2 * h).epsilon(1e-3));
    CHECK(e.companion_wall_seconds > 0.0);  // measured (how fast it is belongs to bench/, not here)
    check_honest(compare(r, e, ref), 2e-9);
  }
}

TEST_CASE("record scene: the estimated errors are within a factor 3 of the true errors but for named exceptions",
          "[error_estimate][record]") {
  const std::string file = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/si-record.toml";
  auto with = [&](double h) {
    return load_scene(file, {"solver.history=fft", "solver.scheme=implicit", "solver.t_end=20", "solver.h=" + std::to_string(h)});
  };
  // Steps that divide the record's sample interval (0.005 s), the companion's too: the ground
  // acceleration is piecewise linear, and a kink inside a step adds an error that is
  // irregular in h.
  const Report ref = run(with(0.005 / 128));
  for (double h : {0.0025, 0.00125}) {
    INFO("h = " << h);
    const Scene scene = with(h);
    const Report r = run(scene);
    const ErrorEstimate e = estimate_error(scene, r);
    REQUIRE(e.available);
    check_honest(compare(r, e, ref), 1e-9, kRecordExceptions);
  }
}

TEST_CASE("a run to a tolerance meets it, and says which steps it tried", "[error_estimate][tolerance]") {
  const std::vector<std::string> implicit = {"solver.scheme=implicit", "solver.history=fft"};
  auto o = implicit;
  o.push_back("solver.h=3.125e-5");
  const Report ref = run(paper_scene("strong", o));
  for (double tolerance : {1e-5, 1e-6}) {
    INFO("tolerance " << tolerance);
    const TolerantRun t = run_to_tolerance(paper_scene("strong", implicit), tolerance);
    CHECK(t.met);
    REQUIRE(!t.ladder.empty());
    CHECK(t.ladder.back() == t.h);
    CHECK(t.report.solver.h == t.h);
    CHECK(t.estimate.max_relative_peak <= tolerance);
    // The true relative errors of the peaks meet the tolerance too.
    for (auto [p, pr] : {std::pair{t.report.peak("A.x1"), ref.peak("A.x1")}, {t.report.peak("B.x1"), ref.peak("B.x1")},
                         {t.report.peak("A.shear1"), ref.peak("A.shear1")}, {t.report.peak("B.shear1"), ref.peak("B.shear1")},
                         {t.report.peak("link1.stroke"), ref.peak("link1.stroke")}, {t.report.peak("link1.force"), ref.peak("link1.force")}})
      CHECK(std::abs(p.max_abs - pr.max_abs) <= tolerance * pr.max_abs);
  }
}

TEST_CASE("a run to a tolerance streams only the kept rung into its files", "[error_estimate][tolerance]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "tolerance-files";
  std::filesystem::remove_all(dir);
  Scene scene = paper_scene("strong", {"solver.scheme=implicit", "solver.history=fft", "output.timeseries=true",
                                       "output.energy_history=true", "output.every=1"});
  scene.accuracy.tolerance = 1e-6;
  const RunFiles files = run_to_folder(scene, dir);
  REQUIRE(files.tolerant);
  CHECK(files.tolerant->ladder.size() >= 2);  // rungs were tried before the kept one
  for (const char* name : {"timeseries.csv", "energy.csv"}) {
    INFO(name);
    std::ifstream in(dir / name);
    std::string line, last;
    std::size_t rows = 0, headers = 0;
    while (std::getline(in, line)) {
      if (line.rfind("t,", 0) == 0) ++headers; else { ++rows; last = line; }
    }
    CHECK(headers == 1);
    CHECK(rows == files.report.solver.steps + 1);  // every grid point of the kept rung, once
    CHECK(std::stod(last.substr(0, last.find(','))) == Approx(16.0).margin(files.report.solver.h));  // the rung's last step
  }
}
