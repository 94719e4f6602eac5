#include "adjoin/structure/device_kinds.hpp"

namespace adjoin::structure {

std::vector<const DeviceKind*> device_kinds() {
#define ADJOIN_DEVICE_KIND_ROW(value, name) &value##_device_kind(),
  return {ADJOIN_DEVICE_KINDS(ADJOIN_DEVICE_KIND_ROW)};
#undef ADJOIN_DEVICE_KIND_ROW
}

const DeviceKind& device_kind(DeviceType type) {
  static const std::vector<const DeviceKind*> table = device_kinds();
  return *table.at(static_cast<std::size_t>(type));
}

}  // namespace adjoin::structure
