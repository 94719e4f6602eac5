#pragma once
// The paper's system as the smallest structure (SPEC §5): buildings A and B of one storey
// each (Zener storeys, or springs for elastic rods), no inherent damping, one friction link
// (if mu > 0) and one contact pair at floor 1 with gap gap0 and the model's contact law.
// `scales` turns the dimensionless model into SI (masses m1, m1/rho, stiffnesses k1, eps k1,
// tau in s^order); the default gives it in the model's dimensionless units.
#include <optional>
#include <string>

#include "adjoin/structure/parameters.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/building.hpp"

namespace adjoin::structure {

Structure two_block_structure(const Model& model, const Scales& scales = Scales::Dimensionless());

// The inverse in the model's dimensionless units: the model whose 1 + 1 structure `s` is (block
// 1's mass and stiffness 1), or none, with the reason in `why` (optional), when `s` is not such
// a structure. A run description holds the structure only (study/run_spec.hpp); the paper's
// scheme and closed forms, which are written for the model, read it back with this.
// two_block_model(two_block_structure(m)) is m, but for rho (1 / (1 / rho)) at rounding level.
std::optional<Model> two_block_model(const Structure& s, std::string* why = nullptr);

// The channel (structure/channels.hpp) of the 1 + 1 structure that SPEC §3's name `name`
// presents (SPEC §4): x1 = A.x1, x2 = B.x1, drift = link1.stroke (x1 - x2), f1 = A.shear1,
// f2 = B.shear1 (the storeys' forces), q = link1.force, a1_abs = A.a1_abs, a2_abs = B.a1_abs,
// gap = contact1.gap, and the two-block run's own values v1 = A.v1, v2 = B.v1 (the floors'
// velocities) and ag. "" for a name that is not a channel's.
std::string two_block_channel(const std::string& name);

}  // namespace adjoin::structure
