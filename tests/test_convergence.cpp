// The convergence study: which reference it picks, and the observed orders it reports.
#include <catch2/catch.hpp>
#include <cmath>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/convergence.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"
#include "png_check.hpp"
#include "scene_helpers.hpp"

using namespace adjoin;
using adjoin::test::paper_scene;

namespace {

double last_order(const ConvergenceResult& r, const std::string& scheme) {
  double order = std::nan("");
  for (const auto& row : r.rows)
    if (row.scheme == scheme) order = row.order;
  return order;
}


// `adjoin converge` on a recorded scene (records/scenes/SCENE) with `options`, into a fresh
// folder `name` of the tests' temporary folder.
test::CliResult converge(const std::string& scene, const std::string& options, const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  return test::run_cli(std::string("converge ") + ADJOIN_SOURCE_DIR + "/records/scenes/" + scene + " " + options +
                       " --out '" + dir.string() + "'");
}

}  // namespace

TEST_CASE("weak scene: analytic reference, orders 1 (paper, implicit-gl) and 2 (implicit)", "[convergence]") {
  ConvergenceOptions o;
  o.steps = {0.008, 0.004, 0.002};
  const auto r = run_convergence(paper_scene("weak"), o);
  CHECK(r.reference.rfind("analytic", 0) == 0);
  CHECK(r.reference.find("stuck") != std::string::npos);
  REQUIRE(r.rows.size() == 9);
  CHECK(last_order(r, "paper") == Approx(1.0).margin(0.05));
  CHECK(last_order(r, "implicit-gl") == Approx(1.0).margin(0.05));
  CHECK(last_order(r, "implicit") == Approx(2.0).margin(0.05));
  for (const auto& row : r.rows) {
    CHECK(row.wall_seconds > 0.0);
    CHECK(std::isnan(row.peak_a1));  // the exact solution gives trajectories only
  }
}

TEST_CASE("no damper: the analytic reference of two free fractional oscillators", "[convergence]") {
  ConvergenceOptions o;
  o.schemes = {Scheme::implicit};
  o.steps = {0.008, 0.004, 0.002};
  const auto r = run_convergence(paper_scene("strong", {"model.mu=0"}), o);
  CHECK(r.reference.find("without damper") != std::string::npos);
  CHECK(last_order(r, "implicit") == Approx(2.0).margin(0.1));
  CHECK(r.rows.back().error < 1e-5);
}

TEST_CASE("strong scene: a fine reference run, and the summary errors too", "[convergence]") {
  ConvergenceOptions o;
  o.schemes = {Scheme::implicit, Scheme::paper};
  o.steps = {0.008, 0.004, 0.002};
  const auto r = run_convergence(paper_scene("strong"), o);
  CHECK(r.reference.find("finer run") != std::string::npos);
  CHECK(last_order(r, "implicit") == Approx(2.0).margin(0.2));
  for (const auto& row : r.rows) {
    CHECK(std::isfinite(row.peak_a1));
    CHECK(std::isfinite(row.friction));
    if (row.scheme == "implicit") CHECK(row.friction < 1e-4);  // converged within 1e-4 already at h = 0.008
  }
}

TEST_CASE("adjoin converge writes the table and the CSV", "[convergence][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "converge";
  const auto r = converge("paper-weak.toml", "--schemes implicit,paper --steps 0.008,0.004 --no-plot", dir);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("analytic") != std::string::npos);
  const std::string csv = test::slurp(dir / "convergence.csv");
  CHECK(csv.rfind("scheme,history,h,steps,wall_seconds,error,order,err_peak_x1,err_min_gap,err_friction\n", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 5);
  CHECK_FALSE(std::filesystem::exists(dir / "work-precision.png"));  // --no-plot
  CHECK(!std::filesystem::exists(dir / "convergence-quantities.csv"));  // the analytic reference has only the trajectory

  const auto bad = test::run_cli(std::string("converge ") + ADJOIN_SOURCE_DIR + "/records/scenes/paper-weak.toml --schemes fast");
  CHECK(bad.status == 2);
  CHECK(bad.err.find("--schemes") != std::string::npos);
  const auto uneven = test::run_cli(std::string("converge ") + ADJOIN_SOURCE_DIR + "/records/scenes/paper-weak.toml --steps 0.004,0.003 --no-plot");
  CHECK(uneven.status == 2);
  CHECK(uneven.err.find("integer") != std::string::npos);
}

TEST_CASE("adjoin converge shows a two-block scene's quantities under SPEC 3's names", "[convergence][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "converge-names";
  const auto r = converge("paper-strong.toml", "--schemes implicit --history soe --steps 0.008,0.004 --no-plot", dir);
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string csv = test::slurp(dir / "convergence-quantities.csv");
  // The run labels them by channel (A.x1, link1.stroke, link1.force); the command by name.
  for (const char* name : {",peak x1,", ",t peak x2,", ",peak stroke,", ",peak f1,", ",t peak f2,", ",peak q,", ",final q,"})
    CHECK(csv.find(name) != std::string::npos);
  for (const char* channel : {"A.x1", "B.x1", "link1.", "shear1"}) CHECK(csv.find(channel) == std::string::npos);
  CHECK(r.out.find("t peak stroke") != std::string::npos);
}

TEST_CASE("adjoin converge draws the work-precision figure", "[convergence][cli][plot]") {
  test::needs_program("gnuplot");
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "converge-plot";
  const auto r = converge("paper-weak.toml", "--schemes implicit,paper --steps 0.008,0.004", dir);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("work-precision.png") != std::string::npos);
  test::require_png(dir / "work-precision.png", 900, 600);
}

TEST_CASE("strong scene: the order of every reported quantity, switching instants included", "[convergence]") {
  ConvergenceOptions o;
  o.schemes = {Scheme::implicit};
  o.engines = {HistoryEngine::fft};
  o.steps = {0.004, 0.002, 0.001, 0.0005};
  const auto r = run_convergence(paper_scene("strong"), o);
  REQUIRE(r.rows.size() == 4);
  const auto& coarse = r.rows.front().quantities;
  const auto& fine = r.rows.back().quantities;
  REQUIRE(coarse.size() == fine.size());
  int switches = 0, checked = 0;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    INFO(fine[i].name << ": " << coarse[i].error << " at h = 0.004, " << fine[i].error << " at h = 0.0005");
    REQUIRE(coarse[i].name == fine[i].name);
    CHECK(!r.rows.back().switches_differ);
    if (fine[i].name.rfind("switch", 0) == 0) ++switches;
    if (fine[i].name == "peak link1.force") {  // the damper's limit mu, exactly
      CHECK(fine[i].error == 0.0);
      continue;
    }
    // Second order over the ladder (8x smaller h): the error falls by at least 8^1.7 = 34.
    ++checked;
    CHECK(fine[i].error < coarse[i].error / 34.0);
    CHECK(std::isfinite(fine[i].order));
  }
  CHECK(switches == 7);
  CHECK(checked >= 21);
}

TEST_CASE("an SI scene's reference step is stated in seconds", "[convergence]") {
  const Scene scene = load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/si-record.toml", {"solver.t_end=2"});
  ConvergenceOptions o;
  o.schemes = {Scheme::implicit};
  o.steps = {0.004 / scene.scales.time, 0.002 / scene.scales.time};  // 4 and 2 ms
  const auto r = run_convergence(scene, o);
  INFO(r.reference);
  CHECK(r.reference.find("at h = 0.00025 s") != std::string::npos);  // 2 ms / 8, not 0.00158 (T0 units)
}
