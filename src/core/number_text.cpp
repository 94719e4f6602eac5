#include "adjoin/core/number_text.hpp"

#include <charconv>
#include <cstdio>

namespace adjoin {

std::string number_text(double v, int significant) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", significant, v);
  return text;
}

std::string shortest_text(double v) {
  char text[64];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  return std::string(text, end);
}

}  // namespace adjoin
