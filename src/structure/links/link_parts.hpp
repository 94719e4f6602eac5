#pragma once
// What the link kinds' files (src/structure/links/<kind>.cpp) share. Internal to structure/.
#include "../devices/device_parts.hpp"
#include "adjoin/structure/link_kinds.hpp"

namespace adjoin::structure::links {

using devices::positive;

inline double none(const Link&) { return 0.0; }
inline std::string no_joint_problem(const Link&) { return ""; }
inline std::string alpha_problem(double v) { return bounded_problem(v, kAlphaRange); }
// A link that keeps nothing: all the work done on it is dissipated.
inline double all_of_it(const Link&, double work, double, double) { return work; }

}  // namespace adjoin::structure::links
