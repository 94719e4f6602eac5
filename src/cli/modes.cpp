// adjoin modes SCENE [--set K=V]...
//
// The modal analysis a run starts from (SPEC §5), alone: each building's natural periods,
// frequencies, modal damping ratios (inherent, from devices, total; Zener storeys by their
// complex stiffness at the mode's frequency) and mass-normalised mode shapes; the coupled
// system's periods with the friction links free and locked. A two-block scene (SPEC §3) is
// the structure of one floor per building, a Zener storey each, one friction link.
#include <cstdio>
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
};

void print_building(const structure::Building& b, const char* time_unit) {
  const structure::Modes m = structure::building_modes(b);
  std::printf("building %s: %d storeys, total mass %.6g\n", b.name.c_str(), b.floors(), b.masses.sum());
  std::printf("  %4s %12s %12s %10s %10s %10s %10s\n", "mode", (std::string("period [") + time_unit + "]").c_str(),
              (std::string("freq [") + (time_unit[0] == 's' ? "Hz" : "1/T0") + "]").c_str(), "inherent", "devices", "total", "zener K'");
  for (int j = 0; j < m.omega.size(); ++j)
    std::printf("  %4d %12.6g %12.6g %10.4f %10.4f %10.4f %10.4f\n", j + 1, m.periods[j], 1.0 / m.periods[j],
                m.inherent_ratio[j], m.device_ratio[j], m.total_ratio[j], m.zener_stiffening[j]);
  std::printf("  mode shapes (mass-normalised; floor 1 first):\n");
  for (int j = 0; j < m.omega.size() && j < 6; ++j) {
    std::printf("  %4d", j + 1);
    for (int i = 0; i < m.shapes.rows(); ++i) std::printf(" %10.4g", m.shapes(i, j));
    std::printf("\n");
  }
}

int modes_command(const ModesArgs& args) {
  structure::Structure s;
  const char* time_unit = "s";
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
    if (!scene.scales.si) time_unit = "T0";
  }
  print_building(s.a, time_unit);
  if (s.b) print_building(*s.b, time_unit);
  if (s.b) {
    const structure::CoupledModes c = structure::coupled_modes(s);
    std::printf("coupled system: periods [%s] with the friction links free | locked\n", time_unit);
    for (int j = 0; j < c.periods_free.size() || j < c.periods_locked.size(); ++j) {
      std::printf("  %4d", j + 1);
      if (j < c.periods_free.size()) std::printf(" %12.6g", c.periods_free[j]); else std::printf(" %12s", "");
      if (j < c.periods_locked.size()) std::printf(" %12.6g", c.periods_locked[j]);
      std::printf("\n");
    }
  }
  return 0;
}

const Registration registration(15, [](CLI::App& app) -> Runner {
  auto args = std::make_shared<ModesArgs>();
  auto* sub = app.add_subcommand("modes", "Natural periods, modal damping ratios and mode shapes of a scene's structure");
  sub->add_option("scene", args->scene, "Scene file (TOML)")->required();
  sub->add_option("--set", args->overrides, "Override a scene key by dotted path, e.g. --set building.B.period=0.6")
      ->allow_extra_args(false);
  sub->add_option("--unset", args->unsets, "Remove a scene key or section first, e.g. --unset link.1")->allow_extra_args(false);
  return [args]() { return modes_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
