#pragma once
// The keys each type of [[link]] and [[building.X.device]] takes (internal to io): the
// structure reader refuses any other key of the table (structure_file.cpp), and an edit that
// changes a table's `type` drops the keys the new type does not take (structure_edits.cpp), as
// `model.rodN.elastic = true` drops a rod's order and times: a friction link made a dashpot
// loses its slip_force or slip_ratio and of, and keeps floors.
#include <set>
#include <string>

#include "adjoin/core/enum_names.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/link_kinds.hpp"

namespace adjoin::detail {

// A link's keys come from its kind (structure/link_kinds.hpp).
inline std::set<std::string> link_keys(structure::LinkType type) {
  const structure::LinkKind& kind = structure::link_kind(type);
  std::set<std::string> keys{"floors", "type"};
  for (const structure::LinkKey& key : kind.keys) keys.insert(key.name);
  keys.insert(kind.own_keys.begin(), kind.own_keys.end());
  return keys;
}

// A device's keys come from its kind (structure/device_kinds.hpp).
inline std::set<std::string> device_keys(structure::DeviceType type) {
  std::set<std::string> keys{"type", "storeys"};
  for (const structure::DeviceKey& key : structure::device_kind(type).keys) keys.insert(key.name);
  return keys;
}

}  // namespace adjoin::detail
