#pragma once
// What the link kinds' files (src/structure/links/<kind>.cpp) share. Internal to structure/.
#include "../devices/device_parts.hpp"
#include "adjoin/structure/link_kinds.hpp"

namespace adjoin::structure::links {

using devices::positive;

inline double none(const Link&) { return 0.0; }
inline std::string no_joint_problem(const Link&) { return ""; }
inline std::string alpha_problem(double v) { return bounded_problem(v, kAlphaRange); }

}  // namespace adjoin::structure::links
