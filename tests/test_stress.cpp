// The stress suite (records/scenes/stress/): extreme orders, relaxation times, mass and
// stiffness ratios, slip forces, excitation levels and steps. The default scheme must finish
// every case with finite outputs and a small energy residual; the paper scheme must either
// agree with it or stop with exit status 3 and name the step it needs.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;

namespace {

std::vector<std::filesystem::path> stress_scenes() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/stress"))
    if (e.path().extension() == ".toml" && e.path().stem() != "long-1e4") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Every reported number is finite.
class FiniteCheck final : public StructureObserver {
 public:
  void observe(const StructureState& s) override {
    if (!std::isfinite(s.t) || !std::isfinite(s.ag)) ++non_finite;
    for (const Eigen::VectorXd* v : {&s.x, &s.v, &s.a_abs, &s.storey_force, &s.link_force})
      if (!v->allFinite()) ++non_finite;
  }
  int non_finite = 0;
};

}  // namespace

TEST_CASE("the stress suite is all there", "[stress]") {
  // The extremes the cases below run, by name: a scene lost or renamed fails here, not
  // silently in a loop over fewer files.
  std::vector<std::string> names;
  for (const auto& file : stress_scenes()) names.push_back(file.stem().string());
  CHECK(names == std::vector<std::string>{"eps-1e-3", "eps-1e3", "glassy-h-0.05", "h-0.1", "h-1e-5", "mu-0", "mu-1e6",
                                          "order-0.01", "order-0.99", "rho-1e-3", "rho-1e3", "tau-f-1e-8", "tau-ratio-1e8",
                                          "u0-1e-9", "u0-1e3"});
}

TEST_CASE("the default scheme finishes every stress case with finite outputs and a small energy residual", "[stress]") {
  for (const auto& file : stress_scenes()) {
    const Scene scene = load_scene(file);
    INFO(file.filename().string());
    REQUIRE(scene.solver.scheme == Scheme::implicit);
    FiniteCheck finite;
    const Report r = run(scene, {&finite});
    CHECK(finite.non_finite == 0);
    CHECK(std::isfinite(r.peak("A.x1").max_abs));
    CHECK(std::isfinite(r.energy.residual));
    // The stated bound: |residual| <= 1e-3 of the input energy at h = 0.1, 1e-5 at h <= 0.002.
    const double bound = scene.solver.h > 0.01 ? 1e-3 : 1e-5;
    CHECK(std::abs(r.energy.residual) <= bound * r.energy.input);
    CHECK(r.link_energy(0) >= 0.0);
    if (two_block_model(scene).mu > 1e3) CHECK(r.phases.size() == 1);  // a damper that cannot slip
  }
}

TEST_CASE("the paper scheme agrees with the default one or stops naming the step it needs", "[stress]") {
  int stopped = 0, agreed = 0;
  for (const auto& file : stress_scenes()) {
    INFO(file.filename().string());
    const Scene implicit = load_scene(file);
    const Scene paper = load_scene(file, {"solver.scheme=paper"});
    const Report reference = run(implicit);
    try {
      const Report r = run(paper);
      // First order against second order: within 2 % in the peak and the energy input.
      CHECK(r.peak("A.x1").max_abs == Approx(reference.peak("A.x1").max_abs).epsilon(0.02));
      CHECK(r.energy.input == Approx(reference.energy.input).epsilon(0.02));
      ++agreed;
    } catch (const NumericalError& e) {
      const std::string message = e.what();
      CHECK(message.find("need h < ") != std::string::npos);
      ++stopped;
    }
  }
  CHECK(stopped >= 1);
  CHECK(agreed >= 10);
}

TEST_CASE("adjoin run on a stress case the paper scheme cannot do: exit 3, the bound, no output", "[stress][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "stress-paper";
  std::filesystem::remove_all(dir);
  const auto r = test::run_cli(std::string("run ") + ADJOIN_SOURCE_DIR +
                               "/records/scenes/stress/glassy-h-0.05.toml --set solver.scheme=paper --out '" + dir.string() + "'");
  CHECK(r.status == 3);
  CHECK(r.err.find("need h < 0.0305") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "summary.json"));
  const auto ok = test::run_cli(std::string("run ") + ADJOIN_SOURCE_DIR +
                                "/records/scenes/stress/glassy-h-0.05.toml -q --out '" + dir.string() + "'");
  CHECK(ok.status == 0);
  CHECK(std::filesystem::exists(dir / "summary.json"));
}
