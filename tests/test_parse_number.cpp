// core/parse_number: the one number parser (record files, CSV cells, journals, options).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "adjoin/core/parse_number.hpp"

using adjoin::NumberStatus;

namespace {

NumberStatus status_of(const std::string& text, double* value = nullptr) {
  double v = -12345.0;
  const NumberStatus s = adjoin::parse_number(text, v);
  if (value) *value = v;
  return s;
}

}  // namespace

TEST_CASE("parse_number takes one whole number: signs, exponents, underflow", "[parse_number]") {
  double v = 0.0;
  CHECK(status_of("0.5", &v) == NumberStatus::ok);
  CHECK(v == 0.5);
  CHECK(status_of("+2.5e-3", &v) == NumberStatus::ok);
  CHECK(v == 2.5e-3);
  CHECK(status_of("-7", &v) == NumberStatus::ok);
  CHECK(v == -7.0);
  // An underflow is the nearest double, not an error.
  CHECK(status_of("1e-400", &v) == NumberStatus::ok);
  CHECK(v == 0.0);
  CHECK(status_of("4.9e-324", &v) == NumberStatus::ok);
  CHECK(v == std::numeric_limits<double>::denorm_min());
}

TEST_CASE("parse_number refuses text around the number, blanks and a Fortran exponent", "[parse_number]") {
  for (const char* text : {"", " 1", "1 ", "1x", "x1", "1,5", "++1", "+-1", "1D3", "0x10", "1e", "-"}) {
    INFO(text);
    CHECK(status_of(text) == NumberStatus::not_a_number);
  }
}

TEST_CASE("parse_number tells non-finite and out-of-range numbers apart", "[parse_number]") {
  double v = 0.0;
  CHECK(status_of("inf", &v) == NumberStatus::not_finite);
  CHECK(std::isinf(v));
  CHECK(status_of("-infinity") == NumberStatus::not_finite);
  CHECK(status_of("nan", &v) == NumberStatus::not_finite);
  CHECK(std::isnan(v));
  CHECK(status_of("1e999") == NumberStatus::out_of_range);
  CHECK(status_of("-1e999") == NumberStatus::out_of_range);
  CHECK(std::string(adjoin::number_problem(NumberStatus::not_a_number)) == "is not a number");
  CHECK(std::string(adjoin::number_problem(NumberStatus::not_finite)) == "is not a finite number");
  CHECK(std::string(adjoin::number_problem(NumberStatus::out_of_range)) == "is out of the range of double");
  // parse_finite: ok only, and the value untouched otherwise.
  double kept = 3.0;
  CHECK_FALSE(adjoin::parse_finite("inf", &kept));
  CHECK(kept == 3.0);
  CHECK(adjoin::parse_finite("-0.25", &kept));
  CHECK(kept == -0.25);
}

TEST_CASE("scan_number stops where the number ends and reads Fortran exponents on request", "[parse_number]") {
  const std::string text = "1.5D-03 2";
  double v = 0.0;
  const char* stop = nullptr;
  REQUIRE(adjoin::scan_number(text.data(), text.data() + text.size(), v, stop, true) == NumberStatus::ok);
  CHECK(v == 1.5e-3);
  CHECK(stop == text.data() + 7);
  // Without, the number is 1.5 and stops at the D.
  REQUIRE(adjoin::scan_number(text.data(), text.data() + text.size(), v, stop) == NumberStatus::ok);
  CHECK(v == 1.5);
  CHECK(*stop == 'D');
  const std::string big = "1d999";
  CHECK(adjoin::scan_number(big.data(), big.data() + big.size(), v, stop, true) == NumberStatus::out_of_range);
}

TEST_CASE("parse_count takes decimal digits only, within size_t", "[parse_number]") {
  std::size_t n = 0;
  CHECK(adjoin::parse_count("0", &n));
  CHECK(n == 0);
  CHECK(adjoin::parse_count("18446744073709551615", &n));
  CHECK(n == std::numeric_limits<std::size_t>::max());
  for (const char* text : {"", "-1", "+1", " 1", "1 ", "1.0", "1e3", "18446744073709551616"}) {
    INFO(text);
    CHECK_FALSE(adjoin::parse_count(text, &n));
  }
  CHECK(adjoin::trim_blanks(" \t 1.5\r ") == "1.5");
  CHECK(adjoin::trim_blanks(" \t ").empty());
}
