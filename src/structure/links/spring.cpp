// A linear spring between the floors: its k joins K0 and the coupled periods.
#include "link_parts.hpp"

namespace adjoin::structure {

const LinkKind& spring_link_kind() {
  using namespace links;
  static const LinkKind kind{
      .type = LinkType::spring,
      .what = "a linear spring",
      .keys = {{"stiffness", [](Link& l) -> double& { return l.k; }, true, 0.0,
                [](double v) { return bounded_problem(v, kStiffnessRange); }}},
      .own_keys = {},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = [](const Link& l) -> std::string { return positive(l.k) ? "" : ".stiffness must be positive (N/m)"; },
      .spring = [](const Link& l) { return l.k; },
      .dashpot = none,
      .relaxed = [](const Link& l) { return l.k; },
      .family = [](const Link&) { return LinkFamily::linear; },
      .dissipated = [](const Link&, double, double, double) { return 0.0; },  // (elastic: it holds it all)
      .summary = {},
  };
  return kind;
}

}  // namespace adjoin::structure
