// Readers for recorded accelerograms (see record_file.hpp for the formats and the rules).
//
// The text is scanned once, line by line (memchr), and numbers are parsed in place with
// std::from_chars: no streams, no per-line allocations.
#include "adjoin/ground/record_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include "adjoin/errors.hpp"

namespace adjoin {
namespace {

constexpr double kUniformTolerance = 1e-6;  // relative part of the allowed step deviation
constexpr std::size_t kHeaderSearchLines = 10;

// ---- lines and small text helpers -------------------------------------------------------

struct Line {
  std::string_view text;
  std::size_t number = 0;
};

class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
  }
  bool next(Line& line) {
    if (pos_ >= text_.size()) return false;
    const char* begin = text_.data() + pos_;
    const std::size_t left = text_.size() - pos_;
    const void* newline = std::memchr(begin, '\n', left);
    std::size_t length = newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - begin) : left;
    pos_ += length + (newline ? 1 : 0);
    if (length > 0 && begin[length - 1] == '\r') --length;
    line.text = std::string_view(begin, length);
    line.number = ++number_;
    return true;
  }
  std::size_t lines_read() const { return number_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

std::string_view trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && is_blank(s[b])) ++b;
  while (e > b && is_blank(s[e - 1])) --e;
  return s.substr(b, e - b);
}

std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = lower(c);
  return out;
}

std::size_t find_ci(std::string_view text, std::string_view word, std::size_t from = 0) {
  if (word.size() > text.size()) return std::string_view::npos;
  for (std::size_t i = from; i + word.size() <= text.size(); ++i) {
    std::size_t k = 0;
    while (k < word.size() && lower(text[i + k]) == lower(word[k])) ++k;
    if (k == word.size()) return i;
  }
  return std::string_view::npos;
}

bool skippable(std::string_view line) {
  const std::string_view t = trim(line);
  return t.empty() || t.front() == '#' || t.front() == '%';
}

std::string quote_token(std::string_view token) {
  std::string out;
  out.reserve(44);
  out.push_back('\'');
  if (token.size() > 40) {
    out.append(token.substr(0, 37));
    out.append("...");
  } else {
    out.append(token);
  }
  out.push_back('\'');
  return out;
}

std::string fmt(double x) {
  std::array<char, 32> buffer{};
  auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  return std::string(buffer.data(), result.ptr);
}

[[noreturn]] void fail(const std::string& name, std::size_t line, const std::string& what) {
  throw InputError(name + ":" + std::to_string(line) + ": " + what);
}

[[noreturn]] void fail(const std::string& name, const std::string& what) { throw InputError(name + ": " + what); }

// ---- numbers ----------------------------------------------------------------------------

enum class NumberStatus { ok, not_a_number, not_finite, out_of_range };

// Parses the number starting at p; *stop is where it ends. Accepts a leading '+', and
// Fortran 'D' exponents. from_chars also accepts "nan" and "inf": reported as not_finite.
NumberStatus parse_number(const char* p, const char* end, double& value, const char*& stop) {
  const char* q = p;
  if (q != end && *q == '+') {
    ++q;
    if (q == end || *q == '+' || *q == '-') return NumberStatus::not_a_number;
  }
  auto result = std::from_chars(q, end, value, std::chars_format::general);
  if (result.ec == std::errc::invalid_argument) return NumberStatus::not_a_number;
  stop = result.ptr;
  if (stop != end && (*stop == 'D' || *stop == 'd')) {  // 1.5D-03
    const char* e = stop + 1;
    if (e != end && (*e == '+' || *e == '-')) ++e;
    if (e != end && is_digit(*e)) {
      while (e != end && is_digit(*e)) ++e;
      std::string copy(q, e);
      copy[static_cast<std::size_t>(stop - q)] = 'e';
      auto again = std::from_chars(copy.data(), copy.data() + copy.size(), value, std::chars_format::general);
      if (again.ec == std::errc::invalid_argument) return NumberStatus::not_a_number;
      if (again.ec == std::errc::result_out_of_range) {
        value = std::strtod(copy.c_str(), nullptr);
        if (std::isinf(value)) return NumberStatus::out_of_range;
      }
      stop = e;
      return std::isfinite(value) ? NumberStatus::ok : NumberStatus::not_finite;
    }
  }
  if (result.ec == std::errc::result_out_of_range) {
    // from_chars leaves the value alone on overflow and on underflow; strtod tells which.
    const std::string copy(q, stop);
    value = std::strtod(copy.c_str(), nullptr);
    if (std::isinf(value)) return NumberStatus::out_of_range;
  }
  return std::isfinite(value) ? NumberStatus::ok : NumberStatus::not_finite;
}

// A whole field must be one number.
double field_number(std::string_view field, const std::string& name, std::size_t line, const std::string& expected) {
  field = trim(field);
  if (field.empty()) fail(name, line, "empty field (expected " + expected + ")");
  double value = 0.0;
  const char* stop = field.data();
  const char* end = field.data() + field.size();
  switch (parse_number(field.data(), end, value, stop)) {
    case NumberStatus::ok:
      if (stop == end) return value;
      break;
    case NumberStatus::not_finite:
      fail(name, line, quote_token(field) + " is not a finite number (expected " + expected + ")");
    case NumberStatus::out_of_range:
      fail(name, line, quote_token(field) + " is out of the range of double (expected " + expected + ")");
    case NumberStatus::not_a_number: break;
  }
  fail(name, line, quote_token(field) + " is not a number (expected " + expected + ")");
}

// The resolution a number is printed with: one unit in its last decimal ("0.02000" -> 1e-5,
// "2.0000000e-002" -> 1e-9, "31" -> 1).
double print_resolution(std::string_view token) {
  static const std::array<double, 61> powers = [] {
    std::array<double, 61> p{};
    for (int i = 0; i < 61; ++i) p[static_cast<std::size_t>(i)] = std::pow(10.0, i - 30);
    return p;
  }();
  int decimals = 0;
  std::size_t i = 0;
  while (i < token.size() && token[i] != '.' && token[i] != 'e' && token[i] != 'E' && token[i] != 'd' && token[i] != 'D') ++i;
  if (i < token.size() && token[i] == '.') {
    ++i;
    while (i < token.size() && is_digit(token[i])) ++decimals, ++i;
  }
  int exponent = 0;
  if (i < token.size() && (token[i] == 'e' || token[i] == 'E' || token[i] == 'd' || token[i] == 'D')) {
    const char* p = token.data() + i + 1;
    const char* end = token.data() + token.size();
    if (p != end && *p == '+') ++p;
    std::from_chars(p, end, exponent);
  }
  const int k = exponent - decimals + 30;
  if (k >= 0 && k < 61) return powers[static_cast<std::size_t>(k)];
  return std::pow(10.0, exponent - decimals);
}

// ---- rows ---------------------------------------------------------------------------------

// Splits a line into fields: on runs of blanks (delimiter 0), or on the delimiter. Fields are
// trimmed by the caller.
void split(std::string_view line, char delimiter, std::vector<std::string_view>& fields) {
  fields.clear();
  if (delimiter == 0 || is_blank(delimiter)) {
    std::size_t i = 0;
    while (true) {
      while (i < line.size() && is_blank(line[i])) ++i;
      if (i >= line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !is_blank(line[i])) ++i;
      fields.push_back(line.substr(start, i - start));
    }
    return;
  }
  line = trim(line);
  std::size_t start = 0;
  while (true) {
    const std::size_t at = line.find(delimiter, start);
    if (at == std::string_view::npos) {
      fields.push_back(line.substr(start));
      break;
    }
    fields.push_back(line.substr(start, at - start));
    start = at + 1;
  }
}

struct TableSpec {
  char delimiter = 0;
  std::size_t columns = 2;  // fields expected on every row
  int time = -1;            // column index, or -1 for none
  int accel = 1;
  std::string expected;     // "2 numbers: time and acceleration"
};

struct Samples {
  std::vector<double> time, accel, resolution;
  std::vector<std::size_t> lines;
  std::size_t last_line = 0;
};

void read_rows(LineReader& reader, const std::string& name, const TableSpec& spec, Samples& out) {
  Line line;
  std::vector<std::string_view> fields;
  const std::string what_time = "a time in s";
  const std::string what_accel = "an acceleration";
  while (reader.next(line)) {
    if (skippable(line.text)) continue;
    split(line.text, spec.delimiter, fields);
    if (fields.size() == spec.columns + 1 && trim(fields.back()).empty()) fields.pop_back();  // "1,2,"
    if (fields.size() != spec.columns)
      fail(name, line.number,
           "found " + std::to_string(fields.size()) + (fields.size() == 1 ? " field" : " fields") + " (expected " +
               spec.expected + ")");
    if (spec.time >= 0) {
      const std::string_view field = trim(fields[static_cast<std::size_t>(spec.time)]);
      out.time.push_back(field_number(field, name, line.number, what_time));
      out.resolution.push_back(print_resolution(field));
      out.lines.push_back(line.number);
    }
    out.accel.push_back(field_number(fields[static_cast<std::size_t>(spec.accel)], name, line.number, what_accel));
    out.last_line = line.number;
  }
  if (out.accel.empty()) fail(name, std::max<std::size_t>(reader.lines_read(), 1), "no data rows (expected " + spec.expected + ")");
}

// dt from a time column: strictly increasing, uniform within the documented tolerance.
double uniform_step(const Samples& s, const std::string& name) {
  const std::size_t n = s.time.size();
  if (n < 2) fail(name, s.last_line, "only one sample: dt cannot be taken from the time column (expected at least 2 rows)");
  for (std::size_t i = 1; i < n; ++i)
    if (!(s.time[i] > s.time[i - 1]))
      fail(name, s.lines[i],
           "time " + fmt(s.time[i]) + " does not increase (previous time " + fmt(s.time[i - 1]) + " on line " +
               std::to_string(s.lines[i - 1]) + "; expected strictly increasing, uniformly spaced times)");
  // Reference step: the median step, so a single gap is reported where it is.
  std::vector<double> steps(n - 1);
  for (std::size_t i = 1; i < n; ++i) steps[i - 1] = s.time[i] - s.time[i - 1];
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  const double reference = steps[steps.size() / 2];
  for (std::size_t i = 1; i < n; ++i) {
    const double step = s.time[i] - s.time[i - 1];
    const double tolerance =
        kUniformTolerance * reference + std::min(0.5 * (s.resolution[i] + s.resolution[i - 1]), 0.25 * reference);
    if (std::abs(step - reference) > tolerance)
      fail(name, s.lines[i],
           "time " + fmt(s.time[i]) + " is " + fmt(step) + " s after the previous one, but the record's step is " +
               fmt(reference) + " s (expected uniformly spaced times)");
  }
  // Rounded to 12 significant digits, so times printed as 24.979999999999997 give dt = 0.02.
  const double dt = (s.time.back() - s.time.front()) / static_cast<double>(n - 1);
  std::array<char, 32> buffer{};
  const auto printed = std::to_chars(buffer.data(), buffer.data() + buffer.size(), dt, std::chars_format::general, 12);
  double rounded = dt;
  std::from_chars(buffer.data(), printed.ptr, rounded);
  return rounded;
}

AccelUnit require_units(const RecordFormat& format, const std::optional<AccelUnit>& from_file, const std::string& name,
                        const std::string& kind) {
  if (from_file && format.units && *from_file != *format.units)
    fail(name, "the file says units of " + to_string(*from_file) + " but " + to_string(*format.units) + " was given");
  if (from_file) return *from_file;
  if (format.units) return *format.units;
  fail(name, kind + " files carry no units: give them (--units g|m/s2|cm/s2|mm/s2, or units in the scene)");
}

void check_given_dt(const std::optional<double>& dt, const std::string& name) {
  if (dt && !(std::isfinite(*dt) && *dt > 0.0)) fail(name, "dt must be a positive number of seconds, got " + fmt(*dt));
}

Record finish(const std::string& name, std::string description, double dt, std::vector<double> accel, AccelUnit unit) {
  Record record;
  record.source = name;
  record.description = std::move(description);
  record.dt = dt;
  record.accel = std::move(accel);
  const double factor = to_m_s2(unit);
  if (factor != 1.0)
    for (double& a : record.accel) a *= factor;
  return record;
}

// Time column -> dt (checked against a given dt), description notes a shifted origin.
double step_from_times(const Samples& samples, const RecordFormat& format, const std::string& name, std::string& description) {
  const double dt = uniform_step(samples, name);
  const double rounding = 0.5 * (samples.resolution.front() + samples.resolution.back()) / static_cast<double>(samples.time.size() - 1);
  if (format.dt && std::abs(*format.dt - dt) > kUniformTolerance * dt + std::min(rounding, 0.25 * dt))
    fail(name, "the time column gives dt = " + fmt(dt) + " s but dt = " + fmt(*format.dt) + " s was given");
  if (samples.time.front() != 0.0) description += (description.empty() ? "" : "; ") + std::string("time column starts at ") + fmt(samples.time.front()) + " s (shifted to 0)";
  return dt;
}

char guess_row_delimiter(std::string_view line) {
  if (line.find(',') != std::string_view::npos) return ',';
  if (line.find(';') != std::string_view::npos) return ';';
  return 0;
}

// ---- one and two columns ------------------------------------------------------------------

Record read_one_column(LineReader& reader, const std::string& name, const RecordFormat& format) {
  check_given_dt(format.dt, name);
  if (!format.dt) fail(name, "a one-column record has no time column: give the sample step (--dt SECONDS, or dt in the scene)");
  const AccelUnit unit = require_units(format, std::nullopt, name, "one-column");
  TableSpec spec;
  spec.delimiter = format.delimiter;
  spec.columns = 1;
  spec.time = -1;
  spec.accel = 0;
  spec.expected = "1 number per line: the acceleration";
  Samples samples;
  read_rows(reader, name, spec, samples);
  return finish(name, "one-column text", *format.dt, std::move(samples.accel), unit);
}

Record read_two_column(LineReader& reader, const std::string& name, const RecordFormat& format, char delimiter) {
  check_given_dt(format.dt, name);
  const AccelUnit unit = require_units(format, std::nullopt, name, "two-column");
  TableSpec spec;
  spec.delimiter = delimiter;
  spec.columns = 2;
  spec.time = 0;
  spec.accel = 1;
  spec.expected = "2 numbers per line: time and acceleration";
  Samples samples;
  read_rows(reader, name, spec, samples);
  std::string description = "two-column text";
  const double dt = step_from_times(samples, format, name, description);
  return finish(name, description, dt, std::move(samples.accel), unit);
}

// ---- delimited with a header ----------------------------------------------------------

std::string_view strip_quotes(std::string_view s) {
  s = trim(s);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) s = trim(s.substr(1, s.size() - 2));
  return s;
}

// The name without a unit suffix: "acc [g]" -> "acc".
std::string base_name(std::string_view name) {
  const std::size_t at = name.find_first_of("[(");
  return to_lower(trim(name.substr(0, at)));
}

std::optional<AccelUnit> unit_in_name(std::string_view name) {
  const std::size_t open = name.find_first_of("[(");
  if (open == std::string_view::npos) return std::nullopt;
  const std::size_t close = name.find_first_of("])", open + 1);
  if (close == std::string_view::npos) return std::nullopt;
  AccelUnit unit;
  if (parse_accel_unit(std::string(name.substr(open + 1, close - open - 1)), &unit)) return unit;
  return std::nullopt;
}

std::string list_names(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + std::to_string(i + 1) + ":" + names[i];
  return out;
}

int resolve_column(const std::string& wanted, const std::vector<std::string>& names, const std::string& name, std::size_t line,
                   const std::string& role) {
  const std::string_view w = trim(wanted);
  if (!w.empty() && std::all_of(w.begin(), w.end(), is_digit)) {
    std::size_t index = 0;
    std::from_chars(w.data(), w.data() + w.size(), index);
    if (index < 1 || index > names.size())
      fail(name, line, role + " column " + std::string(w) + " does not exist (expected 1.." + std::to_string(names.size()) +
                           "; header: " + list_names(names) + ")");
    return static_cast<int>(index - 1);
  }
  const std::string lw = to_lower(w);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (to_lower(names[i]) == lw) return static_cast<int>(i);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (base_name(names[i]) == lw) return static_cast<int>(i);
  fail(name, line, "no " + role + " column named " + quote_token(w) + " (header: " + list_names(names) + ")");
}

Record read_delimited(LineReader& reader, const std::string& name, const RecordFormat& format) {
  check_given_dt(format.dt, name);
  Line header;
  bool found = false;
  while (reader.next(header))
    if (!skippable(header.text)) {
      found = true;
      break;
    }
  if (!found) fail(name, std::max<std::size_t>(reader.lines_read(), 1), "empty file (expected a header line naming the columns)");

  char delimiter = format.delimiter;
  if (delimiter == 0) {
    if (header.text.find(',') != std::string_view::npos)
      delimiter = ',';
    else if (header.text.find(';') != std::string_view::npos)
      delimiter = ';';
    else if (header.text.find('\t') != std::string_view::npos)
      delimiter = '\t';
  }
  std::vector<std::string_view> fields;
  split(header.text, delimiter, fields);
  std::vector<std::string> names;
  if (fields.size() > 1 && trim(fields.back()).empty()) fields.pop_back();  // "t,a,"
  for (auto f : fields) names.emplace_back(strip_quotes(f));

  int time = -1, accel = -1;
  if (!format.time_column.empty())
    time = resolve_column(format.time_column, names, name, header.number, "time");
  else if (!format.dt) {
    for (std::size_t i = 0; i < names.size() && time < 0; ++i) {
      const std::string b = base_name(names[i]);
      if (b == "t" || b.rfind("time", 0) == 0) time = static_cast<int>(i);
    }
    if (time < 0 && names.size() == 2) time = 0;
    if (time < 0)
      fail(name, header.number, "no time column found (header: " + list_names(names) +
                                    "); name it (--time-column NAME|INDEX) or give the step (--dt SECONDS)");
  }
  if (!format.accel_column.empty()) {
    accel = resolve_column(format.accel_column, names, name, header.number, "acceleration");
  } else {
    if (names.size() == 2 && time >= 0) accel = 1 - time;
    if (names.size() == 1 && time < 0) accel = 0;
    for (std::size_t i = 0; i < names.size() && accel < 0; ++i) {
      const std::string b = base_name(names[i]);
      if (static_cast<int>(i) != time && (b == "a" || b == "ag" || b == "a_g" || b.rfind("acc", 0) == 0)) accel = static_cast<int>(i);
    }
    if (accel < 0)
      fail(name, header.number, "which column holds the acceleration? (header: " + list_names(names) +
                                    "; expected --accel-column NAME|INDEX)");
  }
  if (accel == time) fail(name, header.number, "the time and acceleration columns are the same column");

  const AccelUnit unit = require_units(format, unit_in_name(names[static_cast<std::size_t>(accel)]), name, "delimited");
  TableSpec spec;
  spec.delimiter = delimiter;
  spec.columns = names.size();
  spec.time = time;
  spec.accel = accel;
  spec.expected = std::to_string(names.size()) + " fields as in the header on line " + std::to_string(header.number);
  Samples samples;
  read_rows(reader, name, spec, samples);
  std::string description = "delimited text, column " + names[static_cast<std::size_t>(accel)];
  const double dt = time >= 0 ? step_from_times(samples, format, name, description) : *format.dt;
  return finish(name, description, dt, std::move(samples.accel), unit);
}

// ---- PEER AT2 ------------------------------------------------------------------------------

// Units from AT2 header lines: "... IN UNITS OF G", or a unit word on an acceleration line.
std::optional<AccelUnit> at2_units(const std::vector<Line>& header, const std::string& name, std::size_t* where) {
  for (const Line& line : header) {
    const std::string l = to_lower(line.text);
    const bool accel = l.find("accel") != std::string::npos;
    if (!accel && (l.find("velocity") != std::string::npos || l.find("displacement") != std::string::npos))
      fail(name, line.number, "this is a velocity or displacement record (expected an acceleration time series)");
    const std::size_t of = l.find("units of");
    if (of != std::string::npos) {
      std::string_view rest = trim(std::string_view(line.text).substr(of + 8));
      std::size_t end = 0;
      while (end < rest.size() && !is_blank(rest[end]) && rest[end] != ',') ++end;
      std::string word(rest.substr(0, end));
      while (!word.empty() && (word.back() == '.' || word.back() == ')' || word.back() == ']')) word.pop_back();
      AccelUnit unit;
      if (!parse_accel_unit(word, &unit))
        fail(name, line.number, "unknown units " + quote_token(word) + " (expected G, M/S2, CM/SEC/SEC or MM/S2)");
      *where = line.number;
      return unit;
    }
    if (accel) {
      std::vector<std::string_view> words;
      std::string cleaned(line.text);
      for (char& c : cleaned)
        if (c == '(' || c == ')' || c == '[' || c == ']' || c == ',' || c == ':' || c == ';') c = ' ';
      split(cleaned, 0, words);
      for (auto w : words) {
        AccelUnit unit;
        if (parse_accel_unit(std::string(w), &unit)) {
          *where = line.number;
          return unit;
        }
      }
    }
  }
  return std::nullopt;
}

double header_number(std::string_view text, std::size_t from, const std::string& name, std::size_t line, const std::string& what) {
  while (from < text.size() && is_blank(text[from])) ++from;
  double value = 0.0;
  const char* stop = nullptr;
  const char* end = text.data() + text.size();
  if (from >= text.size() || parse_number(text.data() + from, end, value, stop) != NumberStatus::ok)
    fail(name, line, "cannot read " + what + " in " + quote_token(trim(text)) + " (expected e.g. 'NPTS=  7814, DT=   .0050 SEC')");
  return value;
}

Record read_at2(LineReader& reader, const std::string& name, const RecordFormat& format) {
  check_given_dt(format.dt, name);
  std::vector<Line> header;
  Line line;
  bool found = false;
  while (reader.next(line)) {
    if (find_ci(line.text, "NPTS") != std::string_view::npos) {
      found = true;
      break;
    }
    header.push_back(line);
    if (header.size() >= kHeaderSearchLines) break;
  }
  if (!found) {
    if (reader.lines_read() == 0) fail(name, 1, "empty file (expected a PEER AT2 record)");
    fail(name, reader.lines_read(), "no NPTS/DT line in the AT2 header (expected e.g. 'NPTS=  7814, DT=   .0050 SEC')");
  }

  // NPTS and DT: "NPTS= n, DT= x SEC" or the older "n  x  NPTS, DT".
  const std::string_view text = line.text;
  const std::size_t npts_at = find_ci(text, "NPTS");
  double npts_value = 0.0, dt = 0.0;
  std::size_t after = npts_at + 4;
  while (after < text.size() && is_blank(text[after])) ++after;
  if (after < text.size() && text[after] == '=') {
    npts_value = header_number(text, after + 1, name, line.number, "NPTS");
    std::size_t dt_at = find_ci(text, "DT", after);
    while (dt_at != std::string_view::npos) {
      std::size_t eq = dt_at + 2;
      while (eq < text.size() && is_blank(text[eq])) ++eq;
      if (eq < text.size() && text[eq] == '=') {
        dt = header_number(text, eq + 1, name, line.number, "DT");
        break;
      }
      dt_at = find_ci(text, "DT", dt_at + 2);
    }
    if (dt_at == std::string_view::npos) fail(name, line.number, "no DT= after NPTS= (expected e.g. 'NPTS=  7814, DT=   .0050 SEC')");
  } else {
    std::vector<std::string_view> words;
    split(text.substr(0, npts_at), 0, words);
    if (words.size() < 2) fail(name, line.number, "cannot read NPTS and DT in " + quote_token(trim(text)) + " (expected 'NPTS=  7814, DT=   .0050 SEC' or '7814  .0050  NPTS, DT')");
    npts_value = field_number(words[0], name, line.number, "NPTS, a whole number");
    dt = field_number(words[1], name, line.number, "DT in s");
  }
  if (!(npts_value >= 1.0 && npts_value == std::floor(npts_value) && npts_value < 1e12))
    fail(name, line.number, "NPTS = " + fmt(npts_value) + " (expected a positive whole number)");
  if (!(dt > 0.0)) fail(name, line.number, "DT = " + fmt(dt) + " (expected a positive step in s)");
  const auto npts = static_cast<std::size_t>(npts_value);
  const std::size_t npts_line = line.number;

  std::size_t units_line = 0;
  const std::optional<AccelUnit> header_units = at2_units(header, name, &units_line);
  if (header_units && format.units && *header_units != *format.units)
    fail(name, units_line, "the header says units of " + to_string(*header_units) + " but " + to_string(*format.units) + " was given");
  if (!header_units && !format.units)
    fail(name, npts_line, "no units in the AT2 header (expected '... IN UNITS OF G'); give them (--units g|m/s2|cm/s2|mm/s2)");
  const AccelUnit unit = header_units ? *header_units : *format.units;
  if (format.dt && std::abs(*format.dt - dt) > kUniformTolerance * dt)
    fail(name, npts_line, "the header says DT = " + fmt(dt) + " s but dt = " + fmt(*format.dt) + " s was given");

  std::vector<double> accel;
  accel.reserve(std::min<std::size_t>(npts, 1 << 26));
  std::size_t last_value_line = npts_line;
  while (reader.next(line)) {
    const char* p = line.text.data();
    const char* end = p + line.text.size();
    while (true) {
      while (p != end && (is_blank(*p) || *p == ',')) ++p;
      if (p == end) break;
      if (accel.size() == npts) {
        const char* q = p;
        while (q != end && !is_blank(*q)) ++q;
        fail(name, line.number, "more values than NPTS = " + std::to_string(npts) + " (found " + quote_token(std::string_view(p, static_cast<std::size_t>(q - p))) + ")");
      }
      double value = 0.0;
      const char* stop = p;
      const NumberStatus status = parse_number(p, end, value, stop);
      // A number ends at a blank, a comma, the line end, or (F-format values that touch) a sign.
      if (status != NumberStatus::ok || (stop != end && !is_blank(*stop) && *stop != ',' && *stop != '-')) {
        const char* q = p;
        while (q != end && !is_blank(*q)) ++q;
        const std::string token(p, q);
        const std::string expected = "value " + std::to_string(accel.size() + 1) + " of NPTS = " + std::to_string(npts);
        if (status == NumberStatus::not_finite) fail(name, line.number, quote_token(token) + " is not a finite number (expected " + expected + ")");
        fail(name, line.number, quote_token(token) + " is not a number (expected " + expected + ")");
      }
      accel.push_back(value);
      p = stop;
    }
    if (!accel.empty()) last_value_line = std::max(last_value_line, line.number);
  }
  if (accel.size() != npts)
    fail(name, std::max(reader.lines_read(), last_value_line),
         "the file ends after " + std::to_string(accel.size()) + " values, but the header (line " + std::to_string(npts_line) +
             ") says NPTS = " + std::to_string(npts) + " (truncated file?)");

  std::string description;
  for (const Line& h : header) {
    const std::string_view t = trim(h.text);
    if (t.empty()) continue;
    if (!description.empty()) description += " | ";
    description += t;
  }
  return finish(name, description, dt, std::move(accel), unit);
}

// ---- format detection ----------------------------------------------------------------------

bool has_at2_extension(const std::string& name) {
  return name.size() >= 4 && to_lower(std::string_view(name).substr(name.size() - 4)) == ".at2";
}

}  // namespace

bool parse_record_kind(const std::string& name, RecordFormat::Kind* kind) {
  const std::string n = to_lower(trim(name));
  RecordFormat::Kind k;
  if (n == "auto" || n == "automatic")
    k = RecordFormat::Kind::automatic;
  else if (n == "at2" || n == "peer")
    k = RecordFormat::Kind::at2;
  else if (n == "one-column" || n == "one_column" || n == "1col")
    k = RecordFormat::Kind::one_column;
  else if (n == "two-column" || n == "two_column" || n == "2col")
    k = RecordFormat::Kind::two_column;
  else if (n == "delimited" || n == "csv")
    k = RecordFormat::Kind::delimited;
  else
    return false;
  if (kind) *kind = k;
  return true;
}

std::string to_string(RecordFormat::Kind kind) {
  switch (kind) {
    case RecordFormat::Kind::automatic: return "auto";
    case RecordFormat::Kind::at2: return "at2";
    case RecordFormat::Kind::one_column: return "one-column";
    case RecordFormat::Kind::two_column: return "two-column";
    case RecordFormat::Kind::delimited: return "delimited";
  }
  return "?";
}

// The ranges every computation on a record stays finite in (intensity measures square and
// integrate the accelerations, spectra divide by the step): a sampling interval from 1e-6 s
// to 10 s, accelerations within 1e6 g.
void check_ranges(const Record& record, const std::string& name) {
  if (!(record.dt >= 1e-6 && record.dt <= 10.0))
    fail(name, "a sampling interval of " + fmt(record.dt) + " s is outside what accelerograms have (1e-6 s to 10 s)");
  constexpr double kLimit = 1e6 * 9.80665;
  for (std::size_t i = 0; i < record.accel.size(); ++i)
    if (!(std::abs(record.accel[i]) <= kLimit))
      fail(name, "sample " + std::to_string(i + 1) + " (t = " + fmt(static_cast<double>(i) * record.dt) + " s) is " +
                     fmt(record.accel[i] / 9.80665) + " g, beyond the 1e6 g an accelerogram can have (check the units)");
}

Record parse_record(std::string_view text, const std::string& name, const RecordFormat& format) {
  using Kind = RecordFormat::Kind;
  Kind kind = format.kind;
  char row_delimiter = format.delimiter;
  if (kind == Kind::automatic) {
    LineReader probe(text);
    Line line;
    bool at2 = has_at2_extension(name);
    for (std::size_t i = 0; i < kHeaderSearchLines && !at2 && probe.next(line); ++i)
      if (find_ci(line.text, "NPTS") != std::string_view::npos) at2 = true;
    if (at2) {
      kind = Kind::at2;
    } else {
      LineReader reader(text);
      bool found = false;
      while (reader.next(line))
        if (!skippable(line.text)) {
          found = true;
          break;
        }
      if (!found) fail(name, std::max<std::size_t>(reader.lines_read(), 1), "empty file (expected an accelerogram)");
      const char delimiter = format.delimiter ? format.delimiter : guess_row_delimiter(line.text);
      std::vector<std::string_view> fields;
      split(line.text, delimiter, fields);
      bool numeric = true;
      for (auto f : fields) {
        f = trim(f);
        double value = 0.0;
        const char* stop = nullptr;
        if (f.empty() || parse_number(f.data(), f.data() + f.size(), value, stop) == NumberStatus::not_a_number ||
            stop != f.data() + f.size()) {
          numeric = false;
          break;
        }
      }
      if (!numeric) {
        kind = Kind::delimited;
      } else if (fields.size() == 1) {
        kind = Kind::one_column;
      } else if (fields.size() == 2) {
        kind = Kind::two_column;
        row_delimiter = delimiter;
      } else {
        fail(name, line.number,
             "found " + std::to_string(fields.size()) +
                 " numbers on the first data line (expected 1 (one column), 2 (time, acceleration), or a header line naming "
                 "the columns); say the format (--format delimited with --time-column/--accel-column)");
      }
    }
  } else if (kind == Kind::two_column && row_delimiter == 0) {
    LineReader reader(text);
    Line line;
    while (reader.next(line))
      if (!skippable(line.text)) {
        row_delimiter = guess_row_delimiter(line.text);
        break;
      }
  }

  // Column files may state their units in a leading comment, "# units: g" (what adjoin
  // writes: record process, synth), so they read back without --units.
  RecordFormat given = format;
  if (kind == Kind::one_column || kind == Kind::two_column) {
    LineReader scan(text);
    Line line;
    while (scan.next(line)) {
      const std::string_view t = trim(line.text);
      if (t.empty()) continue;
      if (t.front() != '#') break;
      std::string_view body = trim(t.substr(1));
      if (body.size() < 6 || find_ci(body.substr(0, 6), "units:") != 0) continue;
      const std::string word(trim(body.substr(6)));
      AccelUnit unit;
      if (!parse_accel_unit(word, &unit)) fail(name, line.number, "unknown units " + quote_token(word) + " (expected g, m/s2, cm/s2 or mm/s2)");
      if (format.units && *format.units != unit)
        fail(name, line.number, "the file says units of " + to_string(unit) + " but " + to_string(*format.units) + " was given");
      given.units = unit;
      break;
    }
  }
  LineReader reader(text);
  Record record;
  switch (kind) {
    case Kind::at2: record = read_at2(reader, name, format); break;
    case Kind::one_column: record = read_one_column(reader, name, given); break;
    case Kind::two_column: record = read_two_column(reader, name, given, row_delimiter); break;
    case Kind::delimited: record = read_delimited(reader, name, format); break;
    case Kind::automatic: fail(name, "unknown record format");
  }
  check_ranges(record, name);
  return record;
}

Record read_record(const std::filesystem::path& path, const RecordFormat& format) {
  const std::string name = path.string();
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) fail(name, "is a folder (expected a record file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(name, std::string("cannot open the record file: ") + std::strerror(errno));
  std::string text;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size > 0) {
    text.resize(static_cast<std::size_t>(size));
    in.seekg(0, std::ios::beg);
    in.read(text.data(), size);
    if (!in) fail(name, "cannot read the record file");
  }
  return parse_record(text, name, format);
}

}  // namespace adjoin
