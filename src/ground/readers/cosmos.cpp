// COSMOS strong-motion data format, v1.20 (V1 uncorrected and V2 corrected acceleration; see
// record_file.hpp). Each channel is
//   text header    line 1 "Corrected acceleration    (Format v01.20 with 13 text lines) ...",
//                  station, event, "Sta Chan ..." lines
//   " 100 Integer-header values follow on  10 lines, Format= (10I8)"  + the integers
//                  (integer 2: physical parameter, 1 = acceleration; integer 3: units code)
//   " 100 Real-header values follow on  17 lines, Format= (6F13.6)"   + the reals
//                  (real 62: sampling interval in ms; real 64: peak value)
//   "   2 Comment line(s) follow, each starting with a "|":"          + the comment lines
//   data blocks    "   7000  acceleration pts, approx   70 secs, units=cm/sec2(04),Format=(8F10.5)"
//                  + the values (V2 files may add velocity and displacement blocks)
//   an end line    "/&  ----------  End of data for channel  1  ----------" or "End-of-data ..."
// and a file may hold several channels one after the other.
#include <cmath>
#include <string>
#include <vector>

#include "registry.hpp"

namespace adjoin::readers {
namespace {

constexpr std::string_view kIntegerHeader = "Integer-header values follow on";
constexpr std::string_view kRealHeader = "Real-header values follow on";

struct Channel {
  std::size_t text_first = 0;  // index of the text header's first line
  std::string label;
  std::size_t accel_line = 0;  // line number of the acceleration block's header (0: none)
  std::vector<double> accel;
  double scale = 1.0;
  AccelUnit unit = AccelUnit::cm_s2;
  std::size_t count = 0;
  double dt = 0.0;
  std::size_t dt_line = 0;
};

// "N ... follow on L lines, Format= (10I8)": N, L and the layout.
struct HeaderBlock {
  std::size_t values = 0, lines = 0;
  std::optional<FortranFormat> format;
};

HeaderBlock header_block(const Line& line, std::string_view marker, const std::string& name) {
  HeaderBlock block;
  const std::string_view t = line.text;
  std::size_t end = 0;
  const auto n = number_at(t, 0, &end);
  const std::size_t on = find_ci(t, marker) + marker.size();
  std::size_t end2 = 0;
  const auto l = number_at(t, on, &end2);
  if (!n || !l || *n < 0 || *n > 10000 || *l < 0 || *l > 10000 || *n != std::floor(*n) || *l != std::floor(*l))
    fail(name, line.number, "cannot read the counts in " + quote_token(trim(t)) +
                                " (expected e.g. ' 100 Integer-header values follow on  10 lines, Format= (10I8)')");
  block.values = static_cast<std::size_t>(*n);
  block.lines = static_cast<std::size_t>(*l);
  const std::size_t f = find_ci(t, "format");
  if (f != std::string_view::npos) block.format = fortran_format(t.substr(f));
  return block;
}

// Reads the header block's values (any layout, one line after another).
std::vector<double> header_values(const std::vector<Line>& lines, std::size_t* next, const HeaderBlock& block,
                                  const std::string& name, const std::string& what, std::size_t header_line) {
  std::vector<double> values;
  read_block(lines, next, block.values, block.format, name, what, header_line, values);
  return values;
}

bool is_end_line(std::string_view line) {
  const std::string_view t = trim(line);
  return t.substr(0, 2) == "/&" || starts_with_ci(t, "end-of-data") || starts_with_ci(t, "end of data");
}

// "7000  acceleration pts, approx 70 secs, units=cm/sec2(04),Format=(8F10.5)"?
bool is_data_header(std::string_view line) {
  const std::string_view t = trim(line);
  return !t.empty() && is_digit(t.front()) && find_ci(t, " pts") != std::string_view::npos &&
         find_ci(t, "units") != std::string_view::npos;
}

// Units of a data block from its code "(04)" or its name "cm/sec2"; the factor to apply to the
// values before `unit` (mg, in/s^2). False if unknown.
bool block_units(std::string_view units, AccelUnit* unit, double* scale, std::string* shown) {
  // "cm/sec2(04)" -> name "cm/sec2", code 4
  const std::size_t open = units.find('(');
  const std::string_view word = trim(units.substr(0, open));
  *shown = std::string(word);
  int code = -1;
  if (open != std::string_view::npos) {
    const auto c = number_at(units, open + 1);
    if (c && *c >= 0 && *c < 1000 && *c == std::floor(*c)) code = static_cast<int>(*c);
  }
  *scale = 1.0;
  switch (code) {
    case 2: *unit = AccelUnit::g; return true;
    case 4: case 10: *unit = AccelUnit::cm_s2; return true;
    case 11: *unit = AccelUnit::g; *scale = 1e-3; return true;   // mg
    case 7: *unit = AccelUnit::cm_s2; *scale = 2.54; return true;  // in/s^2
    default: break;
  }
  if (code >= 0 && code != 4) return false;  // a known code that is not an acceleration (counts, cm/s, ...)
  return parse_accel_unit(std::string(word), unit);
}

}  // namespace

// The integer-header line in the first lines (its text header has 13 lines, or a few more).
int sniff_cosmos(const Probe& probe) {
  for (std::size_t i = 0; i < probe.head.size() && i < 60; ++i)
    if (find_ci(probe.head[i].text, kIntegerHeader) != std::string_view::npos) return 90;
  return 0;
}

Record parse_cosmos(std::string_view text, const std::string& name, const RecordFormat& format) {
  const std::vector<Line> lines = split_lines(text);
  if (lines.empty()) fail(name, 1, "empty file (expected a COSMOS V1/V2 record)");
  std::vector<Channel> channels;
  std::size_t next = 0;
  while (true) {
    // Text header: up to the integer-header line; end lines of the previous channel skipped.
    while (next < lines.size() && (trim(lines[next].text).empty() || is_end_line(lines[next].text))) ++next;
    if (next >= lines.size()) break;
    Channel channel;
    channel.text_first = next;
    std::size_t ints_at = next;
    while (ints_at < lines.size() && find_ci(lines[ints_at].text, kIntegerHeader) == std::string_view::npos) ++ints_at;
    if (ints_at >= lines.size()) {
      if (channels.empty())
        fail(name, lines.back().number, "no line '... Integer-header values follow on ... lines' (expected a COSMOS V1/V2 header)");
      fail(name, lines[next].number, "text after the last channel that does not start another (expected a COSMOS text header "
                                     "followed by '... Integer-header values follow on ...')");
    }
    const std::string_view first = trim(lines[channel.text_first].text);
    if (find_ci(first, "acceleration") == std::string_view::npos) {
      const bool other = find_ci(first, "velocity") != std::string_view::npos || find_ci(first, "displacement") != std::string_view::npos ||
                         find_ci(first, "spectr") != std::string_view::npos;
      if (other)
        fail(name, lines[channel.text_first].number, quote_token(first) + ": not an acceleration record (expected 'Corrected acceleration' or 'Uncorrected acceleration')");
    }
    if (find_ci(first, "raw acceleration counts") != std::string_view::npos)
      fail(name, lines[channel.text_first].number, quote_token(first) + ": raw counts (a V0 file; expected V1 or V2 acceleration in physical units)");
    for (std::size_t i = channel.text_first; i < ints_at; ++i) {
      const std::string_view t = trim(lines[i].text);
      if (starts_with_ci(t, "sta chan") || starts_with_ci(t, "sta cha:")) {
        channel.label = std::string(trim(t.substr(0, std::min(std::min<std::size_t>(t.size(), 40), t.find('(')))));
        break;
      }
    }
    if (channel.label.empty()) channel.label = std::string(first.substr(0, std::min<std::size_t>(first.size(), 40)));

    // Integer and real headers, comments.
    const Line& ints_line = lines[ints_at];
    const HeaderBlock int_block = header_block(ints_line, kIntegerHeader, name);
    next = ints_at + 1;
    const std::vector<double> ints = header_values(lines, &next, int_block, name, "integer-header values", ints_line.number);
    if (ints.size() >= 2 && ints[1] != 1.0 && ints[1] != -999.0) {
      const std::size_t per = int_block.format ? int_block.format->per_line : 10;
      fail(name, ints_line.number + 1 + 1 / per, "integer 2, the physical parameter, is " + fmt(ints[1]) +
                                                     " (expected 1, acceleration)");
    }
    if (next >= lines.size() || find_ci(lines[next].text, kRealHeader) == std::string_view::npos)
      fail(name, next < lines.size() ? lines[next].number : lines.back().number,
           "expected the line '... Real-header values follow on ... lines' after the integer header (line " +
               std::to_string(ints_line.number) + ")");
    const Line& reals_line = lines[next];
    const HeaderBlock real_block = header_block(reals_line, kRealHeader, name);
    ++next;
    const std::size_t reals_first = next;
    const std::vector<double> reals = header_values(lines, &next, real_block, name, "real-header values", reals_line.number);
    // Real 62 on the line its layout puts it.
    const std::size_t per = real_block.format ? real_block.format->per_line : 0;
    std::size_t dt_line = reals_line.number;
    if (per > 0 && reals_first + 61 / per < lines.size()) dt_line = lines[reals_first + 61 / per].number;
    if (reals.size() < 62)
      fail(name, reals_line.number, "the real header has " + std::to_string(reals.size()) +
                                        " values (expected at least 62: real 62 is the sampling interval in ms)");
    const double dt_ms = reals[61];
    if (!(dt_ms > 0.0) || dt_ms == -999.0)
      fail(name, dt_line, "real 62, the sampling interval, is " + fmt(dt_ms) + (dt_ms == -999.0 ? " (unknown)" : "") +
                              " (expected a step > 0 in ms)");
    channel.dt = dt_ms * 1e-3;
    channel.dt_line = dt_line;
    if (next < lines.size() && find_ci(lines[next].text, "comment line") != std::string_view::npos) {
      const auto n = number_at(lines[next].text, 0);
      if (!n || *n < 0 || *n != std::floor(*n))
        fail(name, lines[next].number, "cannot read the number of comment lines in " + quote_token(trim(lines[next].text)));
      if (*n > static_cast<double>(lines.size() - next - 1))
        fail(name, lines[next].number, "the file ends within the " + fmt(*n) + " comment lines this line announces");
      next += 1 + static_cast<std::size_t>(*n);
    }

    // Data blocks until the end line.
    bool any = false;
    while (next < lines.size() && is_data_header(lines[next].text)) {
      const Line& header = lines[next++];
      const std::string_view t = trim(header.text);
      const auto n = number_at(t, 0);
      if (!n || !(*n >= 1.0) || *n != std::floor(*n) || *n > 1e12)
        fail(name, header.number, "cannot read the number of points in " + quote_token(t) + " (expected e.g. '7000 acceleration pts, ...')");
      const std::size_t count = static_cast<std::size_t>(*n);
      const std::size_t fat = find_ci(t, "format");
      const std::optional<FortranFormat> layout = fat == std::string_view::npos ? std::nullopt : fortran_format(t.substr(fat));
      const bool accel = find_ci(t, "accel") != std::string_view::npos;
      std::vector<double> values;
      read_block(lines, &next, count, layout, name, accel ? "acceleration values" : "values", header.number, values);
      any = true;
      if (!accel || channel.accel_line != 0) continue;
      const std::size_t u = find_ci(t, "units=");
      std::string shown;
      if (u == std::string_view::npos) fail(name, header.number, "no 'units=' on the data line (expected e.g. 'units=cm/sec2(04)')");
      std::string_view units = t.substr(u + 6);
      const std::size_t comma = units.find(',');
      units = units.substr(0, comma);
      if (!block_units(units, &channel.unit, &channel.scale, &shown))
        fail(name, header.number, "units " + quote_token(trim(units)) + " are not an acceleration this reader knows "
                                  "(expected g (02), cm/sec2 (04), gal (10), mg (11) or in/sec2 (07))");
      channel.accel_line = header.number;
      channel.count = count;
      channel.accel = std::move(values);
    }
    if (!any)
      fail(name, next < lines.size() ? lines[next].number : lines.back().number,
           "expected a data line such as '7000 acceleration pts, approx 70 secs, units=cm/sec2(04),Format=(8F10.5)'");
    if (channel.accel_line == 0)
      fail(name, lines[channel.text_first].number, "this channel holds no acceleration block (expected 'N acceleration pts, ...')");
    if (next < lines.size() && !is_end_line(lines[next].text) && !trim(lines[next].text).empty() &&
        find_ci(lines[next].text, "acceleration") == std::string_view::npos)
      fail(name, lines[next].number, quote_token(trim(lines[next].text).substr(0, 40)) +
                                         " after the values (expected the end line '/& ... End of data for channel', or the next channel)");
    channels.push_back(std::move(channel));
  }
  if (channels.empty()) fail(name, lines.back().number, "no channel found (expected a COSMOS V1/V2 record)");

  std::vector<std::string> labels;
  std::vector<std::size_t> starts;
  for (const Channel& c : channels) {
    labels.push_back(c.label);
    starts.push_back(lines[c.text_first].number);
  }
  Channel& chosen = channels[pick_channel(format, labels, starts, name, "COSMOS")];
  agree_dt(format, chosen.dt, name, chosen.dt_line);
  const AccelUnit unit = agree_units(format, chosen.unit, name, chosen.accel_line);
  std::vector<std::string_view> described;
  for (std::size_t i = chosen.text_first; i < chosen.text_first + 3 && i < lines.size(); ++i) described.push_back(lines[i].text);
  std::string description = join_lines(described);
  if (channels.size() > 1) description += " | channel " + std::to_string(format.channel) + " of " + std::to_string(channels.size());
  return finish(name, description, chosen.dt, std::move(chosen.accel), unit, chosen.scale);
}

}  // namespace adjoin::readers
