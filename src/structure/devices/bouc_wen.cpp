// A Bouc-Wen device (SPEC §7): the law of building.X.hysteresis as a device. Its initial
// stiffness k in K0; its hysteretic variable the solver's (solver/bouc_wen_step.hpp).
#include "device_parts.hpp"

namespace adjoin::structure {

const DeviceKind& bouc_wen_device_kind() {
  using namespace devices;
  static const DeviceKind kind{
      .type = DeviceType::bouc_wen,
      .what = "a Bouc-Wen yielding device",
      .keys = {stiffness_key(), yield_force_key(), hardening_key(),
               {"n", [](StoreyDevice& d) -> double& { return d.n; }, false, 2.0, bouc_wen_exponent_problem},
               {"beta", [](StoreyDevice& d) -> double& { return d.beta; }, false, 0.5, [](double) { return std::string(); }},
               {"gamma", [](StoreyDevice& d) -> double& { return d.gamma; }, false, 0.5, [](double) { return std::string(); }}},
      .joint_problem = [](const StoreyDevice& d) { return bouc_wen_shape_problem(d.beta, d.gamma); },
      .joint_keys = {"gamma", "beta"},
      .invalid = [](const StoreyDevice& d) -> std::string {
        if (const std::string p = bouc_wen_check(d.n, d.beta, d.gamma); !p.empty()) return "." + p;
        return yielding_invalid(d);
      },
      .spring = spring_k,
      .dashpot = none,
      .relaxed = spring_k,
      .family = [](const StoreyDevice&) { return DeviceFamily::bouc_wen; },
      .yields = true,
  };
  return kind;
}

}  // namespace adjoin::structure
