// CSMIP/DMG (California Geological Survey, formerly the Division of Mines and Geology) V2
// processed data. Each channel: a text header (line 1 "Corrected accelerogram ... Chan  1: 360
// Deg"), integer and real headers, then three blocks, the acceleration's first:
//   " 12000 points of accel data equally spaced at  .005 sec, in cm/sec2. (8f10.6)"
//   " 3251 POINTS OF ACCEL DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC/SEC)"   (older)
// then the velocity and displacement blocks (not read), and "/&" ending the channel. Only the
// acceleration block is read: npts, dt and units from its line, the values in its layout
// (fixed fields when the line gives one, so values that touch are read right).
//
// V1 files (uncorrected) are read the same way from their block line
//   " 13200 Accelerogram points at 200 pts/sec in units of g .      Format: (8f9.6)".
#include <cmath>
#include <string>
#include <vector>

#include "registry.hpp"

namespace adjoin::readers {
namespace {

constexpr std::string_view kV2Marker = "points of accel data";
constexpr std::string_view kV1Marker = "accelerogram points at";

bool is_block_line(std::string_view line) {
  const std::string_view t = trim(line);
  return !t.empty() && is_digit(t.front()) &&
         (find_ci(t, kV2Marker) != std::string_view::npos || find_ci(t, kV1Marker) != std::string_view::npos);
}

// The unit word after `at` in `text` ("cm/sec2." -> "cm/sec2").
std::string unit_word(std::string_view text, std::size_t at) {
  std::string_view rest = trim(text.substr(std::min(at, text.size())));
  std::size_t end = 0;
  while (end < rest.size() && !is_blank(rest[end]) && rest[end] != ')' && rest[end] != ',') ++end;
  std::string word(rest.substr(0, end));
  while (!word.empty() && word.back() == '.') word.pop_back();
  return word;
}

}  // namespace

int sniff_dmg(const Probe& probe) {
  for (const Line& line : probe.head)
    if (is_block_line(line.text)) return 80;
  return 0;
}

Record parse_dmg(std::string_view text, const std::string& name, const RecordFormat& format) {
  const std::vector<Line> lines = split_lines(text);
  if (lines.empty()) fail(name, 1, "empty file (expected a CSMIP/DMG V2 record)");
  std::vector<std::size_t> blocks;
  std::vector<std::string> labels;
  std::vector<std::size_t> starts;
  std::size_t channel_start = 0;  // the first line after the previous channel's "/&" line
  bool after_end = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string_view t = trim(lines[i].text);
    if (t.substr(0, 2) == "/&") {
      after_end = true;
      continue;
    }
    if (after_end && !t.empty()) {
      channel_start = i;
      after_end = false;
    }
    if (!is_block_line(t)) continue;
    blocks.push_back(i);
    const std::string_view first = trim(lines[channel_start].text);
    const std::size_t chan = find_ci(first, "chan");
    std::string label(chan == std::string_view::npos ? std::string_view{} : first.substr(chan, 20));
    const std::size_t from = find_ci(label, " from");
    if (from != std::string::npos) label.resize(from);
    labels.push_back(std::string(trim(label)));
    starts.push_back(lines[channel_start].number);
  }
  if (blocks.empty())
    fail(name, lines.back().number, "no acceleration block (expected a line such as '12000 points of accel data equally spaced at .005 sec, in cm/sec2.')");
  const std::size_t pick = pick_channel(format, labels, starts, name, "DMG");
  const Line& header = lines[blocks[pick]];
  const std::string_view t = trim(header.text);
  const bool v1 = find_ci(t, kV1Marker) != std::string_view::npos;

  const auto n = number_at(t, 0);
  if (!n || !(*n >= 1.0) || *n != std::floor(*n) || *n > 1e12)
    fail(name, header.number, "cannot read the number of points in " + quote_token(t) + " (expected e.g. '12000 points of accel data ...')");
  double dt = 0.0;
  if (v1) {
    const std::size_t at = find_ci(t, kV1Marker) + kV1Marker.size();
    const auto rate = number_at(t, at);
    if (!rate || !(*rate > 0.0) || !(*rate < 1e7))
      fail(name, header.number, "cannot read the sampling rate in " + quote_token(t) + " (expected '... points at 200 pts/sec ...')");
    dt = 1.0 / *rate;
  } else {
    const std::size_t at = find_ci(t, "spaced at");
    const auto step = at == std::string_view::npos ? std::nullopt : number_at(t, at + 9);
    if (!step) fail(name, header.number, "no step in " + quote_token(t) + " (expected '... equally spaced at .005 sec ...')");
    if (!(*step > 0.0)) fail(name, header.number, "the step is " + fmt(*step) + " s (expected a step > 0 in s)");
    dt = *step;
  }
  agree_dt(format, dt, name, header.number);

  std::string word;
  if (const std::size_t u = find_ci(t, "units:"); u != std::string_view::npos)
    word = unit_word(t, u + 6);
  else if (const std::size_t o = find_ci(t, "units of"); o != std::string_view::npos)
    word = unit_word(t, o + 8);
  else if (const std::size_t in = find_ci(t, ", in "); in != std::string_view::npos)
    word = unit_word(t, in + 5);
  if (word.empty()) fail(name, header.number, "no units in " + quote_token(t) + " (expected '..., in cm/sec2.' or '(UNITS: CM/SEC/SEC)')");
  AccelUnit unit;
  if (!parse_accel_unit(word, &unit))
    fail(name, header.number, "unknown units " + quote_token(word) + " (expected cm/sec2, cm/sec/sec or g)");
  agree_units(format, unit, name, header.number);

  std::optional<FortranFormat> layout;
  if (const std::size_t open = t.rfind('('); open != std::string_view::npos) layout = fortran_format(t.substr(open));
  std::vector<double> values;
  std::size_t next = blocks[pick] + 1;
  read_block(lines, &next, static_cast<std::size_t>(*n), layout, name, "acceleration values", header.number, values);

  std::vector<std::string_view> described;
  const std::size_t first = starts[pick] - 1;
  for (std::size_t i = first; i < first + 3 && i < lines.size(); ++i) described.push_back(lines[i].text);
  std::string description = join_lines(described);
  if (blocks.size() > 1) description += " | channel " + std::to_string(pick + 1) + " of " + std::to_string(blocks.size());
  return finish(name, description, dt, std::move(values), unit);
}

}  // namespace adjoin::readers
