#pragma once
// The storey device kinds (SPEC §5, §7) as one table. A kind says everything the rest of the
// program needs to know about it: its scene keys (the field each sets, its default, its check),
// how a structure built in code is checked, and what it adds to the model — its linear spring
// (in K0 and the storey force), its linear dashpot (in C), its relaxed stiffness (the static
// stiffness the periods use), and the step family the solver hands it to at assembly.
//
// Each kind lives in its own file, src/structure/devices/<kind>.cpp; the table's rows are
// ADJOIN_DEVICE_KINDS (core/enum_names.hpp). The scene reader, the typed builder, Python,
// validation, modal analysis and the solver's assembly loop over this table: a new device is
// one file plus one row (docs/how-to/add-an-element.md).
#include <string>
#include <vector>

#include "adjoin/structure/building.hpp"

namespace adjoin::structure {

// How the solver steps a device; chosen once at assembly, each family keeps its own fast step.
enum class DeviceFamily {
  linear,    // its spring in K0 and its dashpot in C, nothing per step (spring, linear dashpot)
  viscous,   // a nonlinear dashpot F = c |v|^alpha sign v (solver/viscous_step.hpp)
  zener,     // a fractional Zener element and its history (solver/rod_law.hpp)
  bilinear,  // its spring in K0 and a Coulomb slider in series (solver/bilinear_step.hpp)
  bouc_wen,  // its spring in K0 and a smooth hysteretic variable (solver/bouc_wen_step.hpp)
};

// One scene key of a device (and a keyword of the builder and of Python).
struct DeviceKey {
  const char* name;                 // "stiffness"
  double& (*field)(StoreyDevice&);  // the field it sets
  bool required;
  double fallback;                  // the value when optional and not given
  std::string (*problem)(double);   // "" or what is wrong with a value (unit and range)
};

struct DeviceKind {
  DeviceType type;
  const char* what;                 // one line for docs and help: "a linear spring"
  std::vector<DeviceKey> keys;      // besides type and storeys, in the order they are read
  // A rule between keys, checked after each key's own: "" or what is wrong, blamed on the
  // first of `joint_keys` that was given (a scene's key, a builder value off its default).
  std::string (*joint_problem)(const StoreyDevice&);
  std::vector<const char*> joint_keys;
  // Structure::IsValid's check of a device made in code: "" or ".stiffness must be ..."
  // (appended to the device's path).
  std::string (*invalid)(const StoreyDevice&);
  double (*spring)(const StoreyDevice&);   // linear stiffness in K0 [N/m] (yielding: initial)
  double (*dashpot)(const StoreyDevice&);  // linear dashpot in C [N s/m]
  double (*relaxed)(const StoreyDevice&);  // its part of the storey's static stiffness [N/m]
  DeviceFamily (*family)(const StoreyDevice&);
  bool yields;  // its storey's periods are then those of the initial stiffness (SPEC §7)
};

// The kind of a device type, and every kind in the table's order.
const DeviceKind& device_kind(DeviceType type);
std::vector<const DeviceKind*> device_kinds();
inline const DeviceKind& kind_of(const StoreyDevice& d) { return device_kind(d.type); }

// A device's joint rule's key to blame: the first of kind.joint_keys for which given(key).
template <class Given>
const char* joint_key(const DeviceKind& kind, Given given) {
  for (const char* key : kind.joint_keys)
    if (given(key)) return key;
  return kind.joint_keys.empty() ? "" : kind.joint_keys.back();
}

// The kinds' own files (src/structure/devices/<kind>.cpp): one function each, named by
// ADJOIN_DEVICE_KINDS.
#define ADJOIN_DEVICE_KIND_FUNCTION(value, name) const DeviceKind& value##_device_kind();
ADJOIN_DEVICE_KINDS(ADJOIN_DEVICE_KIND_FUNCTION)
#undef ADJOIN_DEVICE_KIND_FUNCTION

}  // namespace adjoin::structure
