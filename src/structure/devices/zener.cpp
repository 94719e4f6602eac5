// The paper's rod as a storey device: f + tau_f D^order f = k (d + tau_x D^order d). Its relaxed
// stiffness k counts in the static stiffness; the solver steps it with its history.
#include "device_parts.hpp"

namespace adjoin::structure {

const DeviceKind& zener_device_kind() {
  using namespace devices;
  static const DeviceKind kind{
      .type = DeviceType::zener,
      .what = "a fractional Zener element (the paper's rod)",
      .keys = {{"stiffness", [](StoreyDevice& d) -> double& { return d.zener.k; }, true, 0.0,
                [](double v) { return bounded_problem(v, kStiffnessRange); }},
               {"order", [](StoreyDevice& d) -> double& { return d.zener.order; }, true, 0.0, zener_order_problem},
               {"tau_f", [](StoreyDevice& d) -> double& { return d.zener.tau_f; }, true, 0.0,
                [](double v) { return bounded_problem(v, kTauRange); }},
               {"tau_x", [](StoreyDevice& d) -> double& { return d.zener.tau_x; }, true, 0.0,
                [](double v) { return bounded_problem(v, kTauRange); }}},
      .joint_problem = [](const StoreyDevice& d) { return zener_tau_problem(d.zener.tau_x, d.zener.tau_f); },
      .joint_keys = {"tau_x"},
      .invalid = [](const StoreyDevice& d) -> std::string {
        const std::string p = zener_check(d.zener);
        return p.empty() ? "" : ": " + p;
      },
      .spring = none,
      .dashpot = none,
      .relaxed = [](const StoreyDevice& d) { return d.zener.k; },
      .family = [](const StoreyDevice&) { return DeviceFamily::zener; },
      .yields = false,
  };
  return kind;
}

}  // namespace adjoin::structure
