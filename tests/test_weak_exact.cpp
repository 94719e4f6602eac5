// The weak scene never leaves stick, so it is linear with an exact solution (study/
// linear_reference.hpp, Laplace inversion; itself checked against 50-digit values). The
// default scheme converges to it at second order and reaches 1e-9 in x(16) at h = 0.0008.
#include <catch2/catch.hpp>
#include <cmath>

#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/study/linear_reference.hpp"
#include "adjoin/study/run.hpp"

using namespace adjoin;

TEST_CASE("weak scene: implicit/fft converges to the exact x(16) at second order, 1e-9 at h = 0.0008", "[exact][weak]") {
  const std::string file = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-weak.toml";
  const Scene base = load_scene(file);
  const auto* sine = dynamic_cast<const DecayingSine*>(base.ground.get());
  REQUIRE(sine);
  const LinearReference exact(two_block_model(base), sine->u0(), sine->omega(), sine->k(), true);
  const double x16 = exact.at(16.0).x[0];
  CHECK(x16 == Approx(1.5037809082027091e-03).epsilon(1e-12));  // the 50-digit value

  std::vector<double> errors;
  for (const char* h : {"0.0032", "0.0016", "0.0008"}) {
    const Report r = run(load_scene(file, {"solver.scheme=implicit", "solver.history=fft", std::string("solver.h=") + h}));
    REQUIRE(r.t_last == Approx(16.0));
    errors.push_back(std::abs(r.last_value("A.x1") - x16));
  }
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2]);
  CHECK(std::log2(errors[0] / errors[1]) == Approx(2.0).margin(0.1));
  CHECK(std::log2(errors[1] / errors[2]) == Approx(2.0).margin(0.1));
  CHECK(errors[2] <= 1e-9);
}
