// A dashpot between the floors, F = c |v|^alpha sign v (SPEC §7): linear (alpha = 1) in C;
// nonlinear a viscous element the solver steps on its own (solver/viscous_step.hpp).
#include "link_parts.hpp"

namespace adjoin::structure {

const LinkKind& dashpot_link_kind() {
  using namespace links;
  static const LinkKind kind{
      .type = LinkType::dashpot,
      .what = "a dashpot, F = c |v|^alpha sign v",
      .keys = {{"c", [](Link& l) -> double& { return l.c; }, true, 0.0, [](double v) { return bounded_problem(v, kDashpotRange); }},
               {"alpha", [](Link& l) -> double& { return l.alpha; }, false, 1.0, alpha_problem}},
      .own_keys = {},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = [](const Link& l) -> std::string {
        if (!positive(l.c)) return ".c must be positive (N s/m)";
        if (!(l.alpha >= kAlphaRange.lo && l.alpha <= kAlphaRange.hi)) return ".alpha must lie in [0.05, 1] (F = c |v|^alpha sign v)";
        return "";
      },
      .spring = none,
      .dashpot = [](const Link& l) { return l.alpha == 1.0 ? l.c : 0.0; },
      .relaxed = none,
      .family = [](const Link& l) { return l.alpha == 1.0 ? LinkFamily::linear : LinkFamily::viscous; },
      .dissipated = all_of_it,
      .summary = {{"c", [](const Link& l) { return l.c; }}, {"alpha", [](const Link& l) { return l.alpha; }}},
  };
  return kind;
}

}  // namespace adjoin::structure
