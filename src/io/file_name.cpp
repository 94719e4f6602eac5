#include "adjoin/io/file_name.hpp"

namespace adjoin {

std::string plain_name_problem(std::string_view name) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return "is a reference to a folder, not a name";
  if (name.find('/') != std::string_view::npos || name.find('\\') != std::string_view::npos)
    return "holds a path separator ('/' or '\\'), so it would write outside the output folder";
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "holds a control character";
  if (name.size() > kMaxPlainNameBytes)
    return "is " + std::to_string(name.size()) + " bytes long; at most " + std::to_string(kMaxPlainNameBytes);
  return "";
}

}  // namespace adjoin
