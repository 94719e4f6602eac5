#pragma once
// Parses TOML text into a table, a syntax error as an InputError naming "file:line" (internal
// to io: scenes, building scenes).
#include <sstream>
#include <string>

#include <toml++/toml.h>

#include "adjoin/errors.hpp"

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

}  // namespace adjoin::detail
