#pragma once
// What the device kinds' files (src/structure/devices/<kind>.cpp) share: the keys several kinds
// take, with their fields and checks, and small checks. Internal to structure/.
#include <cmath>
#include <string>

#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/rules.hpp"

namespace adjoin::structure {

// Structure::IsValid's checks of a Zener element and a Bouc-Wen shape, in its words:
// "" or "tau_x must exceed tau_f (the second law)" (building.cpp).
std::string zener_check(const Zener& z);
std::string bouc_wen_check(double n, double beta, double gamma);

}  // namespace adjoin::structure

namespace adjoin::structure::devices {

inline bool positive(double v) { return std::isfinite(v) && v > 0.0; }

inline double none(const StoreyDevice&) { return 0.0; }
inline double spring_k(const StoreyDevice& d) { return d.k; }
inline DeviceFamily linear(const StoreyDevice&) { return DeviceFamily::linear; }
inline std::string no_joint_problem(const StoreyDevice&) { return ""; }

// The keys: their fields and checks (structure/rules.hpp).
inline DeviceKey stiffness_key() {
  return {"stiffness", [](StoreyDevice& d) -> double& { return d.k; }, true, 0.0,
          [](double v) { return bounded_problem(v, kStiffnessRange); }};
}
inline DeviceKey c_key() {
  return {"c", [](StoreyDevice& d) -> double& { return d.c; }, true, 0.0, [](double v) { return bounded_problem(v, kDashpotRange); }};
}
inline DeviceKey yield_force_key() {
  return {"yield_force", [](StoreyDevice& d) -> double& { return d.yield_force; }, true, 0.0,
          [](double v) { return bounded_problem(v, kForceRange); }};
}
inline DeviceKey hardening_key() {
  return {"hardening", [](StoreyDevice& d) -> double& { return d.hardening; }, false, 0.0, hardening_problem};
}

// Structure::IsValid's checks of a yielding device (bilinear, bouc-wen): "" or the field's problem.
inline std::string yielding_invalid(const StoreyDevice& d) {
  if (!positive(d.k)) return ".stiffness must be positive (N/m)";
  if (!positive(d.yield_force)) return ".yield_force must be a positive force (N)";
  if (!(d.hardening >= 0.0 && d.hardening < 1.0)) return ".hardening must lie in [0, 1)";
  return "";
}

}  // namespace adjoin::structure::devices
