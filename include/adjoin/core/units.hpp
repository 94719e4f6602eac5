#pragma once
// Scale factors between the solver's dimensionless quantities and the scene's units.
//
// The solver always works in the paper's dimensionless form. An SI scene (SPEC §1, "Physical
// units") uses T0 = sqrt(m1/k1) and X0 = m1 g / k1; a dimensionless scene uses factors of 1.
// Multiply a dimensionless value by the factor to get it in the scene's units.
#include <cmath>
#include <string>

namespace adjoin {

inline constexpr double kStandardGravity = 9.80665;  // m/s^2

struct Scales {
  bool si = false;
  double time = 1.0;          // s
  double length = 1.0;        // m
  double velocity = 1.0;      // m/s
  double acceleration = 1.0;  // m/s^2 (dimensionless accelerations are in g)
  double force = 1.0;         // N
  double energy = 1.0;        // J

  static Scales Dimensionless() { return Scales{}; }
  // m1 [kg], k1 [N/m].
  static Scales SI(double m1, double k1) {
    Scales s;
    s.si = true;
    s.time = std::sqrt(m1 / k1);
    s.length = m1 * kStandardGravity / k1;
    s.velocity = s.length / s.time;
    s.acceleration = kStandardGravity;
    s.force = m1 * kStandardGravity;
    s.energy = s.force * s.length;
    return s;
  }
  std::string units_name() const { return si ? "SI" : "dimensionless"; }
};

}  // namespace adjoin
