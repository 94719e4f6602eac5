// ground.scale: a plain factor on any ground source (ground/ground_motion.hpp).
#include <charconv>
#include <cmath>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/ground_motion.hpp"

namespace adjoin {
namespace {

std::string shortest(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

}  // namespace

std::string ScaledMotion::describe() const { return inner_->describe() + " x " + shortest(factor_); }

std::shared_ptr<const GroundMotion> scale_ground(std::shared_ptr<const GroundMotion> ground, double factor) {
  if (!(std::isfinite(factor) && factor > 0.0))
    throw FieldError("ground.scale", shortest(factor) + " must be a finite number > 0 (a factor on the ground's acceleration)");
  if (factor == 1.0) return ground;
  return std::make_shared<ScaledMotion>(std::move(ground), factor);
}

const GroundMotion& unscaled_ground(const GroundMotion& ground) {
  const GroundMotion* g = &ground;
  while (const auto* scaled = dynamic_cast<const ScaledMotion*>(g)) g = &scaled->inner();
  return *g;
}

}  // namespace adjoin
