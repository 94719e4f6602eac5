#pragma once
// The paper's simplified earthquake (2.6): u'' = -u0 Omega^2 e^{-k t} sin(Omega t), so the
// forcing is a_g(t) = u0 Omega^2 e^{-k t} sin(Omega t). Dimensionless parameters.
#include <string>
#include <utility>

#include "adjoin/ground/ground_motion.hpp"

namespace adjoin {

class DecayingSine final : public GroundMotion {
 public:
  // `description`: what describe() says, when the scene's units are not these (an SI scene's
  // u0 [m], omega [rad/s], k [1/s]); empty: the dimensionless parameters.
  DecayingSine(double u0, double omega, double k, std::string description = {})
      : u0_(u0), omega_(omega), k_(k), description_(std::move(description)) {}
  double ag(double t) const override;
  std::string describe() const override;

  double u0() const { return u0_; }
  double omega() const { return omega_; }
  double k() const { return k_; }

 private:
  double u0_, omega_, k_;
  std::string description_;
};

}  // namespace adjoin
