#pragma once
// Numbers written as text: the one formatter (scenes word their numbers in messages with 12
// significant digits, structures with 6; values that must read back exactly, as written in
// scenes, commands and messages, in their shortest round-trip form).
#include <string>

namespace adjoin {

// A number for a message with `significant` digits, as printf's %g writes it: 1e+15, 0.3,
// 1.5e-09, inf, nan.
std::string number_text(double v, int significant);

// The shortest text that reads back as exactly `v` (std::to_chars): 0.1, 1e+300, 2.5e-05,
// inf, nan.
std::string shortest_text(double v);

}  // namespace adjoin
