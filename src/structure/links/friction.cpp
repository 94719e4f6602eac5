// A Coulomb friction damper between the floors, q in F_s Sign(s') (SPEC §5): the non-smooth
// step holds its stick exactly. Its slip force is given in N or as a fraction of a building's
// weight (slip_ratio with of): a rule io applies itself (own_keys).
#include "link_parts.hpp"

namespace adjoin::structure {

const LinkKind& friction_link_kind() {
  using namespace links;
  static const LinkKind kind{
      .type = LinkType::friction,
      .what = "a Coulomb friction damper",
      .keys = {},
      .own_keys = {"slip_force", "slip_ratio", "of"},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = [](const Link& l) -> std::string { return positive(l.slip_force) ? "" : ".slip_force must be positive (N)"; },
      .spring = none,
      .dashpot = none,
      .relaxed = none,
      .family = [](const Link&) { return LinkFamily::friction; },
      .dissipated = all_of_it,
      .summary = {{"slip_force", [](const Link& l) { return l.slip_force; }}},
  };
  return kind;
}

}  // namespace adjoin::structure
