#pragma once
// The structure as data (SPEC §5): buildings A and B side by side on the same ground, their
// storeys and storey devices, inherent damping, and the links and contacts between floors.
// Plain values in SI units, sized at run time; no file formats, no numerics beyond checking.
//
// Floors are numbered 1..n from the bottom (the ground is floor 0); storey i joins floor i-1
// to floor i. A storey's static stiffness is its spring plus the relaxed stiffness k of its
// fractional Zener devices (the paper's storey is a Zener device alone, spring 0).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "adjoin/structure/contact.hpp"

namespace adjoin::structure {

// f + tau_f D^order f = k (d + tau_x D^order d): the paper's rod. 0 < order < 1,
// tau_x > tau_f > 0 (tau in s^order), k > 0.
struct Zener {
  double k = 0.0, order = 0.5, tau_x = 0.0, tau_f = 0.0;
};

// DeviceType (spring, dashpot, zener, bilinear): core/enum_names.hpp.
// A device in parallel with the spring of each listed storey (1-based).
struct StoreyDevice {
  DeviceType type = DeviceType::spring;
  std::vector<int> storeys;
  double k = 0.0;  // spring, bilinear (initial stiffness) [N/m]
  double c = 0.0;  // dashpot [N (s/m)^alpha]
  Zener zener;
  double yield_force = 0.0, hardening = 0.0;  // bilinear (a metallic damper, a BRB): F_y [N], b in [0, 1)
  double n = 2.0, beta = 0.5, gamma = 0.5;     // bouc-wen (with yield_force, hardening): as StoreyHysteresis
  double alpha = 1.0;  // dashpot: F = c |v|^alpha sign v, 0 < alpha <= 1 (1: linear)
};

// A storey spring's own law (SPEC §7; HysteresisModel: core/enum_names.hpp): elastic, or
// bilinear with kinematic hardening, force = b k d + (1 - b) k z, z the elastic-perfectly-
// plastic part (|z| <= F_y / k): the spring b k in parallel with the spring (1 - b) k in
// series with a Coulomb slider of slip force (1 - b) F_y. The inherent damping stays that of
// the initial stiffness k (static_stiffness()).
struct StoreyHysteresis {
  HysteresisModel model = HysteresisModel::elastic;
  Eigen::VectorXd yield_forces;  // bilinear: F_y per storey [N], bottom up
  double hardening = 0.0;        // b, in [0, 1)
  // bouc-wen: force = b k d + (1 - b) k z, z' = d' - beta'|d'||z|^(n-1) z - gamma' d' |z|^n,
  // beta' = beta / u_y^n, gamma' = gamma / u_y^n, u_y = F_y / k (n > 0, beta + gamma > 0).
  double n = 2.0, beta = 0.5, gamma = 0.5;
  // > 0 when the law was given by its yield drift ratio: yield_forces are then k_i x ratio x h_i
  // (yield_forces_from_drift_ratio, structure/rules.hpp); 0 when the forces were given.
  double yield_drift_ratio = 0.0;
};

// Classical damping from the building's mass and elastic (static) stiffness.
// DampingModel (none, modal, rayleigh): core/enum_names.hpp.
struct InherentDamping {
  DampingModel model = DampingModel::none;
  double ratio = 0.0;          // modal: every mode; rayleigh: at the two modes below
  int mode_i = 1, mode_j = 2;  // rayleigh: 1-based mode numbers
};

// An isolated base (SPEC §7): a base floor of mass m_b under floor 1 that slides on the ground
// with Coulomb friction mu W (W = g x the mass of the base and every floor above; stick exact),
// a flat slider, or a friction pendulum that adds the restoring stiffness W / R between the
// base and the ground. Storey 1 joins the base to floor 1; the floors' displacements stay
// relative to the ground.
struct Base {
  double mass = 0.0;  // m_b [kg]
  BaseModel model = BaseModel::flat_slider;
  double friction = 0.0;  // mu, of the total weight W
  double radius = 0.0;    // friction-pendulum: R [m]
};

struct Building {
  std::string name;               // "A" or "B"
  Eigen::VectorXd masses;         // floor masses [kg], bottom up
  Eigen::VectorXd springs;        // storey springs [N/m], bottom up (0 where only devices stiffen)
  std::vector<StoreyDevice> devices;
  InherentDamping damping;
  // Storey heights [m], bottom up; empty when not given (SPEC §7). With them: the drift ratios
  // (channels X.drift_ratioN = drift / h_N), P-Delta and the collapse check.
  Eigen::VectorXd heights;
  // P-Delta: each storey i gets the linear geometric stiffness -P_i/h_i, P_i = g x the mass of
  // floors i..n (constant). Needs heights. The inherent damping stays that of K0 without it.
  bool p_delta = false;
  // Collapse (an outcome, not an error): the run stops when a storey's |drift / h| exceeds this.
  // Checked only with heights.
  double collapse_drift_ratio = 0.10;

  StoreyHysteresis hysteresis;
  std::optional<Base> base;  // an isolated base (SPEC §7), or none: a fixed base
  // A Coulomb slider between floor 1 and the ground, in parallel with storey 1: its slip force
  // [N], 0 for none (the two-block scene's model.base_friction: each block on its base with
  // friction mu_b m_i g, SPEC §7). Not with an isolated base.
  double ground_friction = 0.0;

  int floors() const { return static_cast<int>(masses.size()); }
  bool has_heights() const { return heights.size() > 0; }
  // Spring plus the relaxed stiffness of each storey's Zener devices and springs (and the
  // initial stiffness of bilinear devices).
  Eigen::VectorXd static_stiffness() const;
  // Per storey, the P-Delta geometric stiffness -P_i/h_i [N/m]; zeros without p_delta.
  Eigen::VectorXd geometric_stiffness() const;
  // An isolated base's slip force mu W and pendulum stiffness W / R (0 for a flat slider).
  double base_slip_force() const;
  double base_stiffness() const;
  // Whether its storeys can yield (a hysteresis law, or a device that is not a spring, a dashpot
  // or a Zener element): its periods are then those of the initial stiffness (SPEC §7).
  bool yields() const;
};

// LinkType (friction, dashpot, spring, zener): core/enum_names.hpp.
// Between floor_a of A and floor_b of B; its force acts as -q on A's floor and +q on B's.
struct Link {
  LinkType type = LinkType::friction;
  int floor_a = 1, floor_b = 1;
  double slip_force = 0.0;  // friction [N]
  double c = 0.0, k = 0.0;  // dashpot [N (s/m)^alpha], spring [N/m]
  Zener zener;
  double alpha = 1.0;       // dashpot: F = c |v|^alpha sign v, 0 < alpha <= 1 (1: linear)
};

// A pounding pair: clear gap at rest [m] between floor_a of A and floor_b of B, and what
// happens when it closes (SPEC §6; law.model none: nothing, the floors pass through).
// The gap is g = gap - s, s = x_A,i - x_B,j; a contact force p >= 0 acts as -p on A's floor
// and +p on B's, as a link's force does.
struct Contact {
  int floor_a = 1, floor_b = 1;
  double gap = 0.0;
  ContactLaw law;
};

// A friction damper between a dof and the ground (SPEC §7): an isolated base's slider (mu W
// under the base) or a building's ground_friction (under floor 1). Its force acts -q on the dof.
struct GroundSlider {
  char building = 'A';
  bool base = true;  // an isolated base's slider; false: ground_friction under floor 1
  int dof = 0;
  double slip_force = 0.0;  // [N]
};

struct Structure {
  Building a;
  std::optional<Building> b;
  std::vector<Link> links;
  std::vector<Contact> contacts;

  // The floors, then the isolated bases (SPEC §7): each base is one more dof after every floor
  // (A's base, then B's), so the floors keep their indices and every reader of A's and B's
  // floors (channels, links, contacts, the two blocks) is unchanged; only storey 1 of an
  // isolated building looks at its base instead of the ground (below()).
  int dofs() const { return a.floors() + (b ? b->floors() : 0) + (a.base ? 1 : 0) + (b && b->base ? 1 : 0); }
  // The index of floor `floor` (1-based) of building "A" or "B" in the stacked state; floor 0
  // is its base (base_dof).
  int dof(char building, int floor) const {
    if (floor == 0) return base_dof(building);
    return building == 'A' ? floor - 1 : a.floors() + floor - 1;
  }
  // The index of a building's base, or -1 (a fixed base: the ground).
  int base_dof(char building) const {
    const int floors = a.floors() + (b ? b->floors() : 0);
    if (building == 'A') return a.base ? floors : -1;
    return b && b->base ? floors + (a.base ? 1 : 0) : -1;
  }
  // The dof under storey `storey` (1-based): the floor below, the base, or -1 (the ground).
  int below(char building, int storey) const { return storey > 1 ? dof(building, storey - 1) : base_dof(building); }
  // The friction dampers to the ground, A's then B's: the solver puts each after the links in
  // the state's link arrays (StructureState::link_force[links.size() + k]).
  std::vector<GroundSlider> ground_sliders() const;
  // Why the structure is not valid (sizes, ranges, floors out of range), with the field path
  // ("building.A.masses[3]", "link[2].floors"), or true.
  bool IsValid(std::string* error) const;
};

// The uniform storey stiffness that gives a building the fundamental period `period` [s]
// (with its masses, and no other stiffness): exact, from the first eigenvalue at unit
// stiffness.
double stiffness_for_period(const Eigen::VectorXd& masses, double period);

}  // namespace adjoin::structure
