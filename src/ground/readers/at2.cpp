// PEER AT2 (see record_file.hpp): free-text header lines, a line with NPTS and DT, then NPTS
// values in any fixed or free layout.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "registry.hpp"

namespace adjoin::readers {
namespace {

constexpr std::size_t kHeaderSearchLines = 10;
constexpr double kUniformTolerance = 1e-6;  // a given dt must agree with DT within this (relative)

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

Record read_at2(LineReader& reader, const std::string& name, const RecordFormat& format, std::size_t text_size) {
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
  accel.reserve(std::min<std::size_t>(npts, text_size / 2 + 1));  // each value takes 2 characters or more
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

}  // namespace

// NPTS in the first ten lines, or a name ending in .at2.
int sniff_at2(const Probe& probe) {
  const std::string_view name = probe.name;
  if (name.size() >= 4 && to_lower(name.substr(name.size() - 4)) == ".at2") return 60;
  for (std::size_t i = 0; i < probe.head.size() && i < kHeaderSearchLines; ++i)
    if (find_ci(probe.head[i].text, "NPTS") != std::string_view::npos) return 50;
  return 0;
}

Record parse_at2(std::string_view text, const std::string& name, const RecordFormat& format) {
  LineReader reader(text);
  return read_at2(reader, name, format, text.size());
}

}  // namespace adjoin::readers
