// USGS SMC (strong-motion CD format, as distributed by the USGS NSMP and written by PEER's
// PEA2SMC): a fixed header of
//   lines  1-11  text; line 1 starts with the data-type code: 0 unknown, 1 uncorrected
//                accelerogram, 2 corrected accelerogram, 3 velocity, 4 displacement,
//                5 response spectra, 6 Fourier amplitude spectra
//   lines 12-17  48 integers, 8I10; -32768 means "no value". Integer 16: number of comment
//                lines; integer 17: number of data values
//   lines 18-27  50 reals, 5E15.7; 1.7E+38 means "no value". Real 2: samples per second
//                (real 29/30 time and value of the maximum, 31/32 of the minimum)
// then the comment lines (each starting with '|'), then the values (5E15.7, or 8E10.4 in
// uncorrected files). Accelerations are in cm/s^2.
//
// Uncorrected records digitised from film are unevenly sampled (time, value pairs, no
// sampling rate): they are refused with the line of the missing rate.
#include <cmath>
#include <string>
#include <vector>

#include "registry.hpp"

namespace adjoin::readers {
namespace {

constexpr std::size_t kTextLines = 11, kIntLines = 6, kRealLines = 10;
constexpr std::size_t kIntFirst = kTextLines + 1;            // line 12
constexpr std::size_t kRealFirst = kIntFirst + kIntLines;    // line 18
constexpr std::size_t kCommentFirst = kRealFirst + kRealLines;  // line 28
constexpr long kNoInt = -32768;
constexpr double kNoReal = 1e38;  // 1.7E+38 and above: no value

// Fixed fields of `width` characters; false if one is not a number.
bool fixed_fields(std::string_view text, std::size_t count, std::size_t width, std::vector<double>& out) {
  for (std::size_t f = 0; f < count; ++f) {
    if (f * width >= text.size()) return false;
    const std::string_view field = trim(text.substr(f * width, width));
    double value = 0.0;
    const char* stop = nullptr;
    if (field.empty() || parse_number(field.data(), field.data() + field.size(), value, stop) != NumberStatus::ok ||
        stop != field.data() + field.size())
      return false;
    out.push_back(value);
  }
  return true;
}

// The data-type code of line 1 ("2 CORRECTED ACCELEROGRAM"), or -1.
int type_code(std::string_view line) {
  line = trim(line);
  if (line.size() < 2 || !is_digit(line[0]) || !is_blank(line[1])) return -1;
  return line[0] - '0';
}

}  // namespace

// The header's structure: a type code on line 1, then six lines of 8 integers and ten of 5
// reals in their fixed fields.
int sniff_smc(const Probe& probe) {
  if (probe.head.size() < kCommentFirst - 1) return 0;
  const int code = type_code(probe.head[0].text);
  if (code < 0 || code > 6) return 0;
  std::vector<double> values;
  for (std::size_t i = kIntFirst; i < kRealFirst; ++i)
    if (!fixed_fields(probe.head[i - 1].text, 8, 10, values)) return 0;
  for (std::size_t i = kRealFirst; i < kCommentFirst; ++i)
    if (!fixed_fields(probe.head[i - 1].text, 5, 15, values)) return 0;
  return 80;
}

Record parse_smc(std::string_view text, const std::string& name, const RecordFormat& format) {
  const std::vector<Line> lines = split_lines(text);
  if (lines.empty()) fail(name, 1, "empty file (expected a USGS SMC record)");
  if (lines.size() < kCommentFirst - 1)
    fail(name, lines.back().number,
         "the file ends within the SMC header (expected 11 text lines, 6 lines of integers and 10 of reals)");
  const int code = type_code(lines[0].text);
  if (code < 0 || code > 6)
    fail(name, 1, quote_token(trim(lines[0].text)) + " does not start with an SMC data-type code (expected e.g. '2 CORRECTED ACCELEROGRAM')");
  if (code >= 3) {
    static const char* const kinds[] = {"", "", "", "a velocity", "a displacement", "a response spectrum", "a Fourier spectrum"};
    fail(name, 1, "this is " + std::string(kinds[code]) + " file (data-type code " + std::to_string(code) +
                      "; expected an accelerogram: code 0, 1 or 2)");
  }

  std::vector<double> ints, reals;
  for (std::size_t i = kIntFirst; i < kRealFirst; ++i) {
    const Line& line = lines[i - 1];
    if (!fixed_fields(line.text, 8, 10, ints))
      fail(name, line.number, quote_token(trim(line.text)) + " is not 8 integers in fields of 10 characters (expected the SMC integer header, 8I10)");
  }
  for (std::size_t i = kRealFirst; i < kCommentFirst; ++i) {
    const Line& line = lines[i - 1];
    if (!fixed_fields(line.text, 5, 15, reals))
      fail(name, line.number, quote_token(trim(line.text)) + " is not 5 numbers in fields of 15 characters (expected the SMC real header, 5E15.7)");
  }
  const auto int_line = [](std::size_t k) { return kIntFirst + (k - 1) / 8; };    // 1-based integer k
  const auto real_line = [](std::size_t k) { return kRealFirst + (k - 1) / 5; };  // 1-based real k

  const double comments = ints[15], npts_value = ints[16];
  if (comments == static_cast<double>(kNoInt)) {
    // none
  } else if (!(comments >= 0.0 && comments == std::floor(comments)))
    fail(name, int_line(16), "integer 16, the number of comment lines, is " + fmt(comments) + " (expected 0 or more)");
  if (npts_value == static_cast<double>(kNoInt) || !(npts_value >= 1.0 && npts_value == std::floor(npts_value)))
    fail(name, int_line(17), "integer 17, the number of samples, is " +
                                 (npts_value == static_cast<double>(kNoInt) ? std::string("not given (-32768)") : fmt(npts_value)) +
                                 " (expected a positive whole number)");
  const double rate = reals[1];
  if (!(rate > 0.0) || rate >= kNoReal)
    fail(name, real_line(2), "real 2, the sampling rate, is " +
                                 (rate >= kNoReal ? std::string("not given (") + fmt(rate) + ")" : fmt(rate)) +
                                 " (expected samples per second > 0; an uncorrected record digitised from film is "
                                 "unevenly sampled: read its corrected version)");
  const double dt = 1.0 / rate;
  agree_dt(format, dt, name, real_line(2));
  const AccelUnit unit = agree_units(format, AccelUnit::cm_s2, name, 0, "an SMC file (values in cm/s2)");

  const std::size_t n_comments = comments == static_cast<double>(kNoInt) ? 0 : static_cast<std::size_t>(comments);
  if (n_comments > lines.size() - (kCommentFirst - 1))
    fail(name, int_line(16), "integer 16 says " + std::to_string(n_comments) + " comment lines, but the file ends before (" +
                                 std::to_string(lines.size()) + " lines)");
  std::size_t next = kCommentFirst - 1 + n_comments;
  std::vector<std::string_view> described;
  described.push_back(lines[0].text.substr(2));
  for (std::size_t i = 1; i < kTextLines; ++i)
    if (trim(lines[i].text) != "*") described.push_back(lines[i].text.substr(lines[i].text.starts_with("*") ? 1 : 0));
  for (std::size_t i = kCommentFirst - 1; i < next; ++i) {
    std::string_view c = lines[i].text;
    if (!c.empty() && c.front() == '|') c.remove_prefix(1);
    described.push_back(c);
  }

  std::vector<double> values;
  const std::size_t npts = static_cast<std::size_t>(npts_value);
  read_block(lines, &next, npts, std::nullopt, name, "values", int_line(17), values);
  for (; next < lines.size(); ++next)
    if (!trim(lines[next].text).empty())
      fail(name, lines[next].number, "more values than the " + std::to_string(npts) + " integer 17 on line " +
                                         std::to_string(int_line(17)) + " announces (found " +
                                         quote_token(trim(lines[next].text).substr(0, 40)) + ")");
  return finish(name, join_lines(described), dt, std::move(values), unit);
}

}  // namespace adjoin::readers
