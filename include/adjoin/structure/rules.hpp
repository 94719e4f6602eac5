#pragma once
// The engineering rules of a structure (SPEC §5), in one place for every way of describing
// one: a scene file's reader (io/structure_file.hpp) and the typed builder
// (structure/builder.hpp) apply these same functions, so a value one accepts the other does.
//
// Each check returns what is wrong in words ("" when nothing is), without naming the field:
// the caller names it its own way (a scene's file:line and key, the builder's field path
// "building.A.period", "link[1].slip_force").
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "adjoin/structure/parameters.hpp"
#include "adjoin/structure/building.hpp"

namespace adjoin::structure {

// The range a building quantity may take. The bounds are the two-block scenes' (masses
// 1e-3..1e12 kg, stiffnesses 1e-3..1e15 N/m, relaxation times up to 1e12): inside them the
// step's matrices M + h/2 C + h^2/4 K stay finite and every reported force and energy too
// (1e15 N/m x a metre, 1e12 kg x (1e3 m/s)^2), where 1e300 overflowed only at the end of a run.
struct Range {
  double lo, hi;
  const char* unit;
  const char* why = "bounds that keep the step's matrices finite and well conditioned";
  // "" inside the range, else the value and the supported range.
  std::string problem(double v) const;
};
inline constexpr Range kMassRange{1e-3, 1e12, "kg"};
inline constexpr Range kStiffnessRange{1e-3, 1e15, "N/m"};
inline constexpr Range kDashpotRange{1e-3, 1e15, "N s/m"};
// A nonlinear viscous damper's exponent (F = c |v|^alpha sign v): fluid viscous dampers have
// 0.2-1; below 0.05 the law is a friction damper's in all but name (use one).
inline constexpr Range kAlphaRange{0.05, 1.0, "(exponent)", "F = c |v|^alpha sign v: 1 is the linear dashpot, fluid dampers 0.2-1"};
inline constexpr Range kForceRange{1e-3, 1e18, "N"};
inline constexpr Range kSlipRatioRange{1e-9, 1e6, "(slip force / weight)"};
inline constexpr Range kTauRange{1e-9, kMaxRelaxationTime, "s^order"};
// Stiff Hertz contacts of 1e15-1e16 are real (steel on concrete); 1e300 only overflows.
inline constexpr double kMaxContactStiffness = 1e20;  // N/m or N/m^1.5
// tau_x / tau_f: the Zener element's unrelaxed stiffness over its relaxed one.
inline constexpr double kMaxTauRatio = kMaxRatio;
inline constexpr int kMaxStoreys = 200;
// Storey heights (SPEC §7) and the collapse drift ratio (|drift| / height).
inline constexpr Range kHeightRange{1e-3, 1e4, "m"};
inline constexpr Range kDriftRatioRange{1e-9, 1e3, "(drift / height)"};

// A number as messages show it (6 significant digits).
std::string number_text(double v);

// A positive value within `range`: "expected a positive number", the range's problem, or "".
std::string bounded_problem(double v, const Range& range);
// A Zener element's order in (0, 1).
std::string zener_order_problem(double order);
// tau_x > tau_f (the second law) and tau_x / tau_f within kMaxTauRatio; tau_x is the field
// to blame.
std::string zener_tau_problem(double tau_x, double tau_f);
// Every rule of a Zener element, in the order a scene's keys are read: the field ("stiffness",
// "order", "tau_f", "tau_x") and the problem, or {"", ""}.
std::pair<std::string, std::string> zener_problem(const Zener& z);
// An inherent damping ratio in [0, 1).
std::string damping_ratio_problem(double ratio);
// Rayleigh damping's two modes, different and within the building's n modes.
std::string rayleigh_modes_problem(int mode_i, int mode_j, int n);
// A contact stiffness within kMaxContactStiffness (in `unit`).
std::string contact_stiffness_problem(double k, const std::string& unit);

// A storey device's storeys: at least one, each once, each a storey 1..n.
std::string device_storeys_problem(const std::vector<int>& storeys, int n);
// A link's or contact pair's floor of building `name` ('A' or 'B'), within its floors.
std::string floor_problem(char name, int floor, const Building& b);

// Period -> stiffness. The uniform storey spring that gives a building of these floor masses
// (and no other stiffness) the fundamental period `period` [s]; it must lie within
// kStiffnessRange, else *problem says the periods that do for these masses (the stiffness
// goes as 1 / period^2) and 0 is returned.
double stiffness_for_period_in_range(const Eigen::VectorXd& masses, double period, std::string* problem);
// The same for a building with storey devices: the uniform spring that, with the devices'
// relaxed stiffness, gives `building` the period (by bisection from `enough`, a spring that
// alone gives a shorter period: the period falls as the spring grows). *problem when the
// devices alone already give a shorter period.
double spring_for_period_with_devices(const Building& building, double period, double enough, std::string* problem);

// Slip ratio -> slip force: a fraction of a building's weight, ratio x (sum of its floor
// masses) x g [N].
double slip_force_from_ratio(double ratio, const Building& of);

// Storey heights, drift ratios and P-Delta (SPEC §7) as a building's keys combine them: p_delta
// and collapse_drift_ratio need the heights. "" or the problem, and the key to blame in *key.
std::string heights_problem(const Building& b, bool collapse_given, std::string* key);

// A bilinear storey law given by its yield drift ratio (SPEC §7): sets each storey's yield force
// F_y,i = k_i x ratio x h_i (k_i the storey spring's initial stiffness, h_i its height), so that
// the spring yields when its drift ratio reaches `ratio`. Needs the heights and a spring in
// every storey, so call it once both are final (after a period was turned into springs).
// "" or the problem.
std::string yield_forces_from_drift_ratio(Building* b, double ratio);

// A bilinear or Bouc-Wen law's post-yield stiffness ratio b, in [0, 1) (0: elastic-perfectly-
// plastic; 1 would be no yielding at all).
std::string hardening_problem(double b);
// A Bouc-Wen law's shape (SPEC §7): the exponent n in [1, 20] (below 1, |z|^(n-1) and so the
// implicit step's derivative are unbounded at z = 0), and beta + gamma > 0 (else z never
// saturates: the law never yields).
std::string bouc_wen_exponent_problem(double n);
std::string bouc_wen_shape_problem(double beta, double gamma);

// An isolated base (SPEC §7): its mass [kg] (positive, within kMassRange), its friction
// coefficient mu in (0, 1) (of the weight of the base and every floor above) and a friction
// pendulum's radius of curvature R > 0 [m].
std::string base_mass_problem(double kg);
std::string base_friction_problem(double mu);
std::string base_radius_problem(double m);

// The storey that has no static stiffness (no spring and no spring or Zener device), as
// "storey i has no stiffness: ...", or "".
std::string storey_stiffness_problem(const Building& b);

}  // namespace adjoin::structure
