// AccelUnit helpers declared in adjoin/ground/record.hpp.
#include <cctype>
#include <string>

#include "adjoin/ground/record.hpp"
#include "adjoin/core/units.hpp"

namespace adjoin {

double to_m_s2(AccelUnit unit) {
  switch (unit) {
    case AccelUnit::g: return kStandardGravity;
    case AccelUnit::m_s2: return 1.0;
    case AccelUnit::cm_s2: return 0.01;
    case AccelUnit::mm_s2: return 0.001;
  }
  return 1.0;
}

namespace {

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

}  // namespace

// Accepted spellings, case-insensitive and ignoring blanks: g; m/s2, m/s^2, m/s**2, m/s/s,
// m/s², with "sec" for "s" (so also the AT2 header spelling CM/SEC/SEC); the same with cm and
// mm; gal (= cm/s2).
bool parse_accel_unit(const std::string& name, AccelUnit* unit) {
  std::string s;
  s.reserve(name.size());
  for (char c : name)
    if (!std::isspace(static_cast<unsigned char>(c))) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  replace_all(s, "\xc2\xb2", "2");  // UTF-8 superscript two
  replace_all(s, "sec", "s");
  replace_all(s, "**2", "2");
  replace_all(s, "^2", "2");
  replace_all(s, "/s/s", "/s2");
  AccelUnit found;
  if (!parse_enum(s, &found)) return false;
  if (unit) *unit = found;
  return true;
}

}  // namespace adjoin
