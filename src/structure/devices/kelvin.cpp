// A viscoelastic damper (a Kelvin-Voigt element): a spring k in parallel with a linear dashpot c
// in each listed storey, F = k d + c d'. Linear: k joins K0 (and the static stiffness, so the
// periods), c joins C; nothing is stepped on its own.
#include "device_parts.hpp"

namespace adjoin::structure {

const DeviceKind& kelvin_device_kind() {
  using namespace devices;
  static const DeviceKind kind{
      .type = DeviceType::kelvin,
      .what = "a viscoelastic damper: a spring k in parallel with a linear dashpot c",
      .keys = {stiffness_key(), c_key()},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = [](const StoreyDevice& d) -> std::string {
        if (!positive(d.k)) return ".stiffness must be positive (N/m)";
        if (!positive(d.c)) return ".c must be positive (N s/m)";
        return "";
      },
      .spring = spring_k,
      .dashpot = [](const StoreyDevice& d) { return d.c; },
      .relaxed = spring_k,
      .family = linear,
      .yields = false,
  };
  return kind;
}

}  // namespace adjoin::structure
