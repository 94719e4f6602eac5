#include "adjoin/structure/building.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/structure/rules.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "devices/device_parts.hpp"

namespace adjoin::structure {

using devices::positive;

std::string zener_check(const Zener& z) {
  if (!positive(z.k)) return "stiffness must be a positive number";
  if (!(z.order > 0.0 && z.order < 1.0)) return "order must lie in (0, 1)";
  if (!positive(z.tau_f)) return "tau_f must be positive";
  if (!(std::isfinite(z.tau_x) && z.tau_x > z.tau_f)) return "tau_x must exceed tau_f (the second law)";
  return "";
}

// A Bouc-Wen law's shape (SPEC §7): the exponent n in [1, 20] (below 1, |z|^(n-1) and so the
// implicit step's derivative are unbounded at z = 0) and beta + gamma > 0 (else z does not
// saturate: the law never yields).
std::string bouc_wen_check(double n, double beta, double gamma) {
  if (!(std::isfinite(n) && n >= 1.0 && n <= 20.0)) return "n must lie in [1, 20] (the Bouc-Wen exponent)";
  if (!(std::isfinite(beta) && std::isfinite(gamma) && beta + gamma > 0.0))
    return "beta: beta + gamma must be positive (else the Bouc-Wen law never yields)";
  return "";
}

namespace {

bool building_valid(const Building& b, const std::string& path, std::string* error) {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  const int n = b.floors();
  if (n < 1) return fail(path + ": a building needs at least one storey");
  for (int i = 0; i < n; ++i)
    if (!positive(b.masses[i])) return fail(path + ".masses[" + std::to_string(i + 1) + "] must be a positive mass (kg)");
  if (b.springs.size() != n) return fail(path + ".stiffnesses: expected " + std::to_string(n) + " values, one per storey");
  for (int i = 0; i < n; ++i)
    if (!(std::isfinite(b.springs[i]) && b.springs[i] >= 0.0))
      return fail(path + ".stiffnesses[" + std::to_string(i + 1) + "] must be a non-negative stiffness (N/m)");
  for (std::size_t d = 0; d < b.devices.size(); ++d) {
    const StoreyDevice& dev = b.devices[d];
    const std::string where = path + ".device[" + std::to_string(d + 1) + "]";
    if (dev.storeys.empty()) return fail(where + ".storeys: list at least one storey");
    for (int s : dev.storeys)
      if (s < 1 || s > n) return fail(where + ".storeys: storey " + std::to_string(s) + " is not in 1.." + std::to_string(n));
    if (const std::string p = kind_of(dev).invalid(dev); !p.empty()) return fail(where + p);
  }
  if (b.hysteresis.model == HysteresisModel::bouc_wen) {
    const StoreyHysteresis& y = b.hysteresis;
    if (const std::string p = bouc_wen_check(y.n, y.beta, y.gamma); !p.empty()) return fail(path + ".hysteresis." + p);
  }
  if (b.hysteresis.model != HysteresisModel::elastic) {
    const StoreyHysteresis& y = b.hysteresis;
    if (y.yield_forces.size() != n) return fail(path + ".hysteresis.yield_forces: expected " + std::to_string(n) + " values, one per storey");
    for (int i = 0; i < n; ++i)
      if (!positive(y.yield_forces[i]))
        return fail(path + ".hysteresis.yield_forces[" + std::to_string(i + 1) + "] must be a positive force (N)");
    if (!(y.hardening >= 0.0 && y.hardening < 1.0)) return fail(path + ".hysteresis.hardening must lie in [0, 1)");
    for (int i = 0; i < n; ++i)
      if (!(b.springs[i] > 0.0))
        return fail(path + ".hysteresis: storey " + std::to_string(i + 1) + " has no spring to yield (give its stiffness)");
  }
  const Eigen::VectorXd k = b.static_stiffness();
  for (int i = 0; i < n; ++i)
    if (!(k[i] > 0.0))
      return fail(path + ": storey " + std::to_string(i + 1) + " has no stiffness (give a spring or a Zener device)");
  if (b.has_heights() && b.heights.size() != n)
    return fail(path + ".heights: expected " + std::to_string(n) + " values, one per storey");
  for (int i = 0; i < b.heights.size(); ++i)
    if (!positive(b.heights[i])) return fail(path + ".heights[" + std::to_string(i + 1) + "] must be a positive height (m)");
  if (b.p_delta && !b.has_heights()) return fail(path + ".p_delta needs the storey heights (height or heights)");
  if (!positive(b.collapse_drift_ratio)) return fail(path + ".collapse_drift_ratio must be a positive drift ratio");
  const InherentDamping& c = b.damping;
  if (c.model != DampingModel::none && !(c.ratio >= 0.0 && c.ratio < 1.0))
    return fail(path + ".damping.ratio must lie in [0, 1)");
  if (c.model == DampingModel::rayleigh) {
    if (n < 2) return fail(path + ".damping: Rayleigh damping needs two modes; a one-storey building has one (use \"modal\")");
    if (c.mode_i < 1 || c.mode_j < 1 || c.mode_i > n || c.mode_j > n || c.mode_i == c.mode_j)
      return fail(path + ".damping.modes: two different modes in 1.." + std::to_string(n));
  }
  if (!(std::isfinite(b.ground_friction) && b.ground_friction >= 0.0)) return fail(path + ": the base friction must be a non-negative force (N)");
  if (b.base && b.ground_friction > 0.0) return fail(path + ": base friction under floor 1 and an isolated base: give one of them");
  if (b.base) {
    const Base& base = *b.base;
    if (!positive(base.mass)) return fail(path + ".base.mass must be a positive mass (kg)");
    if (!positive(base.friction)) return fail(path + ".base.friction must be a positive friction coefficient (mu > 0)");
    if (base.model == BaseModel::friction_pendulum && !positive(base.radius))
      return fail(path + ".base.radius must be a positive radius (m) for a friction pendulum");
    if (base.model == BaseModel::flat_slider && base.radius != 0.0)
      return fail(path + ".base.radius: a flat slider has no radius (use model = \"friction-pendulum\")");
  }
  return true;
}

}  // namespace

Eigen::VectorXd Building::static_stiffness() const {
  Eigen::VectorXd k = springs;
  for (const StoreyDevice& d : devices) {
    const double add = kind_of(d).relaxed(d);
    for (int s : d.storeys)
      if (s >= 1 && s <= k.size()) k[s - 1] += add;
  }
  return k;
}

bool Building::yields() const {
  if (hysteresis.model != HysteresisModel::elastic) return true;
  for (const StoreyDevice& d : devices)
    if (kind_of(d).yields) return true;
  return false;
}

Eigen::VectorXd Building::geometric_stiffness() const {
  Eigen::VectorXd k = Eigen::VectorXd::Zero(floors());
  if (!p_delta || heights.size() != floors()) return k;
  double above = 0.0;  // the mass storey i carries: floors i..n
  for (int i = floors() - 1; i >= 0; --i) {
    above += masses[i];
    k[i] = -above * kStandardGravity / heights[i];
  }
  return k;
}

double Building::base_slip_force() const {
  return base ? base->friction * (base->mass + masses.sum()) * kStandardGravity : 0.0;
}

double Building::base_stiffness() const {
  if (!base || base->model != BaseModel::friction_pendulum) return 0.0;
  return (base->mass + masses.sum()) * kStandardGravity / base->radius;
}

std::vector<GroundSlider> Structure::ground_sliders() const {
  std::vector<GroundSlider> out;
  for (const Building* building : {&a, b ? &*b : nullptr}) {
    if (!building) continue;
    const char name = building == &a ? 'A' : 'B';
    if (building->base) out.push_back({name, true, base_dof(name), building->base_slip_force()});
    if (building->ground_friction > 0.0) out.push_back({name, false, dof(name, 1), building->ground_friction});
  }
  return out;
}

bool Structure::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!building_valid(a, "building.A", error)) return false;
  if (b && !building_valid(*b, "building.B", error)) return false;
  if ((!links.empty() || !contacts.empty()) && !b) return fail("links and contacts join building A to building B: add [building.B]");
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Link& l = links[i];
    const std::string where = "link[" + std::to_string(i + 1) + "]";
    if (l.floor_a < 1 || l.floor_a > a.floors() || l.floor_b < 1 || l.floor_b > b->floors())
      return fail(where + ".floors: [" + std::to_string(l.floor_a) + ", " + std::to_string(l.floor_b) + "] is not a floor of A (1.." +
                  std::to_string(a.floors()) + ") and of B (1.." + std::to_string(b->floors()) + ")");
    if (const std::string p = kind_of(l).invalid(l); !p.empty()) return fail(where + p);
  }
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    const std::string where = "contact[" + std::to_string(i + 1) + "]";
    if (c.floor_a < 1 || c.floor_a > a.floors() || c.floor_b < 1 || c.floor_b > b->floors())
      return fail(where + ".floors: not a floor of A and of B");
    if (!(std::isfinite(c.gap) && c.gap >= 0.0)) return fail(where + ".gap must be a non-negative distance (m)");
    if (!c.law.IsValid(where, error)) return false;
  }
  return true;
}

double stiffness_for_period(const Eigen::VectorXd& masses, double period) {
  if (!(positive(period))) throw InputError("period must be a positive number of seconds");
  const Eigen::MatrixXd k1 = stiffness_matrix(Eigen::VectorXd::Ones(masses.size()));
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k1, Eigen::MatrixXd(masses.asDiagonal()));
  const double lambda1 = solver.eigenvalues()[0];  // omega_1^2 at unit storey stiffness
  const double omega = 2.0 * M_PI / period;
  return omega * omega / lambda1;
}

}  // namespace adjoin::structure
