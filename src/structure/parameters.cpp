#include "adjoin/structure/parameters.hpp"

#include <cmath>
#include <sstream>

namespace adjoin {
namespace {

std::string format(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

// The problem's words in *error and its field (the key the words start with) in *field.
bool fail(std::string* error, std::string* field, const std::string& key, const std::string& message) {
  if (error) *error = message;
  if (field) *field = key;
  return false;
}

}  // namespace

bool Rod::IsValid(const std::string& prefix, std::string* error, std::string* field) const {
  if (elastic) return true;
  for (auto [key, value] : {std::pair{"order", order}, {"tau_x", tau_x}, {"tau_f", tau_f}})
    if (!std::isfinite(value))
      return fail(error, field, prefix + "." + key, prefix + "." + key + " = " + format(value) + " must be a finite number");
  if (!(order > 0.0 && order < 1.0))
    return fail(error, field, prefix + ".order", prefix + ".order = " + format(order) +
                           " must lie strictly between 0 and 1 (fractional Zener rod)");
  if (!(tau_f > 0.0))
    return fail(error, field, prefix + ".tau_f", prefix + ".tau_f = " + format(tau_f) + " must be positive (second law)");
  if (tau_x == tau_f)
    return fail(error, field, prefix + ".tau_x", prefix + ".tau_x = " + format(tau_x) + " equals tau_f = " + format(tau_f) +
                           ": that rod is purely elastic; say so with " + prefix +
                           ".elastic = true");
  if (!(tau_x > tau_f))
    return fail(error, field, prefix + ".tau_x", prefix + ".tau_x = " + format(tau_x) + " must be greater than tau_f = " +
                           format(tau_f) + " (second law)");
  if (tau_x > kMaxRelaxationTime)
    return fail(error, field, prefix + ".tau_x", prefix + ".tau_x = " + format(tau_x) + " is beyond the supported " +
                           format(kMaxRelaxationTime) + " (the rod's memory terms would overflow)");
  return true;
}

bool Model::IsValid(std::string* error, std::string* field) const {
  for (auto [key, value] : {std::pair{"rho", rho}, {"eps", eps}, {"mu", mu}, {"gap0", gap0}})
    if (!std::isfinite(value))
      return fail(error, field, std::string("model.") + key, std::string("model.") + key + " = " + format(value) +
                             " must be a finite number");
  if (!(rho > 0.0))
    return fail(error, field, "model.rho", "model.rho = " + format(rho) + " must be positive (mass ratio m1/m2)");
  if (!(eps > 0.0))
    return fail(error, field, "model.eps", "model.eps = " + format(eps) + " must be positive (stiffness ratio k2/k1)");
  if (!(mu >= 0.0))
    return fail(error, field, "model.mu", "model.mu = " + format(mu) + " must be zero or positive (slip force)");
  // Beyond these ranges energies per unit m1 (v2^2 / rho, eps x2^2) overflow or lose every
  // digit; no pair of real structures is that unequal.
  if (rho < 1.0 / kMaxRatio || rho > kMaxRatio)
    return fail(error, field, "model.rho", "model.rho = " + format(rho) + " must lie in [" + format(1.0 / kMaxRatio) + ", " +
                           format(kMaxRatio) + "] (mass ratio m1/m2)");
  if (eps < 1.0 / kMaxRatio || eps > kMaxRatio)
    return fail(error, field, "model.eps", "model.eps = " + format(eps) + " must lie in [" + format(1.0 / kMaxRatio) + ", " +
                           format(kMaxRatio) + "] (stiffness ratio k2/k1)");
  if (mu > kMaxRatio)
    return fail(error, field, "model.mu", "model.mu = " + format(mu) + " must be at most " + format(kMaxRatio) +
                           " (slip force / (m1 g); a larger one never slips: use a large finite value)");
  if (!(std::isfinite(base_friction) && base_friction >= 0.0 && base_friction <= kMaxRatio))
    return fail(error, field, "model.base_friction", "model.base_friction = " + format(base_friction) + " must lie in [0, " + format(kMaxRatio) +
                           "] (the blocks' friction coefficient on their bases)");
  if (std::abs(gap0) > kMaxRatio)
    return fail(error, field, "model.gap0", "model.gap0 = " + format(gap0) + " must lie in [-" + format(kMaxRatio) + ", " +
                           format(kMaxRatio) + "] (in units of X0 = m1 g / k1)");
  if (!rod1.IsValid("model.rod1", error, field) || !rod2.IsValid("model.rod2", error, field)) return false;
  return contact.IsValid("model.contact", error, field);
}

}  // namespace adjoin
