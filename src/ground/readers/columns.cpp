// Column text (see record_file.hpp): one column with a given dt, two columns (time,
// acceleration), and delimited text with a header line naming the columns; and the automatic
// choice among them from the first data line.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "registry.hpp"

namespace adjoin::readers {
namespace {

constexpr double kUniformTolerance = 1e-6;  // relative part of the allowed step deviation

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

// The header's column names for messages: each a short excerpt, the first 20 of them (a file
// with CR-only line ends is one long "header" line).
std::string list_names(const std::vector<std::string>& names) {
  std::string out;
  const auto plain = [](const std::string& n) {
    return n.size() <= 40 && std::none_of(n.begin(), n.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  };
  for (std::size_t i = 0; i < names.size() && i < 20; ++i)
    out += (i ? ", " : "") + std::to_string(i + 1) + ":" + (plain(names[i]) ? names[i] : quote_token(names[i]));
  if (names.size() > 20) out += ", ... (" + std::to_string(names.size()) + " columns)";
  return out;
}

int resolve_column(const std::string& wanted, const std::vector<std::string>& names, const std::string& name, std::size_t line,
                   const std::string& role) {
  const std::string_view w = trim(wanted);
  if (!w.empty() && std::all_of(w.begin(), w.end(), is_digit)) {
    std::size_t index = 0;
    parse_count(w, &index);  // digits only; too many for a size_t leave 0, which does not exist
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

// Column files may state their units in a leading comment, "# units: g" (what adjoin writes:
// record process, synth), so they read back without --units.
RecordFormat with_comment_units(std::string_view text, const std::string& name, const RecordFormat& format) {
  RecordFormat given = format;
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
  return given;
}

char first_row_delimiter(std::string_view text) {
  LineReader reader(text);
  Line line;
  while (reader.next(line))
    if (!skippable(line.text)) return guess_row_delimiter(line.text);
  return 0;
}

}  // namespace

Record parse_one_column(std::string_view text, const std::string& name, const RecordFormat& format) {
  LineReader reader(text);
  return read_one_column(reader, name, with_comment_units(text, name, format));
}

Record parse_two_column(std::string_view text, const std::string& name, const RecordFormat& format) {
  const char delimiter = format.delimiter ? format.delimiter : first_row_delimiter(text);
  LineReader reader(text);
  return read_two_column(reader, name, with_comment_units(text, name, format), delimiter);
}

Record parse_delimited(std::string_view text, const std::string& name, const RecordFormat& format) {
  LineReader reader(text);
  return read_delimited(reader, name, format);
}

Record parse_columns_auto(std::string_view text, const std::string& name, const RecordFormat& format) {
  LineReader reader(text);
  Line line;
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
  if (!numeric) return parse_delimited(text, name, format);
  if (fields.size() == 1) return parse_one_column(text, name, format);
  if (fields.size() == 2) {
    RecordFormat two = format;
    two.delimiter = delimiter;
    return parse_two_column(text, name, two);
  }
  fail(name, line.number,
       "found " + std::to_string(fields.size()) +
           " numbers on the first data line (expected 1 (one column), 2 (time, acceleration), or a header line naming "
           "the columns, or a file in one of the formats with a header: AT2, SMC, COSMOS, K-NET, ESM, DMG); say the "
           "format (--format delimited with --time-column/--accel-column)");
}

}  // namespace adjoin::readers
