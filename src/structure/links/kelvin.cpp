// A viscoelastic damper between the floors (a Kelvin-Voigt element, as the storey device
// `kelvin`): a spring k in parallel with a linear dashpot c, F = k s + c s'. Linear: k joins K0
// and the coupled periods, c joins C; its force is the linear family's; what its spring still
// holds at the end, k s^2 / 2, is not dissipated.
#include "link_parts.hpp"

namespace adjoin::structure {

const LinkKind& kelvin_link_kind() {
  using namespace links;
  static const LinkKind kind{
      .type = LinkType::kelvin,
      .what = "a viscoelastic damper: a spring k in parallel with a linear dashpot c",
      .keys = {{"stiffness", [](Link& l) -> double& { return l.k; }, true, 0.0, [](double v) { return bounded_problem(v, kStiffnessRange); }},
               {"c", [](Link& l) -> double& { return l.c; }, true, 0.0, [](double v) { return bounded_problem(v, kDashpotRange); }}},
      .own_keys = {},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = [](const Link& l) -> std::string {
        if (!positive(l.k)) return ".stiffness must be positive (N/m)";
        if (!positive(l.c)) return ".c must be positive (N s/m)";
        return "";
      },
      .spring = [](const Link& l) { return l.k; },
      .dashpot = [](const Link& l) { return l.c; },
      .relaxed = [](const Link& l) { return l.k; },
      .family = [](const Link&) { return LinkFamily::linear; },
      .dissipated = [](const Link& l, double work, double, double stroke) { return work - 0.5 * l.k * stroke * stroke; },
      .summary = {{"stiffness", [](const Link& l) { return l.k; }}, {"c", [](const Link& l) { return l.c; }}},
  };
  return kind;
}

}  // namespace adjoin::structure
