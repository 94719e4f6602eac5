#pragma once
// The paper's system as the smallest structure (SPEC §5): buildings A and B of one storey
// each (Zener storeys, or springs for elastic rods), no inherent damping, one friction link
// (if mu > 0) and one contact pair at floor 1 with gap gap0 and the model's contact law.
// `scales` turns the dimensionless model into SI (masses m1, m1/rho, stiffnesses k1, eps k1,
// tau in s^order); the default gives it in the model's dimensionless units.
#include "adjoin/structure/parameters.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/building.hpp"

namespace adjoin::structure {

Structure two_block_structure(const Model& model, const Scales& scales = Scales::Dimensionless());

}  // namespace adjoin::structure
