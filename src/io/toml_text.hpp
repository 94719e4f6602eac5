#pragma once
// Parses TOML text into a table, a syntax error as an InputError naming "file:line" (internal
// to io: scenes, building scenes).
#include <sstream>
#include <string>

#include <toml++/toml.h>

#include "adjoin/core/errors.hpp"

namespace adjoin::detail {

inline toml::table parse_toml_text(const std::string& text, const std::string& name) {
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << name << ":" << e.source().begin.line << ": not valid TOML: " << e.description();
    throw InputError(s.str());
  }
}

// The value of an edit `key=value` as TOML, in a table under the key "v": a TOML value
// (0.1, "x", [1, 2], { a = 1 }), or else the text as a bare string (record, SI).
inline toml::table toml_value_of(const std::string& value) {
  try {
    return toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    toml::table holder;
    holder.insert("v", value);
    return holder;
  }
}

}  // namespace adjoin::detail
