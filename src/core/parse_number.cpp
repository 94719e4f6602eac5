// The one number parser (core/parse_number.hpp).
#include "adjoin/core/parse_number.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <system_error>

namespace adjoin {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// from_chars leaves the value alone on overflow and on underflow; strtod tells which (and
// gives the nearest double for an underflow).
NumberStatus out_of_range(const std::string& text, double& value) {
  value = std::strtod(text.c_str(), nullptr);
  return std::isinf(value) ? NumberStatus::out_of_range : NumberStatus::ok;
}

}  // namespace

NumberStatus scan_number(const char* p, const char* end, double& value, const char*& stop, bool fortran_exponent) {
  const char* q = p;
  if (q != end && *q == '+') {  // from_chars takes '-' only
    ++q;
    if (q == end || *q == '+' || *q == '-') return NumberStatus::not_a_number;
  }
  auto result = std::from_chars(q, end, value, std::chars_format::general);
  if (result.ec == std::errc::invalid_argument) return NumberStatus::not_a_number;
  stop = result.ptr;
  if (fortran_exponent && stop != end && (*stop == 'D' || *stop == 'd')) {  // 1.5D-03
    const char* e = stop + 1;
    if (e != end && (*e == '+' || *e == '-')) ++e;
    if (e != end && is_digit(*e)) {
      while (e != end && is_digit(*e)) ++e;
      std::string copy(q, e);
      copy[static_cast<std::size_t>(stop - q)] = 'e';
      auto again = std::from_chars(copy.data(), copy.data() + copy.size(), value, std::chars_format::general);
      if (again.ec == std::errc::invalid_argument) return NumberStatus::not_a_number;
      if (again.ec == std::errc::result_out_of_range && out_of_range(copy, value) == NumberStatus::out_of_range)
        return NumberStatus::out_of_range;
      stop = e;
      return std::isfinite(value) ? NumberStatus::ok : NumberStatus::not_finite;
    }
  }
  if (result.ec == std::errc::result_out_of_range && out_of_range(std::string(q, stop), value) == NumberStatus::out_of_range)
    return NumberStatus::out_of_range;
  return std::isfinite(value) ? NumberStatus::ok : NumberStatus::not_finite;
}

NumberStatus parse_number(std::string_view text, double& value) {
  const char* end = text.data() + text.size();
  const char* stop = text.data();
  if (text.empty()) return NumberStatus::not_a_number;
  const NumberStatus status = scan_number(text.data(), end, value, stop);
  if (status == NumberStatus::not_a_number || stop != end) return NumberStatus::not_a_number;
  return status;
}

bool parse_finite(std::string_view text, double* value) {
  double v = 0.0;
  if (parse_number(text, v) != NumberStatus::ok) return false;
  *value = v;
  return true;
}

bool parse_count(std::string_view text, std::size_t* value) {
  if (text.empty() || !is_digit(text.front())) return false;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

const char* number_problem(NumberStatus status) {
  switch (status) {
    case NumberStatus::ok: return "is a number";
    case NumberStatus::not_a_number: break;
    case NumberStatus::not_finite: return "is not a finite number";
    case NumberStatus::out_of_range: return "is out of the range of double";
  }
  return "is not a number";
}

std::string_view trim_blanks(std::string_view text) {
  std::size_t b = 0, e = text.size();
  while (b < e && is_blank(text[b])) ++b;
  while (e > b && is_blank(text[e - 1])) --e;
  return text.substr(b, e - b);
}

}  // namespace adjoin
