// A bilinear device (a metallic yielding damper, a buckling-restrained brace; SPEC §7): its
// initial stiffness k in K0, and a Coulomb slider in series with (1 - b) k that the solver
// steps exactly (solver/bilinear_step.hpp).
#include "device_parts.hpp"

namespace adjoin::structure {

const DeviceKind& bilinear_device_kind() {
  using namespace devices;
  static const DeviceKind kind{
      .type = DeviceType::bilinear,
      .what = "a bilinear yielding device (metallic damper, BRB)",
      .keys = {stiffness_key(), yield_force_key(), hardening_key()},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = yielding_invalid,
      .spring = spring_k,
      .dashpot = none,
      .relaxed = spring_k,
      .family = [](const StoreyDevice&) { return DeviceFamily::bilinear; },
      .yields = true,
  };
  return kind;
}

}  // namespace adjoin::structure
