#pragma once
// Contact laws for pounding (SPEC §6): what happens when the gap g between two floors closes.
// With delta = -g the penetration, delta' its rate and m_eff = m_i m_j / (m_i + m_j):
//
//   linear     k delta + c delta' while delta > 0 (with tension_cut, only while that is > 0);
//              c = 2 zeta sqrt(k m_eff), zeta = -ln e / sqrt(pi^2 + ln^2 e): the rebound ratio
//              is e exactly without the cut
//   hertz      k delta^(3/2), no damping (elastic: rebound ratio 1)
//   hertzdamp  k delta^(3/2) (1 + xi_bar delta' / v0), v0 the approach speed at first touch,
//              xi_bar = 8 (1 - e) / (5 e) (Muthukumar and DesRoches; approximate); the force is
//              never taken below 0, and v0 never below sqrt(k delta^(5/2) / (1.25 m_eff)), the
//              speed a free impact needs to reach delta (a contact at rest keeps a finite damping)
//   jankowski  k delta^(3/2) + c delta' while approaching (delta' > 0), k delta^(3/2) while
//              separating; c = 2 xi sqrt(k sqrt(delta) m_eff),
//              xi = 9 sqrt(5) (1 - e^2) / (2 e (e (9 pi - 16) + 16))
//   impact     Newton's law: no penetration at all (g >= 0 exactly), g'+ = -e g'- at impact
//   none       nothing resists the closing gap: the floors pass through each other, and every
//              value after the first contact is flagged as outside the model
//
// The damping parameter (zeta, xi_bar or xi) follows from the coefficient of restitution e,
// or is given directly (`damping`, then e is not used). Values in SI units for building
// scenes, in the dimensionless units of SPEC §1 for two-block scenes.
#include <cmath>
#include <limits>
#include <string>

// ContactModel, with the scene words "none", "linear", "hertz", "hertzdamp", "jankowski",
// "impact" (to_string, parse_enum).
#include "adjoin/core/enum_names.hpp"

namespace adjoin::structure {

struct ContactLaw {
  ContactModel model = ContactModel::none;
  double stiffness = 0.0;    // linear: k [N/m]; hertz, hertzdamp, jankowski: k [N/m^1.5]
  double restitution = 1.0;  // e, 0 < e <= 1
  // zeta (linear), xi_bar (hertzdamp) or xi (jankowski) given directly; NaN: from e.
  double damping = std::numeric_limits<double>::quiet_NaN();
  bool tension_cut = false;  // linear only

  bool compliant() const { return model != ContactModel::none && model != ContactModel::impact; }
  // The damping parameter the law uses: `damping` if given, else the formula of its model
  // from e (0 for hertz, none and impact).
  double damping_parameter() const;
  // Why the law is not valid (stiffness > 0 for compliant models, 0 < e <= 1, damping >= 0,
  // tension_cut only on linear), with `where` ("contact[2]", "model.contact") and the key
  // ("contact[2].stiffness"), or true.
  // `field` (optional): the key of the problem (WHERE.stiffness, ...).
  bool IsValid(const std::string& where, std::string* error, std::string* field = nullptr) const;
};

// The formulas of SPEC §6, e in (0, 1].
double linear_damping_ratio(double e);       // zeta
double hertzdamp_damping(double e);          // xi_bar
double jankowski_damping_ratio(double e);    // xi
// The linear model's rebound ratio with the tension cut: exp(-zeta (pi - 2 asin zeta) / sqrt(1 - zeta^2)).
double linear_cut_rebound_ratio(double zeta);

}  // namespace adjoin::structure
