// Readers for recorded accelerograms (see record_file.hpp for the formats and the rules): the
// public entry points. Each format has its own reader in src/ground/readers/, behind one table
// (registry.cpp) that also makes the automatic choice.
#include "adjoin/ground/record_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "adjoin/core/errors.hpp"
#include "readers/registry.hpp"

namespace adjoin {
namespace {

using readers::fail;
using readers::fmt;

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

// The reader whose sniffer is most confident about the text, or nullptr if none claims it.
const readers::ReaderEntry* sniff(std::string_view text, std::string_view name) {
  readers::Probe probe{name, readers::first_lines(text, readers::kProbeLines)};
  const readers::ReaderEntry* chosen = nullptr;
  int best = 0;
  for (const readers::ReaderEntry& entry : readers::reader_table()) {
    if (!entry.sniff) continue;
    const int confidence = entry.sniff(probe);
    if (confidence > best) {
      best = confidence;
      chosen = &entry;
    }
  }
  return chosen;
}

std::string read_text(const std::filesystem::path& path) {
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
  return text;
}

}  // namespace

RecordFormat::Kind detect_record_format(std::string_view text, std::string_view name) {
  const readers::ReaderEntry* chosen = sniff(text, name);
  return chosen ? chosen->kind : RecordFormat::Kind::automatic;
}

RecordFormat::Kind detect_record_format(const std::filesystem::path& path) {
  return detect_record_format(read_text(path), path.string());
}

Record parse_record(std::string_view text, const std::string& name, const RecordFormat& format) {
  using Kind = RecordFormat::Kind;
  const readers::ReaderEntry* chosen = nullptr;
  if (format.kind == Kind::automatic) {
    chosen = sniff(text, name);
  } else {
    chosen = &readers::reader_entry(format.kind);
    if (!chosen->parse) fail(name, "unknown record format");
  }
  if (format.channel < 0) fail(name, "channel " + std::to_string(format.channel) + " (expected 1, 2, ...)");
  if (chosen && !chosen->multi_channel && format.channel > 1)
    fail(name, "channel " + std::to_string(format.channel) + " was asked, but a " + std::string(chosen->title) +
                   " file holds one channel");
  // Column choices only apply to column text; a file with its own header layout would ignore them.
  const bool columns = !chosen || chosen->kind == Kind::one_column || chosen->kind == Kind::two_column || chosen->kind == Kind::delimited;
  if (!columns)
    for (const auto& [given, what] : {std::pair{!format.time_column.empty(), "a time column (--time-column, ground.time_column)"},
                                      {!format.accel_column.empty(), "an acceleration column (--accel-column, ground.accel_column)"},
                                      {format.delimiter != 0, "a delimiter (--delimiter)"}})
      if (given)
        fail(name, std::string(what) + " was given, but a " + std::string(chosen->title) + " file has its own layout; it applies to "
                                                                               "delimited text only");
  Record record = chosen ? chosen->parse(text, name, format) : readers::parse_columns_auto(text, name, format);
  check_ranges(record, name);
  return record;
}

Record read_record(const std::filesystem::path& path, const RecordFormat& format) {
  return parse_record(read_text(path), path.string(), format);
}

}  // namespace adjoin
