#include "adjoin/structure/contact.hpp"


namespace adjoin::structure {
double linear_damping_ratio(double e) {
  const double l = std::log(e);
  return -l / std::sqrt(M_PI * M_PI + l * l);
}

double hertzdamp_damping(double e) { return 8.0 * (1.0 - e) / (5.0 * e); }

double jankowski_damping_ratio(double e) {
  return 9.0 * std::sqrt(5.0) * (1.0 - e * e) / (2.0 * e * (e * (9.0 * M_PI - 16.0) + 16.0));
}

double linear_cut_rebound_ratio(double zeta) {
  return std::exp(-zeta * (M_PI - 2.0 * std::asin(zeta)) / std::sqrt(1.0 - zeta * zeta));
}

double ContactLaw::damping_parameter() const {
  if (!std::isnan(damping)) return damping;
  switch (model) {
    case ContactModel::linear: return linear_damping_ratio(restitution);
    case ContactModel::hertzdamp: return hertzdamp_damping(restitution);
    case ContactModel::jankowski: return jankowski_damping_ratio(restitution);
    default: return 0.0;
  }
}

bool ContactLaw::IsValid(const std::string& where, std::string* error, std::string* field) const {
  auto fail = [&](const char* key, const std::string& problem) {
    if (error) *error = where + "." + key + ": " + problem;
    if (field) *field = where + "." + key;
    return false;
  };
  if (compliant() && !(std::isfinite(stiffness) && stiffness > 0.0))
    return fail("stiffness", "expected a positive contact stiffness");
  if (!(std::isfinite(restitution) && restitution > 0.0 && restitution <= 1.0))
    return fail("restitution", "expected a coefficient of restitution e with 0 < e <= 1");
  if (!std::isnan(damping) && !(std::isfinite(damping) && damping >= 0.0))
    return fail("damping", "expected a non-negative damping parameter");
  if (model == ContactModel::linear && !std::isnan(damping) && damping >= 1.0)
    return fail("damping", "the linear model's damping ratio must be below 1");
  if (tension_cut && model != ContactModel::linear)
    return fail("tension_cut", "only the linear model pulls before separation");
  return true;
}

}  // namespace adjoin::structure
