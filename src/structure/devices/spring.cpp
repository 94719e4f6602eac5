// A linear spring in parallel with the storey's own: its k joins K0 and the storey force.
#include "device_parts.hpp"

namespace adjoin::structure {

const DeviceKind& spring_device_kind() {
  using namespace devices;
  static const DeviceKind kind{
      .type = DeviceType::spring,
      .what = "a linear spring",
      .keys = {stiffness_key()},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = [](const StoreyDevice& d) -> std::string { return positive(d.k) ? "" : ".stiffness must be positive (N/m)"; },
      .spring = spring_k,
      .dashpot = none,
      .relaxed = spring_k,
      .family = linear,
      .yields = false,
  };
  return kind;
}

}  // namespace adjoin::structure
