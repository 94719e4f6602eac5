#include "adjoin/structure/rules.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "adjoin/core/number_text.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/modal.hpp"

namespace adjoin::structure {

// Numbers in the structure's messages: 6 significant digits.
std::string number_text(double v) { return adjoin::number_text(v, 6); }

std::string Range::problem(double v) const {
  if (v >= lo && v <= hi) return "";
  return number_text(v) + " is outside the supported " + number_text(lo) + " to " + number_text(hi) + " " + unit +
         " (" + why + ")";
}

std::string bounded_problem(double v, const Range& range) {
  if (!(v > 0.0)) return std::isfinite(v) ? "expected a positive number" : "expected a finite number";
  return range.problem(v);
}

std::string zener_order_problem(double order) {
  return order > 0.0 && order < 1.0 ? "" : "expected a fractional order in (0, 1)";
}

std::string zener_tau_problem(double tau_x, double tau_f) {
  if (!(tau_x > tau_f)) return "must exceed tau_f (the second law; tau_x = tau_f is a spring)";
  if (tau_x > kMaxTauRatio * tau_f)
    return "tau_x / tau_f = " + number_text(tau_x / tau_f) + " is beyond the supported " + number_text(kMaxTauRatio) +
           " (the unrelaxed stiffness, stiffness x tau_x / tau_f, would make the step ill conditioned)";
  return "";
}

std::pair<std::string, std::string> zener_problem(const Zener& z) {
  if (auto p = bounded_problem(z.k, kStiffnessRange); !p.empty()) return {"stiffness", p};
  if (auto p = zener_order_problem(z.order); !p.empty()) return {"order", p};
  if (auto p = bounded_problem(z.tau_f, kTauRange); !p.empty()) return {"tau_f", p};
  if (auto p = bounded_problem(z.tau_x, kTauRange); !p.empty()) return {"tau_x", p};
  if (auto p = zener_tau_problem(z.tau_x, z.tau_f); !p.empty()) return {"tau_x", p};
  return {"", ""};
}

std::string damping_ratio_problem(double ratio) {
  return ratio >= 0.0 && ratio < 1.0 ? "" : "expected a damping ratio in [0, 1) (0.05 is 5 %)";
}

std::string rayleigh_modes_problem(int mode_i, int mode_j, int n) {
  if (mode_i >= 1 && mode_j >= 1 && mode_i != mode_j && mode_i <= n && mode_j <= n) return "";
  return "Rayleigh damping is fitted at two different modes of the " + std::to_string(n) + " the building has";
}

std::string contact_stiffness_problem(double k, const std::string& unit) {
  if (!(k > kMaxContactStiffness)) return "";
  return number_text(k) + " is beyond the supported " + number_text(kMaxContactStiffness) + " " + unit +
         " (the contact force would overflow)";
}

std::string device_storeys_problem(const std::vector<int>& storeys, int n) {
  if (storeys.empty()) return "expected a list of at least one storey";
  // A storey listed twice would get the device twice.
  std::set<int> seen;
  for (int v : storeys)
    if (!seen.insert(v).second) return std::to_string(v) + " is listed twice; list each storey once";
  for (int v : storeys)
    if (v < 1 || v > n) return "storey " + std::to_string(v) + " is not in 1.." + std::to_string(n);
  return "";
}

std::string floor_problem(char name, int floor, const Building& b) {
  if (floor >= 1 && floor <= b.floors()) return "";
  return "floor " + std::to_string(floor) + " is not a floor of " + name + " (1.." + std::to_string(b.floors()) + ")";
}

double stiffness_for_period_in_range(const Eigen::VectorXd& masses, double period, std::string* problem) {
  const double k_at_1s = stiffness_for_period(masses, 1.0);
  const double k = k_at_1s / (period * period);
  if (k >= kStiffnessRange.lo && k <= kStiffnessRange.hi) return k;
  const double shortest = std::sqrt(k_at_1s / kStiffnessRange.hi), longest = std::sqrt(k_at_1s / kStiffnessRange.lo);
  *problem = number_text(period) + " s is outside the supported " + number_text(shortest) + " to " + number_text(longest) +
             " s for these floor masses (the periods of storey springs from " + number_text(kStiffnessRange.lo) + " to " +
             number_text(kStiffnessRange.hi) + " N/m, bounds that keep the step's matrices finite and well conditioned)";
  return 0.0;
}

double spring_for_period_with_devices(const Building& building, double period, double enough, std::string* problem) {
  const auto n = building.masses.size();
  auto period_with = [&](double k) {
    Building trial = building;
    trial.springs = Eigen::VectorXd::Constant(n, k);
    const Eigen::VectorXd storey = trial.static_stiffness();
    if (storey.minCoeff() <= 0.0) return std::numeric_limits<double>::infinity();
    return building_modes(trial).periods[0];
  };
  if (period_with(0.0) <= period) {
    *problem = "the storey devices alone already give a period of " + std::to_string(period_with(0.0)) + " s, below " +
               std::to_string(period) + " s: remove period, or soften the devices";
    return 0.0;
  }
  double lo = 0.0, hi = enough;
  for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (period_with(mid) > period ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double slip_force_from_ratio(double ratio, const Building& of) { return ratio * (of.masses.sum() * kStandardGravity); }

std::string hardening_problem(double b) {
  return b >= 0.0 && b < 1.0 ? "" : "expected a post-yield stiffness ratio in [0, 1)";
}

std::string bouc_wen_exponent_problem(double n) {
  return n >= 1.0 && n <= 20.0 ? "" : "expected the Bouc-Wen exponent n in [1, 20]";
}

std::string bouc_wen_shape_problem(double beta, double gamma) {
  if (std::isfinite(beta) && std::isfinite(gamma) && beta + gamma > 0.0) return "";
  return "expected beta + gamma > 0 (else the Bouc-Wen law never yields)";
}

std::string base_mass_problem(double kg) {
  if (!(kg > 0.0)) return "expected a positive base mass (kg)";
  return kMassRange.problem(kg);
}

std::string base_friction_problem(double mu) {
  if (mu > 0.0 && mu < 1.0) return "";
  return "expected a friction coefficient mu in (0, 1) (of the weight of the base and the floors above)";
}

std::string base_radius_problem(double m) {
  return std::isfinite(m) && m > 0.0 ? "" : "expected a positive radius of curvature (m)";
}

std::string storey_stiffness_problem(const Building& b) {
  const Eigen::VectorXd k = b.static_stiffness();
  for (Eigen::Index i = 0; i < k.size(); ++i)
    if (!(k[i] > 0.0))
      return "storey " + std::to_string(i + 1) +
             " has no stiffness: give stiffness, stiffnesses or period, or a spring or Zener device on it";
  return "";
}

std::string heights_problem(const Building& b, bool collapse_given, std::string* key) {
  if (b.has_heights()) return "";
  if (b.p_delta) {
    *key = "p_delta";
    return "P-Delta needs the storey heights: give height (every storey) or heights (a list) [m]";
  }
  if (collapse_given) {
    *key = "collapse_drift_ratio";
    return "the collapse check needs the storey heights: give height (every storey) or heights (a list) [m]";
  }
  return "";
}

std::string yield_forces_from_drift_ratio(Building* b, double ratio) {
  if (const std::string problem = bounded_problem(ratio, kDriftRatioRange); !problem.empty()) return problem;
  if (!b->has_heights())
    return "the yield drift ratio needs the storey heights: give height (every storey) or heights (a list) [m], or "
           "give the yield force (yield_force or yield_forces) instead";
  const int n = b->floors();
  Eigen::VectorXd forces(n);
  for (int i = 0; i < n; ++i) {
    if (!(b->springs[i] > 0.0))
      return "storey " + std::to_string(i + 1) + " has no spring to yield (give its stiffness)";
    forces[i] = b->springs[i] * ratio * b->heights[i];
    if (const std::string problem = kForceRange.problem(forces[i]); !problem.empty())
      return "storey " + std::to_string(i + 1) + "'s yield force k x ratio x h: " + problem;
  }
  b->hysteresis.yield_forces = forces;
  b->hysteresis.yield_drift_ratio = ratio;
  return "";
}

}  // namespace adjoin::structure
