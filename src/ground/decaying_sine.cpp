#include "adjoin/ground/decaying_sine.hpp"

#include <cmath>
#include <sstream>

namespace adjoin {

double DecayingSine::ag(double t) const {
  return u0_ * omega_ * omega_ * std::exp(-k_ * t) * std::sin(omega_ * t);
}

std::string DecayingSine::describe() const {
  if (!description_.empty()) return description_;
  std::ostringstream s;
  s << "decaying-sine u0=" << u0_ << " omega=" << omega_ << " k=" << k_;
  return s.str();
}

}  // namespace adjoin
