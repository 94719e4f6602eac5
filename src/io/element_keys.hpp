#pragma once
// The keys each type of [[link]] and [[building.X.device]] takes (internal to io): the
// structure reader refuses any other key of the table (structure_file.cpp), and an edit that
// changes a table's `type` drops the keys the new type does not take (structure_edits.cpp), as
// `model.rodN.elastic = true` drops a rod's order and times: a friction link made a dashpot
// loses its slip_force or slip_ratio and of, and keeps floors.
#include <set>
#include <string>

#include "adjoin/core/enum_names.hpp"

namespace adjoin::detail {

inline std::set<std::string> link_keys(structure::LinkType type) {
  using T = structure::LinkType;
  switch (type) {
    case T::friction: return {"floors", "type", "slip_force", "slip_ratio", "of"};
    case T::dashpot: return {"floors", "type", "c", "alpha"};
    case T::spring: return {"floors", "type", "stiffness"};
    case T::zener: return {"floors", "type", "stiffness", "order", "tau_x", "tau_f"};
  }
  return {};
}

inline std::set<std::string> device_keys(structure::DeviceType type) {
  using T = structure::DeviceType;
  switch (type) {
    case T::spring: return {"type", "storeys", "stiffness"};
    case T::dashpot: return {"type", "storeys", "c", "alpha"};
    case T::bilinear: return {"type", "storeys", "stiffness", "yield_force", "hardening"};
    case T::bouc_wen: return {"type", "storeys", "stiffness", "yield_force", "hardening", "n", "beta", "gamma"};
    case T::zener: return {"type", "storeys", "stiffness", "order", "tau_x", "tau_f"};
  }
  return {};
}

}  // namespace adjoin::detail
