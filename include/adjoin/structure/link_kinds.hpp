#pragma once
// The link kinds (SPEC §5, §7) as one table, as the storey devices' (device_kinds.hpp): per kind
// its scene keys (the field each sets, its default, its check), how a link made in code is
// checked, and what it adds to the model — its linear spring (K0, the coupled periods), its
// linear dashpot (C) — and the step family the solver hands it to at assembly; and what its
// report holds: the part of its work it dissipates, the fields summary.json gives it.
//
// Each kind lives in its own file, src/structure/links/<kind>.cpp; the table's rows are
// ADJOIN_LINK_KINDS (core/enum_names.hpp). The scene reader, validation, modal analysis, the
// solver (its assembly and the link forces it reports, by family), the run's link report and
// summary.json loop over it: nothing else switches on LinkType.
#include <string>
#include <vector>

#include "adjoin/structure/building.hpp"

namespace adjoin::structure {

// How the solver steps a link; chosen once at assembly, each family keeps its own fast step.
enum class LinkFamily {
  friction,  // a Coulomb friction damper: the non-smooth step (exact stick)
  linear,    // its spring in K0 and its dashpot in C; its force spring * stroke + dashpot * velocity
  viscous,   // a nonlinear dashpot F = c |v|^alpha sign v (solver/viscous_step.hpp)
  zener,     // a fractional Zener element and its history (solver/rod_law.hpp)
};

// One scene key of a link (and a keyword of the builder).
struct LinkKey {
  const char* name;
  double& (*field)(Link&);
  bool required;
  double fallback;
  std::string (*problem)(double);
};

// One of a link's own values summary.json gives beside its force, stroke and energy.
struct LinkValue {
  const char* name;
  double (*value)(const Link&);
};

struct LinkKind {
  LinkType type;
  const char* what;
  std::vector<LinkKey> keys;  // besides floors and type, in the order they are read
  // Keys io reads by a rule of their own (friction: slip_force, or slip_ratio of a building's
  // weight with `of`); empty for the others.
  std::vector<const char*> own_keys;
  // A rule between keys: "" or what is wrong, blamed on the first of joint_keys given.
  std::string (*joint_problem)(const Link&);
  std::vector<const char*> joint_keys;
  // Structure::IsValid's check of a link made in code: "" or ".c must be ..." (after its path).
  std::string (*invalid)(const Link&);
  double (*spring)(const Link&);   // linear stiffness in K0 [N/m]
  double (*dashpot)(const Link&);  // linear dashpot in C [N s/m]
  double (*relaxed)(const Link&);  // its stiffness in the coupled periods [N/m]
  LinkFamily (*family)(const Link&);
  // The part of the work done on it that it dissipated, given that work and its force and
  // stroke at the end [J]: what an elastic part still holds is not dissipated (SPEC §7).
  double (*dissipated)(const Link&, double work, double force, double stroke);
  // Its values in summary.json's `links` entry, after force_max and stroke_max (a friction
  // link's family adds its switches after them).
  std::vector<LinkValue> summary;
};

const LinkKind& link_kind(LinkType type);
std::vector<const LinkKind*> link_kinds();
inline const LinkKind& kind_of(const Link& l) { return link_kind(l.type); }

#define ADJOIN_LINK_KIND_FUNCTION(value, name) const LinkKind& value##_link_kind();
ADJOIN_LINK_KINDS(ADJOIN_LINK_KIND_FUNCTION)
#undef ADJOIN_LINK_KIND_FUNCTION

}  // namespace adjoin::structure
