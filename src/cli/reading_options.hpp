#pragma once
// The options every command that reads an accelerogram takes (record info/process/fourier,
// spectrum), in one place: --units, --format, --dt, --time-column, --accel-column,
// --delimiter, --channel, and the RecordFormat they make.
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/ground/record_file.hpp"

namespace adjoin::cli {

struct ReadingArgs {
  std::string units, format, time_column, accel_column, delimiter;
  double dt = 0.0;
  int channel = 0;  // 0: not given
};

inline RecordFormat format_from(const ReadingArgs& args) {
  RecordFormat f;
  if (!args.format.empty() && !parse_record_kind(args.format, &f.kind))
    throw InputError("--format " + text_excerpt(args.format) + ": unknown format (expected one of " + record_kind_names() + ")");
  if (!args.units.empty()) {
    AccelUnit unit;
    if (!parse_accel_unit(args.units, &unit))
      throw InputError("--units " + text_excerpt(args.units) + ": unknown unit (expected g, m/s2, cm/s2 (gal) or mm/s2)");
    f.units = unit;
  }
  if (args.dt != 0.0) {
    if (!(args.dt > 0.0) || !std::isfinite(args.dt)) throw InputError("--dt: expected a positive step in s");
    f.dt = args.dt;
  }
  if (args.channel < 0) throw InputError("--channel " + std::to_string(args.channel) + ": expected a channel number 1, 2, ...");
  f.channel = args.channel;
  f.time_column = args.time_column;
  f.accel_column = args.accel_column;
  const std::string& d = args.delimiter;
  if (d.empty())
    f.delimiter = 0;
  else if (d == "tab" || d == "\\t")
    f.delimiter = '\t';
  else if (d == "comma")
    f.delimiter = ',';
  else if (d == "semicolon")
    f.delimiter = ';';
  else if (d == "space" || d == "blank")
    f.delimiter = ' ';
  else if (d.size() == 1)
    f.delimiter = d[0];
  else
    throw InputError("--delimiter " + text_excerpt(d) + ": expected one character, or tab, comma, semicolon, space");
  return f;
}

inline void add_reading_options(CLI::App* sub, ReadingArgs* args) {
  sub->add_option("--units", args->units,
                  "Acceleration units of the file: g, m/s2, cm/s2 (gal), mm/s2 (required unless the file says them)");
  sub->add_option("--format", args->format,
                  "auto (default: from the file's content), at2, one-column, two-column, delimited, smc, cosmos, knet, "
                  "esm, dmg");
  sub->add_option("--dt", args->dt, "Time step [s] of a one-column file (or a delimited file without a time column)");
  sub->add_option("--time-column", args->time_column, "Delimited files: time column, by header name or 1-based index");
  sub->add_option("--accel-column", args->accel_column,
                  "Delimited files: acceleration column, by header name or 1-based index");
  sub->add_option("--delimiter", args->delimiter, "Delimited files: one character, or tab, comma, semicolon, space");
  sub->add_option("--channel", args->channel,
                  "Multi-channel files (COSMOS, DMG): the channel to read, 1-based in the file's order");
}

}  // namespace adjoin::cli
