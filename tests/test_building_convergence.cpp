// Convergence of building runs (study/convergence.hpp run_convergence, `adjoin converge` on a
// building scene): every reported quantity's error against a finer run with its observed
// order. The structure step is trapezoidal: on a linear structure every smooth quantity
// converges at order 2; with a friction damper the displacements and the switching instants still do,
// and the table says when a rung switches another number of times than the reference.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "adjoin/io/building_scene.hpp"
#include "adjoin/study/convergence.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;
using adjoin::test::run_cli;
using adjoin::test::slurp;

namespace {

const std::string kScene = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";

const QuantityError* find(const ConvergenceRow& row, const std::string& name) {
  for (const auto& q : row.quantities)
    if (q.name == name) return &q;
  return nullptr;
}

}  // namespace

TEST_CASE("a linear building converges at order 2 in its trajectory and in every refined peak", "[building_convergence]") {
  // No damper, no contact pair: springs, Zener storeys and classical damping, linear.
  const BuildingScene scene = load_building_scene(kScene, {"solver.t_end=6"}, {"link", "contact"});
  ConvergenceOptions options;
  options.steps = {0.008, 0.004, 0.002, 0.001};
  const ConvergenceResult result = run_convergence(scene, options);
  REQUIRE(result.rows.size() == 4);
  CHECK(result.reference.find("h = 0.000125 s") != std::string::npos);
  for (std::size_t i = 1; i < result.rows.size(); ++i) {
    INFO("h = " << result.rows[i].h);
    CHECK(result.rows[i].order == Approx(2.0).margin(0.1));
    // Peak values and their times converge at 2 once the step resolves the record's samples
    // (dt = 0.02 s: h = 0.008 puts the forcing's kinks inside steps, and the first order
    // measured from it is pre-asymptotic).
    if (i < 2) continue;
    for (const char* name : {"peak A.x5", "t peak A.x5", "peak A.drift1", "peak B.x3", "t peak B.x3", "peak B.drift1"}) {
      const QuantityError* q = find(result.rows[i], name);
      REQUIRE(q != nullptr);
      INFO(name << ": error " << q->error);
      CHECK(q->order == Approx(2.0).margin(0.1));
    }
  }
  // Errors shrink by about 4 per halving: the finest rung is some 60 times better than the
  // coarsest (4^3 = 64).
  CHECK(result.rows.front().error / result.rows.back().error == Approx(64.0).epsilon(0.25));
  // The energy residual is itself an error of order 2.
  const QuantityError* coarse = find(result.rows[1], "energy residual");
  const QuantityError* fine = find(result.rows[3], "energy residual");
  REQUIRE(coarse != nullptr);
  REQUIRE(fine != nullptr);
  CHECK(std::log2(coarse->error / fine->error) / 2.0 == Approx(2.0).margin(0.3));
}

TEST_CASE("a building with a friction damper: displacements converge, and switches are compared when they match",
          "[building_convergence]") {
  const BuildingScene scene = load_building_scene(kScene, {"solver.t_end=6"}, {"contact"});
  ConvergenceOptions options;
  options.steps = {0.004, 0.002, 0.001, 0.0005};
  const ConvergenceResult result = run_convergence(scene, options);
  REQUIRE(result.rows.size() == 4);
  // Locating each switch inside its step (a slip's end on the parabola of the grid velocities)
  // keeps the trajectory, the roof's peak and the switching instants at order 2.
  for (std::size_t i = 0; i < result.rows.size(); ++i) {
    const auto& row = result.rows[i];
    INFO("h = " << row.h);
    REQUIRE(find(row, "peak link1.stroke") != nullptr);
    CHECK(find(row, "link1 energy") != nullptr);
    // A rung switching as often as the reference has its switching instants compared.
    CHECK((row.switches_differ || find(row, "link1 switch 1") != nullptr));
    if (i == 0) continue;
    CHECK(row.order == Approx(2.0).margin(0.15));
    CHECK(find(row, "peak A.x5")->order == Approx(2.0).margin(0.15));
    if (const QuantityError* t = find(row, "link1 switch 1")) CHECK(t->order == Approx(2.0).margin(0.2));
  }
  CHECK(find(result.rows.back(), "peak A.x5")->error < 1e-4);
}

TEST_CASE("adjoin converge on a building scene writes the ladder's tables", "[building_convergence][cli]") {
  const std::filesystem::path dir = std::filesystem::path(ADJOIN_TEST_TMP) / "building-converge";
  std::filesystem::remove_all(dir);
  auto r = run_cli("converge '" + kScene + "' --set solver.t_end=2 --steps 0.004,0.002 --no-plot --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("peak A.x5") != std::string::npos);
  const std::string table = slurp(dir / "convergence-quantities.csv");
  CHECK(table.find("implicit,soe,0.004,peak A.x5,relative,") != std::string::npos);
  CHECK(table.find("implicit,soe,0.002,t peak B.x3,absolute,") != std::string::npos);
  CHECK(slurp(dir / "convergence.csv").find("implicit,soe,0.002,") != std::string::npos);
  // The two-block schemes are refused by name.
  r = run_cli("converge '" + kScene + "' --schemes paper --no-plot --out '" + dir.string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.find("--schemes: \"paper\"") != std::string::npos);
}
