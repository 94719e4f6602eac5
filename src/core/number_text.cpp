#include "adjoin/core/number_text.hpp"

#include <cstdio>

namespace adjoin {

std::string number_text(double v, int significant) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", significant, v);
  return text;
}

}  // namespace adjoin
