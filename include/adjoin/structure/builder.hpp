#pragma once
// A structure described in code (SPEC §5), the way an engineer describes it: storey count,
// floor masses, storey stiffnesses or a fundamental period, inherent damping, storey devices,
// links and contacts at chosen floor pairs. Each setter checks its value by the rules a scene
// file's reader applies (structure/rules.hpp, structure/contact_rules.hpp), and build() checks
// what needs the whole (sizes, floors, a period with devices, a slip ratio's weight).
//
//     structure::StructureBuilder s;
//     s.building('A', 5).mass(45.0e3).stiffness(5.482e6).modal_damping(0.05);
//     s.building('B', 3).masses({60e3, 60e3, 50e3}).period(0.5);
//     s.friction_link_ratio(3, 3, 0.05, 'B');
//     s.contact(3, 3, 0.05).model(structure::ContactModel::linear).stiffness(2e9).restitution(0.65);
//     structure::Structure structure = s.build();
//
// Errors are FieldError (adjoin/core/errors.hpp) naming the field by its path, counted from 1 as a
// scene's tables are: "building.A.period", "building.A.masses[3]", "building.A.device[1].tau_x",
// "building.B.base.friction", "link[2].slip_force", "contact[1].restitution". SI units throughout.
#include <deque>
#include <optional>
#include <map>
#include <string>
#include <vector>

#include "adjoin/structure/building.hpp"

namespace adjoin::structure {

// A Bouc-Wen law's shape (SPEC §7): z' = d' - beta'|d'||z|^(n-1) z - gamma' d' |z|^n.
struct BoucWenShape {
  double n = 2.0, beta = 0.5, gamma = 0.5;
};

class BuildingBuilder {
 public:
  // `name` 'A' (the left building) or 'B'; 1 to kMaxStoreys storeys.
  BuildingBuilder(char name, int storeys);

  // Floor masses [kg]: one for every floor, or a list bottom up (one per floor). Of two ways
  // of giving the same thing (mass, masses; stiffness, stiffnesses, period) the last counts.
  BuildingBuilder& mass(double kg);
  BuildingBuilder& masses(const std::vector<double>& kg);
  // Storey stiffness [N/m]: one for every storey, a list bottom up (0 where the storey's devices
  // alone stiffen it), or instead the fundamental period [s]: a uniform storey spring is found
  // that gives it (with the devices' relaxed stiffness, when the building has devices).
  BuildingBuilder& stiffness(double n_per_m);
  BuildingBuilder& stiffnesses(const std::vector<double>& n_per_m);
  BuildingBuilder& period(double seconds);
  // Inherent (classical) damping: none (the default), one ratio for every mode, or Rayleigh's
  // fitted at two modes (1-based).
  BuildingBuilder& no_damping();
  BuildingBuilder& modal_damping(double ratio);
  BuildingBuilder& rayleigh_damping(double ratio, int mode_i = 1, int mode_j = 2);
  // A device of any kind (structure/device_kinds.hpp) in parallel with the spring of each
  // listed storey (1-based, each once), by its scene keys: device(DeviceType::dashpot, {1, 2},
  // {{"c", 1e5}, {"alpha", 0.5}}). Each value is checked as a scene's; a key the kind does not
  // take, or a required one left out, is a FieldError. The typed calls below use it.
  BuildingBuilder& device(DeviceType type, const std::vector<int>& storeys, const std::map<std::string, double>& values);
  BuildingBuilder& spring(const std::vector<int>& storeys, double k);
  // alpha: F = c |v|^alpha sign v (1: the linear dashpot; c in N (s/m)^alpha).
  BuildingBuilder& dashpot(const std::vector<int>& storeys, double c, double alpha = 1.0);
  BuildingBuilder& zener(const std::vector<int>& storeys, const Zener& z);
  // Storey heights [m] (SPEC §7): one for every storey, or a list bottom up. With them the
  // drift ratios are channels and a storey whose |drift / h| passes collapse_drift_ratio
  // (default 0.10) stops the run (collapse, an outcome). P-Delta (each storey's geometric
  // stiffness -P_i/h_i) and collapse_drift_ratio need the heights (checked by build()).
  BuildingBuilder& height(double m);
  BuildingBuilder& heights(const std::vector<double>& m);
  BuildingBuilder& p_delta(bool on);
  BuildingBuilder& collapse_drift_ratio(double ratio);
  // The storey springs' own law (SPEC §7): bilinear, kinematic hardening b in [0, 1) (0:
  // elastic-perfectly-plastic), yielding at F_y [N] (every storey), at F_y,i (a list bottom
  // up), or at a drift ratio: F_y,i = k_i x ratio x h_i with k_i the storey spring's initial
  // stiffness (needs the heights; checked by build(), after a period gave the springs).
  BuildingBuilder& bilinear(double yield_force, double hardening = 0.0);
  BuildingBuilder& bilinear_per_storey(const std::vector<double>& yield_forces, double hardening = 0.0);
  BuildingBuilder& bilinear_drift_ratio(double yield_drift_ratio, double hardening = 0.0);
  // Or Bouc-Wen's smooth law, yielding at the same three kinds of yield force, with its shape
  // (n in [1, 20], beta + gamma > 0; the defaults saturate z at u_y = F_y / k).
  BuildingBuilder& bouc_wen(double yield_force, double hardening = 0.0, BoucWenShape shape = {});
  BuildingBuilder& bouc_wen_per_storey(const std::vector<double>& yield_forces, double hardening = 0.0, BoucWenShape shape = {});
  BuildingBuilder& bouc_wen_drift_ratio(double yield_drift_ratio, double hardening = 0.0, BoucWenShape shape = {});
  // Yielding storey devices (a scene's type = "bilinear" / "bouc-wen"): a metallic damper or a
  // buckling-restrained brace of initial stiffness k [N/m], yield force F_y [N], hardening b.
  BuildingBuilder& bilinear_device(const std::vector<int>& storeys, double k, double yield_force, double hardening = 0.0);
  BuildingBuilder& bouc_wen_device(const std::vector<int>& storeys, double k, double yield_force, double hardening = 0.0,
                                   BoucWenShape shape = {});
  // An isolated base under floor 1 (SPEC §7; a scene's [building.X.base]): a base floor of mass
  // m_b [kg] sliding on the ground with friction mu in (0, 1) of the weight of the base and every
  // floor above, on a flat slider, or on a friction pendulum of radius R [m] that adds the
  // restoring stiffness W / R (isolated period 2 pi sqrt(R / g)). The last call counts.
  BuildingBuilder& flat_slider(double base_mass, double friction);
  BuildingBuilder& friction_pendulum(double base_mass, double friction, double radius);

  const std::string& path() const { return path_; }  // "building.A"
  int storeys() const { return b_.floors(); }
  // The building, every storey stiff (its spring or its devices).
  Building build() const;

 private:
  void add_device(StoreyDevice device, const std::vector<int>& storeys);
  // A yielding storey law (bilinear or Bouc-Wen): its forces (one per storey) or, when null,
  // its yield drift ratio; the shape is checked for Bouc-Wen only.
  BuildingBuilder& hysteresis(HysteresisModel model, const std::vector<double>* yield_forces, double yield_drift_ratio,
                              double hardening, const BoucWenShape& shape);
  BuildingBuilder& isolated_base(const Base& base);
  std::string device_path() const;  // the next device's

  std::string path_;
  Building b_;
  bool mass_given_ = false;
  std::string stiffness_given_;  // "stiffness", "stiffnesses" or "period": the one given
  double period_ = 0.0;
  bool collapse_given_ = false;
};

// A contact pair's law; the model's keys as a scene's [[contact]] takes them.
class ContactBuilder {
 public:
  ContactBuilder(std::string path, int floor_a, int floor_b, double gap);
  ContactBuilder& model(ContactModel model);
  ContactBuilder& stiffness(double k);      // N/m (linear) or N/m^1.5
  ContactBuilder& restitution(double e);    // 0 < e <= 1
  ContactBuilder& damping(double value);    // zeta, xi_bar or xi directly (instead of restitution)
  ContactBuilder& tension_cut(bool cut);    // linear only
  Contact build() const;

 private:
  std::string path_;
  Contact c_;
  std::optional<double> stiffness_, restitution_, damping_;
  std::optional<bool> tension_cut_;
};

class StructureBuilder {
 public:
  // Building A (the left one) or B (the right one, optional), made on the first call; a
  // second call with the same name returns the same builder (its storeys must agree).
  BuildingBuilder& building(char name, int storeys);

  // Links between floor_a of A and floor_b of B, numbered link[1], link[2], ... in the order
  // they are added. A friction link's slip force [N], or a fraction of building `of`'s weight.
  StructureBuilder& friction_link(int floor_a, int floor_b, double slip_force);
  StructureBuilder& friction_link_ratio(int floor_a, int floor_b, double slip_ratio, char of);
  // A link of any kind but friction (structure/link_kinds.hpp) by its scene keys:
  // link(LinkType::dashpot, 3, 3, {{"c", 2e5}, {"alpha", 0.5}}), each value checked as a
  // scene's; a key the kind does not take, or a required one left out, is a FieldError. The
  // typed calls below use it (a friction link: friction_link or friction_link_ratio).
  StructureBuilder& link(LinkType type, int floor_a, int floor_b, const std::map<std::string, double>& values);
  StructureBuilder& dashpot_link(int floor_a, int floor_b, double c, double alpha = 1.0);
  StructureBuilder& spring_link(int floor_a, int floor_b, double k);
  StructureBuilder& zener_link(int floor_a, int floor_b, const Zener& z);
  // A pounding pair with its clear gap at rest [m] >= 0; set its law on the builder returned
  // (no law: model none, the floors pass through).
  ContactBuilder& contact(int floor_a, int floor_b, double gap);

  Structure build() const;

 private:
  struct LinkEntry {
    Link link;
    std::optional<double> slip_ratio;  // friction, by weight
    char of = 'B';
  };
  std::string link_path() const;  // the next link's
  StructureBuilder& add_link(Link link);

  std::optional<BuildingBuilder> a_, b_;
  std::vector<LinkEntry> links_;
  std::deque<ContactBuilder> contacts_;  // a deque: the references handed out stay valid
};

}  // namespace adjoin::structure
