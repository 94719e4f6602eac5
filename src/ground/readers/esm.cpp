// ESM ASCII (Engineering Strong-Motion database, ORFEUS; the same layout as ITACA's): header
// lines "KEY: value" (64 of them in the DYNA 1.2 header), then the values, one a line. Read:
//   SAMPLING_INTERVAL_S: 0.005000      the step [s]
//   NDATA: 19128                       the number of values
//   UNITS: cm/s^2                      cm/s^2, m/s^2, g (also mm/s^2)
//   DATA_TYPE: ACCELERATION            if present, must be an acceleration
// and EVENT_NAME, NETWORK, STATION_CODE, STREAM for the description.
#include <cmath>
#include <string>
#include <vector>

#include "registry.hpp"

namespace adjoin::readers {
namespace {

// "KEY: value" -> KEY (upper-case letters, digits, '_', '/', '^' ...), or "" if not a header line.
std::string_view key_of(std::string_view line) {
  const std::size_t colon = line.find(':');
  if (colon == std::string_view::npos || colon == 0) return {};
  const std::string_view key = line.substr(0, colon);
  for (char c : key)
    if (is_blank(c)) return {};
  if (is_digit(key.front()) || key.front() == '-' || key.front() == '.') return {};
  return key;
}

}  // namespace

int sniff_esm(const Probe& probe) {
  bool interval = false, ndata = false;
  for (const Line& line : probe.head) {
    interval = interval || starts_with_ci(line.text, "SAMPLING_INTERVAL_S:");
    ndata = ndata || starts_with_ci(line.text, "NDATA:");
  }
  return interval && ndata ? 90 : 0;
}

Record parse_esm(std::string_view text, const std::string& name, const RecordFormat& format) {
  const std::vector<Line> lines = split_lines(text);
  if (lines.empty()) fail(name, 1, "empty file (expected an ESM ASCII record)");
  const Line *interval = nullptr, *ndata = nullptr, *units = nullptr, *type = nullptr;
  std::vector<std::string_view> described;
  std::size_t data = 0;
  for (; data < lines.size(); ++data) {
    const std::string_view t = lines[data].text;
    const std::string_view key = key_of(t);
    if (key.empty()) {
      if (trim(t).empty()) continue;
      break;  // the first value
    }
    const std::string k = to_lower(key);
    if (k == "sampling_interval_s") interval = &lines[data];
    if (k == "ndata") ndata = &lines[data];
    if (k == "units") units = &lines[data];
    if (k == "data_type") type = &lines[data];
    if (k == "event_name" || k == "event_id" || k == "network" || k == "station_code" || k == "stream") described.push_back(t);
  }
  const std::size_t last_header = data > 0 ? lines[data - 1].number : 1;
  const auto value = [](const Line* line) { return trim(line->text.substr(line->text.find(':') + 1)); };
  if (type) {
    const std::string v = to_lower(value(type));
    if (v.find("acceleration") == std::string::npos || v.find("spectrum") != std::string::npos)
      fail(name, type->number, "DATA_TYPE is " + quote_token(value(type)) + " (expected ACCELERATION)");
  }
  if (!interval) fail(name, last_header, "no SAMPLING_INTERVAL_S line in the header (expected e.g. 'SAMPLING_INTERVAL_S: 0.005000')");
  const double dt = field_number(value(interval), name, interval->number, "SAMPLING_INTERVAL_S, the step in s");
  if (!(dt > 0.0)) fail(name, interval->number, "SAMPLING_INTERVAL_S = " + fmt(dt) + " (expected a step > 0 in s)");
  agree_dt(format, dt, name, interval->number);
  if (!ndata) fail(name, last_header, "no NDATA line in the header (expected e.g. 'NDATA: 19128')");
  const double n = field_number(value(ndata), name, ndata->number, "NDATA, the number of values");
  if (!(n >= 1.0 && n == std::floor(n) && n < 1e12)) fail(name, ndata->number, "NDATA = " + fmt(n) + " (expected a positive whole number)");
  if (!units) fail(name, last_header, "no UNITS line in the header (expected e.g. 'UNITS: cm/s^2')");
  AccelUnit unit;
  if (!parse_accel_unit(std::string(value(units)), &unit))
    fail(name, units->number, "unknown units " + quote_token(value(units)) + " (expected cm/s^2, m/s^2 or g)");
  agree_units(format, unit, name, units->number);

  std::vector<double> values;
  std::size_t next = data;
  read_block(lines, &next, static_cast<std::size_t>(n), std::nullopt, name, "values", ndata->number, values);
  for (; next < lines.size(); ++next)
    if (!trim(lines[next].text).empty())
      fail(name, lines[next].number, "more values than NDATA = " + std::to_string(values.size()) + " (line " +
                                         std::to_string(ndata->number) + ") announces (found " +
                                         quote_token(trim(lines[next].text).substr(0, 40)) + ")");
  return finish(name, join_lines(described), dt, std::move(values), unit);
}

}  // namespace adjoin::readers
