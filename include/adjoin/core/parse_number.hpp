#pragma once
// Numbers read from text: the one parser every reader of adjoin uses (record files, CSV
// tables, sweep journals, target spectra, command-line options). It says what is wrong and
// leaves the words "FILE:LINE:" or "--option" to the caller, who knows where the text came
// from. Locale-free (std::from_chars underneath): 0.5 is 0.5 whatever LC_NUMERIC says.
//
// The core layer: no adjoin header below it, so every layer may include it.
#include <cstddef>
#include <string_view>

namespace adjoin {

enum class NumberStatus {
  ok,            // a finite number
  not_a_number,  // empty, or not a number, or (parse_number) text before or after it
  not_finite,    // nan, inf, infinity (the value holds it)
  out_of_range,  // beyond the range of double (1e999); an underflow gives the nearest double
};

// Scans the number that starts at `p` (no blanks skipped): an optional sign ('+' too),
// digits, a fraction, an exponent, and with `fortran_exponent` a Fortran 'D' exponent
// (1.5D-03). On any status but not_a_number, `stop` is where the number ends.
NumberStatus scan_number(const char* p, const char* end, double& value, const char*& stop,
                         bool fortran_exponent = false);

// The whole text must be one number, nothing before or after it (no blanks: trim first
// where blanks are allowed). A non-finite number is reported as not_finite with its value.
NumberStatus parse_number(std::string_view text, double& value);
// parse_number(...) == ok: one finite number.
bool parse_finite(std::string_view text, double* value);
// The whole text one count: decimal digits only (no sign, no blanks), within std::size_t.
bool parse_count(std::string_view text, std::size_t* value);

// What went wrong, for a message "'TEXT' " + number_problem(s) + " (expected ...)":
// "is not a number", "is not a finite number", "is out of the range of double".
const char* number_problem(NumberStatus status);

// Blanks (space, tab, CR, FF, VT) cut from both ends.
std::string_view trim_blanks(std::string_view text);

}  // namespace adjoin
