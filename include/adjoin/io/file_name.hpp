#pragma once
// Names that become file or folder names: a scene's or a sweep's `name` picks its output
// folder (out/<name>/), so a name such as "../../x" or "/tmp/x" would write outside out/.
// Such names are refused where they are read, with the file, line and key.
#include <cstddef>
#include <string>
#include <string_view>

namespace adjoin {

// The longest name accepted (bytes): well below the 255 a file system allows for one name.
inline constexpr std::size_t kMaxPlainNameBytes = 100;

// Why `name` cannot be one plain file name ("" if it can): empty, "." or "..", a '/' or '\\'
// (a path, on Linux or Windows), a control character, or longer than kMaxPlainNameBytes.
std::string plain_name_problem(std::string_view name);

}  // namespace adjoin
