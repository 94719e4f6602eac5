#pragma once
// Readers for recorded accelerograms: files in, Record (accelerations in m/s^2) out.
//
// Formats
//  - at2: PEER AT2, every header generation: any number of free-text header lines, then a
//    line with NPTS and DT ("NPTS=  7814, DT=   .0050 SEC," with or without the trailing comma,
//    or the older "  2000   0.0200   NPTS, DT"), then NPTS values in any fixed or free layout
//    (5E15.7, 8F10.5, ...; F-format values that touch, "-0.12345-0.23456", are split at the
//    sign). Units come from the header ("... IN UNITS OF G", "CM/SEC/SEC", or a unit word on
//    an acceleration line such as "Acceleration (g)"). If `units` is given too, it must agree.
//  - one_column: one value per line; the step `dt` must be given.
//  - two_column: time and acceleration per line, separated by blanks/tabs (or by ',' or ';'
//    when the first data line uses one; `delimiter` forces it). dt comes from the time column.
//  - delimited: a header line of column names, then rows (CSV, ';', tab or blank separated;
//    `delimiter` 0 guesses from the header: ',' then ';' then tab then blanks). Columns are
//    chosen by name (case-insensitive) or 1-based index in time_column / accel_column.
//    Defaults: time = a column named t, time... (or column 1 of two); acceleration = the
//    other of two columns, or one whose name starts with "acc" or is "a". If `dt` is given
//    and time_column is not, no time column is used. Units may be written in the
//    acceleration column's name: "acc [g]", "a (m/s2)".
//  - smc: USGS SMC. 11 text lines (line 1 "2 CORRECTED ACCELEROGRAM": code 0 unknown, 1
//    uncorrected or 2 corrected accelerogram are read; 3-6, velocity, displacement and spectra,
//    are refused), 48 integers in 8I10 (integer 16: comment lines, integer 17: npts; -32768 =
//    no value), 50 reals in 5E15.7 (real 2: samples per second; 1.7E+38 = no value), the
//    comment lines ('|'), then npts values (5E15.7 or 8E10.4). Values in cm/s^2.
//  - cosmos: COSMOS V1/V2 (format v1.20). Per channel: text header (line 1 "Corrected
//    acceleration ..."), "N Integer-header values follow on L lines, Format= (10I8)",
//    "N Real-header values follow on L lines, Format= (5F15.6)" (real 62: sampling interval in
//    ms), "N Comment line(s) follow", then data blocks "NPTS acceleration pts, approx T secs,
//    units=cm/sec2(04),Format=(8F10.5)" (also velocity, displacement: skipped), ended by "/&" or
//    "End-of-data". Units from the block line's code (2 g, 4 cm/s^2, 10 gal, 11 mg, 7 in/s^2) or
//    its name; raw counts (50) are refused. Several channels in one file: `channel` picks one.
//  - knet: NIED K-NET / KiK-net ASCII. 17 header lines "Key  value" ("Origin Time" first,
//    "Sampling Freq(Hz)  100Hz", "Scale Factor  7845(gal)/8223790", "Memo." last), then counts,
//    8 a line. Acceleration = (count - mean of all counts) x scale factor, in gal.
//  - esm: ESM / ITACA ASCII ("KEY: value" header lines: SAMPLING_INTERVAL_S, NDATA, UNITS
//    (cm/s^2, m/s^2, g), DATA_TYPE ACCELERATION), then NDATA values.
//  - dmg: CSMIP/DMG V2 (CGS processed data): per channel a text header, integer and real
//    headers, then "NPTS points of accel data equally spaced at DT sec, in cm/sec2. (8f10.6)"
//    (older files: "... AT .020 SEC.  (UNITS: CM/SEC/SEC)") and the values, then the velocity
//    and displacement blocks (skipped), "/&" between channels. `channel` picks one.
//  - automatic: the format whose header the file's first lines show (the SMC header
//    structure, the COSMOS "Integer-header values follow" line, K-NET's "Origin Time" ...
//    "Scale Factor", ESM's "SAMPLING_INTERVAL_S:" and "NDATA:", DMG's "points of accel data";
//    at2 if "NPTS" appears in the first ten lines or the name ends in .at2); otherwise the
//    first data line decides: one number -> one_column, two -> two_column, anything that is
//    not a number -> delimited with a header.
//
// Channels: `channel` (1-based, the order in the file) picks one of a multi-channel COSMOS or
// DMG file; such a file with several channels and no channel given is an error listing them.
// A channel above 1 for a single-channel format is an error.
//
// Everywhere except inside AT2 headers, blank lines and lines starting with '#' or '%' are
// skipped; CRLF line ends and a UTF-8 byte-order mark are accepted. Numbers are parsed with
// std::from_chars (Fortran 'D' exponents accepted).
//
// Time columns: dt = (t_last - t_first) / (n - 1), rounded to 12 significant digits (so that
// times printed as 24.979999999999997 give dt = 0.02 exactly). Times must increase strictly, and every
// step must equal the median step within 1e-6 of it plus the rounding of the two printed
// times (half a unit in the last printed decimal of each: "0.02000" -> 0.5e-5; at most a
// quarter step), so rounding in print is accepted but a missing or repeated sample is not. A time column that does not start at 0
// is shifted: the Record starts at the first sample (noted in the description).
//
// Units: two-column, one-column and delimited files carry none unless the column name says
// them; the caller must give `units` (error otherwise).
//
// Every defect is an InputError "FILE:LINE: what was found (what was expected)": non-numeric
// tokens, NaN or infinite values, times not increasing or not uniform, NPTS different from
// the number of values, empty or truncated files, missing units or dt.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "adjoin/ground/record.hpp"

namespace adjoin {

struct RecordFormat {
  enum class Kind { automatic, at2, one_column, two_column, delimited, smc, cosmos, knet, esm, dmg };
  Kind kind = Kind::automatic;
  std::optional<AccelUnit> units;  // required unless the file says them
  std::optional<double> dt;        // s; one column (and delimited files without a time column)
  std::string time_column, accel_column;  // delimited: header name or 1-based index
  char delimiter = 0;                     // 0: guess
  int channel = 0;                        // multi-channel files: 1-based; 0: not given
};

// "auto", "at2", "one-column", "two-column", "delimited" (also "csv"), "smc", "cosmos",
// "knet" (also "kiknet"), "esm", "dmg" (also "csmip"); false if unknown. One table holds the
// names (src/ground/readers/registry.cpp).
bool parse_record_kind(const std::string& name, RecordFormat::Kind* kind);
std::string to_string(RecordFormat::Kind kind);
// The accepted format names, "auto, at2, one-column, ..." (for messages and --help).
std::string record_kind_names();

// The format the automatic choice finds from a file's content (and name): a format whose
// header the first lines show (at2, smc, cosmos, knet, esm, dmg), or automatic when none does
// (the column readers then decide from the first data line). InputError if the file cannot be
// read.
RecordFormat::Kind detect_record_format(std::string_view text, std::string_view name);
RecordFormat::Kind detect_record_format(const std::filesystem::path& path);

// Reads a file (InputError if it cannot be read or is malformed). Record::source is the path.
Record read_record(const std::filesystem::path& path, const RecordFormat& format = {});

// Parses text already in memory; `name` is used as the file name in messages and as source.
// The automatic format looks at `name`'s extension like read_record does.
Record parse_record(std::string_view text, const std::string& name, const RecordFormat& format = {});

}  // namespace adjoin
