#pragma once
// Whole-string number parsing for the tables adjoin reads back (sweep tables, journals,
// demand inputs): the text must be exactly one number, nothing before or after it.
#include <charconv>
#include <cstddef>
#include <string>
#include <system_error>

namespace adjoin::detail {

inline bool parse_double(const std::string& text, double* value) {
  if (text.empty()) return false;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

inline bool parse_size(const std::string& text, std::size_t* value) {
  if (text.empty()) return false;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

}  // namespace adjoin::detail
