// adjoin modes SCENE [--set K=V]... [--modes N]
//
// The modal analysis a run starts from (SPEC §5), alone: each building's natural periods,
// frequencies, modal damping ratios (inherent, from devices, total; Zener storeys by their
// complex stiffness at the mode's frequency), participation factors, effective modal masses
// (and their share of the total mass, cumulated) and mode shapes scaled to 1 at the roof, for
// every mode or the first N; the coupled system's periods with the friction links free and
// locked (with P-Delta, SPEC §7: of the tangent K0 + K_G, and said so; a building whose storeys
// yield: of the initial stiffness, and said so; an isolated building: its friction pendulum's
// isolated period 2 pi sqrt(R/g) beside them, or that a flat slider has none). Every number has its unit. A two-block scene (SPEC §3) is the structure of one floor
// per building, a Zener storey each, one friction link (dimensionless: time in T0, mass in m1).
#include <algorithm>
#include <cstdio>
#include <string>
#include <memory>

#include "adjoin/io/scene.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/structure/modal.hpp"
#include "command.hpp"

namespace adjoin::cli {
namespace {

struct ModesArgs {
  std::string scene;
  std::vector<std::string> overrides, unsets;
  int modes = 0;  // how many modes to show per building (0: all)
};

// The units the numbers are printed in: SI, or the two-block scene's dimensionless units
// (time in T0, mass in m1, block A's mass).
struct Units {
  std::string time = "s", frequency = "Hz", mass = "kg";
};

std::string bracketed(const std::string& what, const std::string& unit) { return what + " [" + unit + "]"; }

// An isolated base (SPEC §7): the period of a friction pendulum while it slides, or why a flat
// slider has none; the table below is the fixed-base superstructure's (the base stuck).
void print_base(const structure::Building& b, const Units& u) {
  const structure::Base& base = *b.base;
  std::printf("  isolated base (%s, mu = %.4g, base mass %.6g %s): it slides when the force holding it to the ground would exceed mu W = %.6g N "
              "(W the weight of the base and the floors)\n",
              structure::to_string(base.model).c_str(), base.friction, base.mass, u.mass.c_str(), b.base_slip_force());
  if (base.model == structure::BaseModel::friction_pendulum) {
    const structure::IsolatedPeriod p = structure::isolated_period(b);
    std::printf("    isolated period 2 pi sqrt(R/g) = %.6g %s (R = %.4g m; the superstructure rigid), %.6g %s with the storeys' "
                "initial stiffness on the pendulum's W/R = %.6g N/m\n",
                p.rigid, u.time.c_str(), base.radius, p.flexible, u.time.c_str(), b.base_stiffness());
  } else {
    std::printf("    no isolated period: a flat slider has no restoring force (the base stops wherever it sticks)\n");
  }
  std::printf("    the periods below are the fixed-base superstructure's: the building's while its base sticks\n");
}

void print_building(const structure::Building& b, const Units& u, int shown) {
  const structure::Modes m = structure::building_modes(b);
  const int n = static_cast<int>(m.omega.size());
  const int count = shown > 0 ? std::min(shown, n) : n;
  const double total = b.masses.sum();
  std::printf("building %s: %d storey%s, total mass %.6g %s; %d of %d mode%s shown\n", b.name.c_str(), b.floors(),
              b.floors() == 1 ? "" : "s", total, u.mass.c_str(), count, n, n == 1 ? "" : "s");
  if (m.p_delta)
    std::printf("  with P-Delta: periods and shapes of K0 + K_G (each storey's geometric stiffness -P_i/h_i, P_i the weight "
                "it carries); inherent damping from K0; a period inf is a mode the gravity load makes unstable\n");
  if (b.yields())
    std::printf("  yielding storeys: periods, shapes and damping ratios of the initial (elastic) stiffness; they hold until "
                "a storey yields, and the inherent damping stays the initial stiffness's throughout the run\n");
  if (b.base) print_base(b, u);
  std::printf("  %4s %12s %12s %12s %12s %12s %12s %14s %16s %12s %12s\n", "mode", bracketed("period", u.time).c_str(),
              bracketed("freq", u.frequency).c_str(), "inherent [-]", "devices [-]", "total [-]", "zener K' [-]",
              "Gamma_roof [-]", bracketed("eff. mass", u.mass).c_str(), "eff. [%]", "cumul. [%]");
  double cumulative = 0.0;
  for (int j = 0; j < count; ++j) {
    const double share = 100.0 * m.effective_mass[j] / total;
    cumulative += share;
    std::printf("  %4d %12.6g %12.6g %12.4f %12.4f %12.4f %12.4f %14.4f %16.6g %12.2f %12.2f\n", j + 1, m.periods[j],
                1.0 / m.periods[j], m.inherent_ratio[j], m.device_ratio[j], m.total_ratio[j], m.zener_stiffening[j],
                m.participation[j], m.effective_mass[j], share, cumulative);
  }
  std::printf("  damping ratios [-] (0.05 is 5 %%); Gamma_roof: the participation factor of the shape scaled to 1 at the roof\n");
  std::printf("  mode shapes [-] (scaled to 1 at the roof; floor 1 first):\n");
  for (int j = 0; j < count; ++j) {
    std::printf("  %4d", j + 1);
    const double roof = m.shapes(m.shapes.rows() - 1, j);
    for (int i = 0; i < m.shapes.rows(); ++i) std::printf(" %10.4g", m.shapes(i, j) / roof);
    std::printf("\n");
  }
}

int modes_command(const ModesArgs& args) {
  structure::Structure s;
  Units units;
  if (is_building_scene(args.scene)) {
    for (const auto& o : args.overrides)
      if (!is_structure_key(o.substr(0, o.find('='))))
        throw InputError("--set " + text_excerpt(o) + ": adjoin modes reads only the structure (building.*, link.*, contact.*)");
    for (const auto& u : args.unsets)
      if (!is_structure_key(u))
        throw InputError("--unset " + text_excerpt(u) + ": adjoin modes reads only the structure (building.*, link.*, contact.*)");
    s = parse_structure(read_text_file(args.scene, "scene"), args.scene, args.overrides, args.unsets);
  } else {
    const Scene scene = load_scene(args.scene, args.overrides, args.unsets);
    s = structure_of(scene);
    if (!scene.scales.si) units = Units{"T0", "1/T0", "m1"};
  }
  print_building(s.a, units, args.modes);
  if (s.b) print_building(*s.b, units, args.modes);
  if (s.b) {
    const structure::CoupledModes c = structure::coupled_modes(s);
    std::printf("coupled system: periods [%s] with the friction links free | locked\n", units.time.c_str());
    for (int j = 0; j < c.periods_free.size() || j < c.periods_locked.size(); ++j) {
      std::printf("  %4d", j + 1);
      if (j < c.periods_free.size()) std::printf(" %12.6g", c.periods_free[j]); else std::printf(" %12s", "");
      if (j < c.periods_locked.size()) std::printf(" %12.6g", c.periods_locked[j]);
      std::printf("\n");
    }
  }
  return 0;
}

const Registration registration(15, "modes", "Natural periods, modal damping ratios and mode shapes of a scene's structure",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<ModesArgs>();
  sub->add_option("scene", args->scene, "Scene file (TOML)")->required();
  sub->add_option("--set", args->overrides, "Override a scene key by dotted path, e.g. --set building.B.period=0.6")
      ->allow_extra_args(false);
  sub->add_option("--modes", args->modes, "How many modes to show for each building (default: all)")
      ->check(CLI::Range(1, 1000000));
  sub->add_option("--unset", args->unsets, "Remove a scene key or section first, e.g. --unset link.1")->allow_extra_args(false);
  return [args]() { return modes_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
