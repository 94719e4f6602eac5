// Internal text scanning shared by the record readers (see text.hpp).
#include "text.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/number_text.hpp"

namespace adjoin::readers {

LineReader::LineReader(std::string_view text) : text_(text) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

bool LineReader::next(Line& line) {
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

std::vector<Line> split_lines(std::string_view text) {
  std::vector<Line> lines;
  LineReader reader(text);
  Line line;
  while (reader.next(line)) lines.push_back(line);
  return lines;
}

std::vector<Line> first_lines(std::string_view text, std::size_t count) {
  std::vector<Line> lines;
  LineReader reader(text);
  Line line;
  while (lines.size() < count && reader.next(line)) lines.push_back(line);
  return lines;
}

char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = lower(c);
  return out;
}

std::size_t find_ci(std::string_view text, std::string_view word, std::size_t from) {
  if (word.size() > text.size()) return std::string_view::npos;
  for (std::size_t i = from; i + word.size() <= text.size(); ++i) {
    std::size_t k = 0;
    while (k < word.size() && lower(text[i + k]) == lower(word[k])) ++k;
    if (k == word.size()) return i;
  }
  return std::string_view::npos;
}

bool starts_with_ci(std::string_view text, std::string_view word) {
  return text.size() >= word.size() && find_ci(text.substr(0, word.size()), word) == 0;
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
  // Messages are printable text: control bytes of a binary file are shown as '?'.
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

std::string fmt(double x) { return shortest_text(x); }

void fail(const std::string& name, std::size_t line, const std::string& what) {
  throw InputError(name + ":" + std::to_string(line) + ": " + what);
}

void fail(const std::string& name, const std::string& what) { throw InputError(name + ": " + what); }

double field_number(std::string_view field, const std::string& name, std::size_t line, const std::string& expected) {
  field = trim(field);
  if (field.empty()) fail(name, line, "empty field (expected " + expected + ")");
  double value = 0.0;
  const char* stop = field.data();
  const char* end = field.data() + field.size();
  NumberStatus status = parse_number(field.data(), end, value, stop);
  if (status == NumberStatus::ok && stop == end) return value;
  if (status == NumberStatus::ok) status = NumberStatus::not_a_number;  // text after the number
  fail(name, line, quote_token(field) + " " + number_problem(status) + " (expected " + expected + ")");
}

std::optional<double> number_at(std::string_view text, std::size_t from, std::size_t* end) {
  while (from < text.size() && is_blank(text[from])) ++from;
  if (from >= text.size()) return std::nullopt;
  double value = 0.0;
  const char* stop = nullptr;
  if (parse_number(text.data() + from, text.data() + text.size(), value, stop) != NumberStatus::ok) return std::nullopt;
  if (end) *end = static_cast<std::size_t>(stop - text.data());
  return value;
}

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

std::optional<FortranFormat> fortran_format(std::string_view text) {
  const std::size_t open = text.find('(');
  if (open == std::string_view::npos) return std::nullopt;
  std::size_t i = open + 1;
  while (i < text.size() && is_blank(text[i])) ++i;
  std::size_t per_line = 0, width = 0;
  const auto digits = [&](std::size_t& n) {
    const std::size_t start = i;
    n = 0;
    while (i < text.size() && is_digit(text[i]) && i - start < 6) n = n * 10 + static_cast<std::size_t>(text[i++] - '0');
    return i > start;
  };
  if (!digits(per_line)) per_line = 1;
  if (i >= text.size()) return std::nullopt;
  const char letter = lower(text[i++]);
  if (letter != 'f' && letter != 'e' && letter != 'i' && letter != 'g' && letter != 'd') return std::nullopt;
  if (!digits(width)) return std::nullopt;
  if (per_line < 1 || per_line > 100 || width < 1 || width > 40) return std::nullopt;
  return FortranFormat{per_line, width};
}

namespace {

// Numbers on one line, blank- or comma-separated, F-format values that touch split at a sign.
// Stops after `limit` values. Returns false on a token that is not a finite number (*bad, *status).
bool line_tokens(std::string_view text, std::size_t limit, std::vector<double>& out, std::size_t* taken,
                 std::string_view* bad, NumberStatus* status, std::string_view* rest) {
  const char* p = text.data();
  const char* end = p + text.size();
  *taken = 0;
  while (true) {
    while (p != end && (is_blank(*p) || *p == ',')) ++p;
    if (p == end) break;
    if (*taken == limit) {
      *rest = std::string_view(p, static_cast<std::size_t>(end - p));
      return true;
    }
    double value = 0.0;
    const char* stop = p;
    const NumberStatus s = parse_number(p, end, value, stop);
    if (s != NumberStatus::ok || (stop != end && !is_blank(*stop) && *stop != ',' && *stop != '-')) {
      const char* q = p;
      while (q != end && !is_blank(*q)) ++q;
      *bad = std::string_view(p, static_cast<std::size_t>(q - p));
      *status = s == NumberStatus::ok ? NumberStatus::not_a_number : s;
      return false;
    }
    out.push_back(value);
    ++*taken;
    p = stop;
  }
  *rest = {};
  return true;
}

[[noreturn]] void bad_token(const std::string& name, std::size_t line, std::string_view token, NumberStatus status,
                            const std::string& expected) {
  if (status == NumberStatus::not_finite) fail(name, line, quote_token(token) + " is not a finite number (expected " + expected + ")");
  if (status == NumberStatus::out_of_range)
    fail(name, line, quote_token(token) + " is out of the range of double (expected " + expected + ")");
  fail(name, line, quote_token(token) + " is not a number (expected " + expected + ")");
}

// Fixed fields of one line; false if a field is not a number (then the caller tries tokens).
bool line_fields(std::string_view text, std::size_t fields, std::size_t width, std::vector<double>& out) {
  const std::size_t before = out.size();
  for (std::size_t f = 0; f < fields; ++f) {
    const std::size_t at = f * width;
    if (at >= text.size()) break;
    const std::string_view field = trim(text.substr(at, width));
    double value = 0.0;
    const char* stop = nullptr;
    if (field.empty() || parse_number(field.data(), field.data() + field.size(), value, stop) != NumberStatus::ok ||
        stop != field.data() + field.size()) {
      out.resize(before);
      return false;
    }
    out.push_back(value);
  }
  if (out.size() - before != fields || !trim(text.substr(std::min(text.size(), fields * width))).empty()) {
    out.resize(before);
    return false;
  }
  return true;
}

std::size_t chars_from(const std::vector<Line>& lines, std::size_t first) {
  if (first >= lines.size()) return 0;
  const char* begin = lines[first].text.data();
  const char* end = lines.back().text.data() + lines.back().text.size();
  return static_cast<std::size_t>(end - begin);
}

}  // namespace

void read_block(const std::vector<Line>& lines, std::size_t* next, std::size_t count,
                const std::optional<FortranFormat>& format, const std::string& name, const std::string& what,
                std::size_t header_line, std::vector<double>& out) {
  // Never reserve from the header's count alone: each value takes at least 2 characters.
  out.reserve(out.size() + std::min(count, chars_from(lines, *next) / 2 + 1));
  std::size_t got = 0;
  const std::string counted = std::to_string(count);
  while (got < count) {
    if (*next >= lines.size()) {
      const std::size_t last = lines.empty() ? 1 : lines.back().number;
      fail(name, last, "the file ends after " + std::to_string(got) + " " + what + ", but line " +
                           std::to_string(header_line) + " says " + counted + " (truncated file?)");
    }
    const Line& line = lines[(*next)++];
    const std::size_t wanted = format ? std::min(format->per_line, count - got) : count - got;
    if (format && line_fields(line.text, wanted, format->width, out)) {
      got += wanted;
      continue;
    }
    std::size_t taken = 0;
    std::string_view bad, rest;
    NumberStatus status = NumberStatus::ok;
    const std::string expected = "value " + std::to_string(got + 1) + " of the " + counted + " " + what + " (line " +
                                 std::to_string(header_line) + ")";
    if (!line_tokens(line.text, wanted, out, &taken, &bad, &status, &rest)) bad_token(name, line.number, bad, status, expected);
    if (!rest.empty()) {
      std::string_view word = rest.substr(0, std::min<std::size_t>(rest.size(), 40));
      fail(name, line.number, "more values than the " + counted + " " + what + " line " + std::to_string(header_line) +
                                  " announces (found " + quote_token(trim(word)) + ")");
    }
    if (format && taken != wanted && got + taken < count)
      fail(name, line.number, "found " + std::to_string(taken) + " values on the line, " + std::to_string(got + taken) +
                                  " of the " + counted + " " + what + " line " + std::to_string(header_line) +
                                  " announces (expected " + std::to_string(wanted) + " on this line in its layout)");
    got += taken;
  }
}

void read_to_end(const std::vector<Line>& lines, std::size_t first, const std::string& name, const std::string& what,
                 std::vector<double>& out) {
  out.reserve(out.size() + chars_from(lines, first) / 2 + 1);
  for (std::size_t i = first; i < lines.size(); ++i) {
    std::size_t taken = 0;
    std::string_view bad, rest;
    NumberStatus status = NumberStatus::ok;
    if (!line_tokens(lines[i].text, static_cast<std::size_t>(-1), out, &taken, &bad, &status, &rest))
      bad_token(name, lines[i].number, bad, status, what + " " + std::to_string(out.size() + 1));
  }
}

AccelUnit agree_units(const RecordFormat& format, AccelUnit from_file, const std::string& name, std::size_t line,
                      const std::string& source) {
  if (format.units && *format.units != from_file) {
    const std::string what = source + " says units of " + to_string(from_file) + " but " + to_string(*format.units) + " was given";
    if (line > 0) fail(name, line, what);
    fail(name, what);
  }
  return from_file;
}

void check_given_dt(const std::optional<double>& dt, const std::string& name) {
  if (dt && !(std::isfinite(*dt) && *dt > 0.0)) fail(name, "dt must be a positive number of seconds, got " + fmt(*dt));
}

void agree_dt(const RecordFormat& format, double dt, const std::string& name, std::size_t line) {
  check_given_dt(format.dt, name);
  if (format.dt && std::abs(*format.dt - dt) > 1e-6 * dt)
    fail(name, line, "the header says dt = " + fmt(dt) + " s but dt = " + fmt(*format.dt) + " s was given");
}

std::size_t pick_channel(const RecordFormat& format, const std::vector<std::string>& labels,
                         const std::vector<std::size_t>& lines, const std::string& name, const std::string& kind) {
  std::string list;
  for (std::size_t i = 0; i < labels.size(); ++i)
    list += (i ? "; " : "") + std::to_string(i + 1) + ": " + (labels[i].empty() ? "line " + std::to_string(lines[i]) : labels[i]);
  if (format.channel == 0) {
    if (labels.size() == 1) return 0;
    fail(name, "this " + kind + " file holds " + std::to_string(labels.size()) + " channels (" + list +
                   "): choose one (--channel N, or ground.channel in a scene)");
  }
  if (format.channel < 1 || static_cast<std::size_t>(format.channel) > labels.size())
    fail(name, "channel " + std::to_string(format.channel) + " was asked but the file holds " +
                   std::to_string(labels.size()) + (labels.size() == 1 ? " channel" : " channels") + " (" + list + ")");
  return static_cast<std::size_t>(format.channel - 1);
}

Record finish(const std::string& name, std::string description, double dt, std::vector<double> values, AccelUnit unit,
              double scale) {
  Record record;
  record.source = name;
  record.description = std::move(description);
  record.dt = dt;
  record.accel = std::move(values);
  const double factor = to_m_s2(unit) * scale;
  if (factor != 1.0)
    for (double& a : record.accel) a *= factor;
  return record;
}

std::string join_lines(const std::vector<std::string_view>& lines, std::size_t limit) {
  std::string out;
  for (std::string_view l : lines) {
    l = trim(l);
    if (l.empty()) continue;
    if (!out.empty()) out += " | ";
    out += l;
  }
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  if (out.size() > limit) out = out.substr(0, limit - 3) + "...";
  return out;
}

}  // namespace adjoin::readers
