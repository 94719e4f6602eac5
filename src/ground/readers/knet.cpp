// NIED K-NET and KiK-net ASCII (one component per file: .EW .NS .UD, KiK-net .EW1 borehole /
// .EW2 surface ...). 17 header lines, a key in columns 1-18 and its value after:
//   Origin Time       2014/12/31 23:49:00
//   ...
//   Station Code      CHB002
//   Sampling Freq(Hz) 100Hz
//   Duration Time(s)  68
//   Dir.              E-W          (KiK-net: 1-3 borehole, 4-6 surface)
//   Scale Factor      7845(gal)/8223790
//   Max. Acc. (gal)   6.847
//   Memo.
// then the samples as integer counts, 8 a line. Acceleration [gal] = (count - mean of the
// record's counts) x 7845 / 8223790: the offset the logger adds is removed with the mean, as
// NIED's own "Max. Acc." is computed.
#include <cmath>
#include <numeric>
#include <utility>
#include <string>
#include <vector>

#include "registry.hpp"

namespace adjoin::readers {
namespace {

// The value of a "Key   value" header line: what follows the key (column 19 in NIED's files).
std::string_view value_of(const Line& line, std::string_view key) {
  const std::string_view t = line.text;
  std::size_t at = std::min(key.size(), t.size());
  if (find_ci(t.substr(at), "(Hz)") == 0) at += 4;  // "Sampling Freq(Hz)"
  return trim(t.substr(at));
}

}  // namespace

// "Origin Time" on the first line, "Scale Factor" and "Sampling Freq" in the header.
int sniff_knet(const Probe& probe) {
  if (probe.head.empty() || !starts_with_ci(trim(probe.head[0].text), "Origin Time")) return 0;
  bool scale = false, freq = false;
  for (std::size_t i = 0; i < probe.head.size() && i < 20; ++i) {
    scale = scale || starts_with_ci(probe.head[i].text, "Scale Factor");
    freq = freq || starts_with_ci(probe.head[i].text, "Sampling Freq");
  }
  return scale && freq ? 90 : 0;
}

Record parse_knet(std::string_view text, const std::string& name, const RecordFormat& format) {
  const std::vector<Line> lines = split_lines(text);
  if (lines.empty()) fail(name, 1, "empty file (expected a K-NET/KiK-net ASCII record)");
  const Line* freq = nullptr;
  const Line* scale = nullptr;
  const Line* station = nullptr;
  const Line* direction = nullptr;
  const Line* origin = nullptr;
  std::size_t data = 0;
  for (std::size_t i = 0; i < lines.size() && i < 40; ++i) {
    const std::string_view t = lines[i].text;
    if (starts_with_ci(t, "Sampling Freq")) freq = &lines[i];
    if (starts_with_ci(t, "Scale Factor")) scale = &lines[i];
    if (starts_with_ci(t, "Station Code")) station = &lines[i];
    if (starts_with_ci(t, "Dir.")) direction = &lines[i];
    if (starts_with_ci(t, "Origin Time")) origin = &lines[i];
    if (starts_with_ci(t, "Memo.")) {
      data = i + 1;
      break;
    }
  }
  const std::size_t header_end = data ? data : std::min<std::size_t>(lines.size(), 17);
  if (!freq) fail(name, lines[header_end - 1].number, "no 'Sampling Freq(Hz)' line in the header (expected e.g. 'Sampling Freq(Hz) 100Hz')");
  if (!scale) fail(name, lines[header_end - 1].number, "no 'Scale Factor' line in the header (expected e.g. 'Scale Factor      7845(gal)/8223790')");
  if (!data) fail(name, lines[header_end - 1].number, "no 'Memo.' line ending the 17-line header (expected the K-NET header)");

  // Sampling frequency: "100Hz".
  const std::string_view f = value_of(*freq, "Sampling Freq");
  std::size_t end = 0;
  const auto hz = number_at(f, 0, &end);
  if (!hz || !(*hz > 0.0) || !(*hz < 1e7))
    fail(name, freq->number, "sampling frequency " + quote_token(f) + " (expected a rate > 0 in Hz, e.g. '100Hz')");
  const double dt = 1.0 / *hz;
  agree_dt(format, dt, name, freq->number);

  // Scale factor: "7845(gal)/8223790".
  const std::string_view s = value_of(*scale, "Scale Factor");
  const std::size_t open = s.find('('), close = s.find(')'), slash = s.find('/', close == std::string_view::npos ? 0 : close);
  const std::optional<double> top = number_at(s, 0);
  const std::optional<double> bottom = slash == std::string_view::npos ? std::nullopt : number_at(s, slash + 1);
  if (slash == std::string_view::npos || open == std::string_view::npos || close == std::string_view::npos || close < open)
    fail(name, scale->number, "scale factor " + quote_token(s) + " (expected e.g. '7845(gal)/8223790')");
  // Both parts are magnitudes (full scale in gal over full scale in counts): a negative or zero
  // one would flip or kill the record, an infinite one inflate it, so neither is guessed at.
  // (number_at reads no inf, nan or overflowing value: those are "not a finite number".)
  const double numerator = top.value_or(NAN), denominator = bottom.value_or(NAN);
  for (const auto& [part, value] : {std::pair{"numerator", numerator}, std::pair{"denominator", denominator}})
    if (!(value > 0.0) || !std::isfinite(value))
      fail(name, scale->number, "scale factor " + quote_token(s) + ": the " + part + " is " +
                                    (value == 0.0 ? "zero" : value < 0.0 ? "negative" : "not a finite number") +
                                    " (expected a finite number > 0 on each side, e.g. '7845(gal)/8223790')");
  if (!std::isfinite(numerator / denominator) || !(numerator / denominator > 0.0))
    fail(name, scale->number, "scale factor " + quote_token(s) + " is not a finite number > 0 (expected e.g. '7845(gal)/8223790')");
  AccelUnit unit;
  const std::string unit_word(trim(s.substr(open + 1, close - open - 1)));
  if (!parse_accel_unit(unit_word, &unit))
    fail(name, scale->number, "unknown units " + quote_token(unit_word) + " in the scale factor (expected gal)");
  agree_units(format, unit, name, scale->number);
  const double factor = numerator / denominator;

  std::vector<double> counts;
  read_to_end(lines, data, name, "count", counts);
  if (counts.empty()) fail(name, lines.back().number, "no samples after the header (expected counts, 8 a line)");
  const double mean = std::accumulate(counts.begin(), counts.end(), 0.0) / static_cast<double>(counts.size());
  for (double& c : counts) c -= mean;

  std::vector<std::string_view> described;
  for (const Line* l : {station, direction, origin})
    if (l) described.push_back(l->text);
  std::string description = join_lines(described);
  description += (description.empty() ? "" : " | ") + std::string("scale factor ") + std::string(s) + ", mean count " + fmt(mean) + " removed";
  return finish(name, description, dt, std::move(counts), unit, factor);
}

}  // namespace adjoin::readers
