// A fractional Zener damper between the floors (the paper's rod as a link): its relaxed
// stiffness k counts in the coupled periods; the solver steps it with its history.
#include "link_parts.hpp"

namespace adjoin::structure {

const LinkKind& zener_link_kind() {
  using namespace links;
  static const LinkKind kind{
      .type = LinkType::zener,
      .what = "a fractional Zener damper",
      .keys = {{"stiffness", [](Link& l) -> double& { return l.zener.k; }, true, 0.0,
                [](double v) { return bounded_problem(v, kStiffnessRange); }},
               {"order", [](Link& l) -> double& { return l.zener.order; }, true, 0.0, zener_order_problem},
               {"tau_f", [](Link& l) -> double& { return l.zener.tau_f; }, true, 0.0, [](double v) { return bounded_problem(v, kTauRange); }},
               {"tau_x", [](Link& l) -> double& { return l.zener.tau_x; }, true, 0.0, [](double v) { return bounded_problem(v, kTauRange); }}},
      .own_keys = {},
      .joint_problem = [](const Link& l) { return zener_tau_problem(l.zener.tau_x, l.zener.tau_f); },
      .joint_keys = {"tau_x"},
      .invalid = [](const Link& l) -> std::string {
        const std::string p = zener_check(l.zener);
        return p.empty() ? "" : ": " + p;
      },
      .spring = none,
      .dashpot = none,
      .relaxed = [](const Link& l) { return l.zener.k; },
      .family = [](const Link&) { return LinkFamily::zener; },
      .dissipated = [](const Link&, double work, double force, double stroke) { return work - 0.5 * force * stroke; },
      .summary = {},
  };
  return kind;
}

}  // namespace adjoin::structure
