// A dashpot, F = c |v|^alpha sign v (SPEC §7): linear (alpha = 1) in C; nonlinear (alpha < 1)
// a viscous element the solver steps on its own (solver/viscous_step.hpp).
#include "device_parts.hpp"

namespace adjoin::structure {

const DeviceKind& dashpot_device_kind() {
  using namespace devices;
  static const DeviceKind kind{
      .type = DeviceType::dashpot,
      .what = "a dashpot, F = c |v|^alpha sign v",
      .keys = {c_key(),
               {"alpha", [](StoreyDevice& d) -> double& { return d.alpha; }, false, 1.0,
                [](double v) { return bounded_problem(v, kAlphaRange); }}},
      .joint_problem = no_joint_problem,
      .joint_keys = {},
      .invalid = [](const StoreyDevice& d) -> std::string {
        if (!positive(d.c)) return ".c must be positive (N s/m)";
        if (!(d.alpha >= kAlphaRange.lo && d.alpha <= kAlphaRange.hi)) return ".alpha must lie in [0.05, 1] (F = c |v|^alpha sign v)";
        return "";
      },
      .spring = none,
      .dashpot = [](const StoreyDevice& d) { return d.alpha == 1.0 ? d.c : 0.0; },  // (a nonlinear one has no matrix)
      .relaxed = none,
      .family = [](const StoreyDevice& d) { return d.alpha == 1.0 ? DeviceFamily::linear : DeviceFamily::viscous; },
      .yields = false,
  };
  return kind;
}

}  // namespace adjoin::structure
