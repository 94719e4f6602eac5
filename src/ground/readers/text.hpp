#pragma once
// Internal: the text scanning every record reader shares (lines, numbers, messages). Not part
// of the public API; see record_file.hpp for the formats and the rules.
//
// Text is scanned in place (memchr for lines, std::from_chars for numbers): no streams, no
// per-line allocations. Every defect is an InputError "FILE:LINE: what was found (what was
// expected)".
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "adjoin/core/parse_number.hpp"
#include "adjoin/ground/record.hpp"
#include "adjoin/ground/record_file.hpp"

namespace adjoin::readers {

struct Line {
  std::string_view text;
  std::size_t number = 0;  // 1-based
};

class LineReader {
 public:
  explicit LineReader(std::string_view text);
  bool next(Line& line);
  std::size_t lines_read() const { return number_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

// Every line of the text (CR of CRLF removed, UTF-8 byte-order mark skipped).
std::vector<Line> split_lines(std::string_view text);
// The first `count` lines (fewer if the text is shorter).
std::vector<Line> first_lines(std::string_view text, std::size_t count);

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
char lower(char c);
inline std::string_view trim(std::string_view s) { return trim_blanks(s); }  // core/parse_number.hpp
std::string to_lower(std::string_view s);
// Case-insensitive search; npos if absent.
std::size_t find_ci(std::string_view text, std::string_view word, std::size_t from = 0);
bool starts_with_ci(std::string_view text, std::string_view word);
// Blank, or a '#' / '%' comment.
bool skippable(std::string_view line);
std::string quote_token(std::string_view token);
// A number in a reader's message: its shortest round-trip text (core/number_text.hpp).
std::string fmt(double x);

[[noreturn]] void fail(const std::string& name, std::size_t line, const std::string& what);
[[noreturn]] void fail(const std::string& name, const std::string& what);

// Parses the number starting at p; *stop is where it ends. Accepts a leading '+', and Fortran
// 'D' exponents. "nan" and "inf" are reported as not_finite. (The project's one number
// parser, core/parse_number.hpp, with Fortran exponents.)
inline NumberStatus parse_number(const char* p, const char* end, double& value, const char*& stop) {
  return scan_number(p, end, value, stop, /*fortran_exponent=*/true);
}
// A whole field must be one number; `expected` says what it should be.
double field_number(std::string_view field, const std::string& name, std::size_t line, const std::string& expected);
// The number at `from` in `text` (leading blanks skipped), or nullopt.
std::optional<double> number_at(std::string_view text, std::size_t from, std::size_t* end = nullptr);
// The resolution a number is printed with: one unit in its last decimal.
double print_resolution(std::string_view token);
// Fields separated by runs of blanks (delimiter 0 or blank) or by the delimiter.
void split(std::string_view line, char delimiter, std::vector<std::string_view>& fields);

// A Fortran edit descriptor such as "(8F10.5)", "(10I8)", "(1E15.6)", "(5e15.7)": fields per
// line and field width. nullopt if `text` holds none that makes sense.
struct FortranFormat {
  std::size_t per_line = 0, width = 0;
};
std::optional<FortranFormat> fortran_format(std::string_view text);

// Reads `count` numbers from the lines at lines[*next...], advancing *next past the last line
// used. With a format, each line holds up to per_line fields of `width` characters (Fortran
// fixed fields, so values that touch are read right); without, values are separated by blanks
// or commas, and F-format values that touch are split at a sign. `what` names the block for
// messages ("acceleration values of channel 2"); `header_line` is where the count was read.
// The values are appended to `out` (a vector reserved from the text's size, never from the
// count alone).
void read_block(const std::vector<Line>& lines, std::size_t* next, std::size_t count,
                const std::optional<FortranFormat>& format, const std::string& name, const std::string& what,
                std::size_t header_line, std::vector<double>& out);

// Reads every number on the lines from lines[first] to the end (blank- or comma-separated,
// F-format values that touch split at a sign); `what` names a value for messages.
void read_to_end(const std::vector<Line>& lines, std::size_t first, const std::string& name, const std::string& what,
                 std::vector<double>& out);

// The unit the file declares, checked against the one the caller gave (format.units); `line`
// is where the file says it (0: the format fixes it).
AccelUnit agree_units(const RecordFormat& format, AccelUnit from_file, const std::string& name, std::size_t line,
                      const std::string& source = "the file");
void check_given_dt(const std::optional<double>& dt, const std::string& name);
// A step from the header checked against a given --dt.
void agree_dt(const RecordFormat& format, double dt, const std::string& name, std::size_t line);

// Multi-channel files: the channel asked for (1-based), or an error listing them. `labels`
// holds one label per channel, `lines` where each starts.
std::size_t pick_channel(const RecordFormat& format, const std::vector<std::string>& labels,
                         const std::vector<std::size_t>& lines, const std::string& name, const std::string& kind);

// A Record in m/s^2 from values in `unit` multiplied by `scale`.
Record finish(const std::string& name, std::string description, double dt, std::vector<double> values, AccelUnit unit,
              double scale = 1.0);

// "a | b | c" of the non-empty trimmed lines (at most `limit` characters).
std::string join_lines(const std::vector<std::string_view>& lines, std::size_t limit = 400);

}  // namespace adjoin::readers
