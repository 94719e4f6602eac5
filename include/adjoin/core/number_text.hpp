#pragma once
// Numbers written into messages: the one formatter (scenes word their numbers with 12
// significant digits, structures with 6).
#include <string>

namespace adjoin {

// A number for a message with `significant` digits, as printf's %g writes it: 1e+15, 0.3,
// 1.5e-09, inf, nan.
std::string number_text(double v, int significant);

}  // namespace adjoin
