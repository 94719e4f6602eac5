// ground.scale: a plain factor on any ground source (ground/ground_motion.hpp).
#include <cmath>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/number_text.hpp"
#include "adjoin/ground/ground_motion.hpp"

namespace adjoin {

std::string ScaledMotion::describe() const { return inner_->describe() + " x " + shortest_text(factor_); }

std::shared_ptr<const GroundMotion> scale_ground(std::shared_ptr<const GroundMotion> ground, double factor) {
  if (!(std::isfinite(factor) && factor > 0.0))
    throw FieldError("ground.scale", shortest_text(factor) + " must be a finite number > 0 (a factor on the ground's acceleration)");
  if (factor == 1.0) return ground;
  return std::make_shared<ScaledMotion>(std::move(ground), factor);
}

const GroundMotion& unscaled_ground(const GroundMotion& ground) {
  const GroundMotion* g = &ground;
  while (const auto* scaled = dynamic_cast<const ScaledMotion*>(g)) g = &scaled->inner();
  return *g;
}

}  // namespace adjoin
