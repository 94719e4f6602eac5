// ground.source = "decaying-sine": the paper's forcing (ground/decaying_sine.hpp), given in
// the scene's units (SI: u0 [m], omega [rad/s], k [1/s]).
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "adjoin/ground/decaying_sine.hpp"
#include "registry.hpp"

namespace adjoin::detail {
namespace {

constexpr std::array<KeySpec, 3> kKeys = {{
    {"ground.u0", Kind::number}, {"ground.omega", Kind::number}, {"ground.k", Kind::number},
}};

std::span<const KeySpec> decaying_sine_keys() { return kKeys; }

std::shared_ptr<const GroundMotion> read_decaying_sine(const SceneReader& r, const Scales& s) {
  const double u0 = r.number("ground.u0"), omega = r.number("ground.omega"), k = r.number("ground.k");
  for (auto [key, value] : {std::pair{"ground.u0", u0}, {"ground.omega", omega}, {"ground.k", k}})
    if (!std::isfinite(value)) r.fail(key, std::string(key) + " must be a finite number");
  if (!(k >= 0.0)) r.fail("ground.k", "ground.k = " + format_scene_number(k) + " must be zero or positive (decay rate)");
  // An SI scene's summary says the motion in the units the scene gave it.
  const std::string si = s.si ? "decaying-sine u0=" + format_scene_number(u0) + " m omega=" + format_scene_number(omega) +
                                    " rad/s k=" + format_scene_number(k) + " 1/s"
                              : std::string();
  return std::make_shared<DecayingSine>(u0 / s.length, omega * s.time, k * s.time, si);
}

}  // namespace

GroundSource decaying_sine_source() { return {"decaying-sine", decaying_sine_keys, read_decaying_sine}; }

}  // namespace adjoin::detail
