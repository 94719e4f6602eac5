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

namespace {

// One channel: where it starts, its acceleration block line and its "/&" end line, if any.
struct Channel {
  std::size_t first = 0;                               // index of its first line
  std::size_t block = std::string_view::npos;          // index of its block line
  std::size_t end = std::string_view::npos;            // index of its "/&" line
  std::string label;
};

std::string channel_label(std::string_view first) {
  const std::size_t chan = find_ci(first, "chan");
  std::string label(chan == std::string_view::npos ? std::string_view{} : first.substr(chan, 20));
  const std::size_t from = find_ci(label, " from");
  if (from != std::string::npos) label.resize(from);
  return std::string(trim(label));
}

// The channels of the file, each checked to be whole: a channel begins with the first
// non-blank line after the previous "/&"; each must have its acceleration block, and when the
// file ends its channels with "/&" the last one must end so too. A file cut inside a channel
// is refused here, naming the line where the channel's text stops (else a two-channel file cut
// inside its second channel would read as a one-channel file).
std::vector<Channel> find_channels(const std::vector<Line>& lines, const std::string& name) {
  std::vector<Channel> channels;
  bool open = false;  // a channel has begun and has not ended with "/&"
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string_view t = trim(lines[i].text);
    if (t.empty()) continue;
    if (!open) {
      channels.push_back(Channel{i, std::string_view::npos, std::string_view::npos, channel_label(t)});
      open = true;
    }
    Channel& c = channels.back();
    if (t.substr(0, 2) == "/&") {
      c.end = i;
      open = false;
    } else if (c.block == std::string_view::npos && is_block_line(t)) {
      c.block = i;
    }
  }
  const bool ended = !channels.empty() && channels.front().end != std::string_view::npos;
  for (std::size_t k = 0; k < channels.size(); ++k) {
    const Channel& c = channels[k];
    const std::size_t last = c.end != std::string_view::npos ? c.end : lines.size() - 1;
    const std::string which = "channel " + std::to_string(k + 1) + " (from line " + std::to_string(lines[c.first].number) + ")";
    if (c.block == std::string_view::npos)
      fail(name, lines[last].number,
           (c.end != std::string_view::npos ? which + " ends" : "the file ends inside " + which) +
               " without an acceleration block (expected a line such as '12000 points of accel data equally spaced at .005 sec, in cm/sec2.')");
    if (ended && c.end == std::string_view::npos)
      fail(name, lines[last].number, "the file ends inside " + which +
                                         " (expected its velocity and displacement blocks and a '/&' end line, as channel 1 has)");
  }
  return channels;
}

struct Block {
  double dt = 0.0;
  AccelUnit unit = AccelUnit::m_s2;
  std::vector<double> values;
};

// The acceleration block whose header line is lines[at]: count, step, units, then the values.
Block read_accel_block(const std::vector<Line>& lines, std::size_t at, const std::string& name) {
  const Line& header = lines[at];
  const std::string_view t = trim(header.text);
  const bool v1 = find_ci(t, kV1Marker) != std::string_view::npos;
  Block out;

  const auto n = number_at(t, 0);
  if (!n || !(*n >= 1.0) || *n != std::floor(*n) || *n > 1e12)
    fail(name, header.number, "cannot read the number of points in " + quote_token(t) + " (expected e.g. '12000 points of accel data ...')");
  if (v1) {
    const std::size_t from = find_ci(t, kV1Marker) + kV1Marker.size();
    const auto rate = number_at(t, from);
    if (!rate || !(*rate > 0.0) || !(*rate < 1e7))
      fail(name, header.number, "cannot read the sampling rate in " + quote_token(t) + " (expected '... points at 200 pts/sec ...')");
    out.dt = 1.0 / *rate;
  } else {
    const std::size_t spaced = find_ci(t, "spaced at");
    const auto step = spaced == std::string_view::npos ? std::nullopt : number_at(t, spaced + 9);
    if (!step) fail(name, header.number, "no step in " + quote_token(t) + " (expected '... equally spaced at .005 sec ...')");
    if (!(*step > 0.0)) fail(name, header.number, "the step is " + fmt(*step) + " s (expected a step > 0 in s)");
    out.dt = *step;
  }

  std::string word;
  if (const std::size_t u = find_ci(t, "units:"); u != std::string_view::npos)
    word = unit_word(t, u + 6);
  else if (const std::size_t o = find_ci(t, "units of"); o != std::string_view::npos)
    word = unit_word(t, o + 8);
  else if (const std::size_t in = find_ci(t, ", in "); in != std::string_view::npos)
    word = unit_word(t, in + 5);
  if (word.empty()) fail(name, header.number, "no units in " + quote_token(t) + " (expected '..., in cm/sec2.' or '(UNITS: CM/SEC/SEC)')");
  if (!parse_accel_unit(word, &out.unit))
    fail(name, header.number, "unknown units " + quote_token(word) + " (expected cm/sec2, cm/sec/sec or g)");

  std::optional<FortranFormat> layout;
  if (const std::size_t open = t.rfind('('); open != std::string_view::npos) layout = fortran_format(t.substr(open));
  std::size_t next = at + 1;
  read_block(lines, &next, static_cast<std::size_t>(*n), layout, name, "acceleration values", header.number, out.values);
  return out;
}

}  // namespace

Record parse_dmg(std::string_view text, const std::string& name, const RecordFormat& format) {
  const std::vector<Line> lines = split_lines(text);
  if (lines.empty()) fail(name, 1, "empty file (expected a CSMIP/DMG V2 record)");
  const std::vector<Channel> channels = find_channels(lines, name);
  if (channels.empty())
    fail(name, lines.back().number, "no acceleration block (expected a line such as '12000 points of accel data equally spaced at .005 sec, in cm/sec2.')");
  std::vector<std::string> labels;
  std::vector<std::size_t> starts;
  for (const Channel& c : channels) {
    labels.push_back(c.label);
    starts.push_back(lines[c.first].number);
  }
  const std::size_t pick = pick_channel(format, labels, starts, name, "DMG");
  // Every channel's block is read, so a cut or damaged one is found whichever is chosen.
  Block chosen;
  for (std::size_t k = 0; k < channels.size(); ++k) {
    Block b = read_accel_block(lines, channels[k].block, name);
    if (k == pick) chosen = std::move(b);
  }
  const Line& header = lines[channels[pick].block];
  agree_dt(format, chosen.dt, name, header.number);
  agree_units(format, chosen.unit, name, header.number);

  std::vector<std::string_view> described;
  for (std::size_t i = channels[pick].first; i < channels[pick].first + 3 && i < lines.size(); ++i)
    described.push_back(lines[i].text);
  std::string description = join_lines(described);
  if (channels.size() > 1) description += " | channel " + std::to_string(pick + 1) + " of " + std::to_string(channels.size());
  return finish(name, description, chosen.dt, std::move(chosen.values), chosen.unit);
}

}  // namespace adjoin::readers
