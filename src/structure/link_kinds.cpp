#include "adjoin/structure/link_kinds.hpp"

namespace adjoin::structure {

std::vector<const LinkKind*> link_kinds() {
#define ADJOIN_LINK_KIND_ROW(value, name) &value##_link_kind(),
  return {ADJOIN_LINK_KINDS(ADJOIN_LINK_KIND_ROW)};
#undef ADJOIN_LINK_KIND_ROW
}

const LinkKind& link_kind(LinkType type) {
  static const std::vector<const LinkKind*> table = link_kinds();
  return *table.at(static_cast<std::size_t>(type));
}

}  // namespace adjoin::structure
