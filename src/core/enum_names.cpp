#include "adjoin/core/enum_names.hpp"

namespace adjoin {

std::string join_names(const std::vector<std::string>& list, const char* quote, const char* separator, const char* last) {
  std::string out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (i > 0) out += i + 1 == list.size() ? last : separator;
    out += quote + list[i] + quote;
  }
  return out;
}

}  // namespace adjoin
