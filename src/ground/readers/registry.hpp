#pragma once
// Internal: the record readers, one file each, behind one table (registry.cpp). Each entry
// has a name (what --format and ground.format take), a content sniffer that returns a
// confidence (0: not this format) and a parse function. The automatic format picks the entry
// with the highest confidence; when none claims the file, the column readers decide from the
// first data line (columns.cpp).
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "adjoin/ground/record_file.hpp"
#include "text.hpp"

namespace adjoin::readers {

// What a sniffer sees: the file's name and its first lines.
struct Probe {
  std::string_view name;
  std::vector<Line> head;  // at most kProbeLines lines
};
inline constexpr std::size_t kProbeLines = 80;

using Sniffer = int (*)(const Probe&);
using Parser = Record (*)(std::string_view text, const std::string& name, const RecordFormat& format);

struct ReaderEntry {
  RecordFormat::Kind kind;
  std::string_view name;            // canonical name, as to_string(kind) gives it
  std::string_view aliases;         // other accepted names, blank-separated
  std::string_view title;           // "USGS SMC", for messages and --help
  bool multi_channel;               // may hold several channels (RecordFormat::channel)
  Sniffer sniff;                    // nullptr: never chosen by content
  Parser parse;
};

// Every reader, in the order of RecordFormat::Kind (automatic first, with no parser).
std::span<const ReaderEntry> reader_table();
const ReaderEntry& reader_entry(RecordFormat::Kind kind);

// The readers (one .cpp each).
int sniff_at2(const Probe&);
Record parse_at2(std::string_view, const std::string&, const RecordFormat&);
Record parse_one_column(std::string_view, const std::string&, const RecordFormat&);
Record parse_two_column(std::string_view, const std::string&, const RecordFormat&);
Record parse_delimited(std::string_view, const std::string&, const RecordFormat&);
// The automatic choice among the column formats (one number, two numbers, or a header line).
Record parse_columns_auto(std::string_view, const std::string&, const RecordFormat&);
int sniff_smc(const Probe&);
Record parse_smc(std::string_view, const std::string&, const RecordFormat&);
int sniff_cosmos(const Probe&);
Record parse_cosmos(std::string_view, const std::string&, const RecordFormat&);
int sniff_knet(const Probe&);
Record parse_knet(std::string_view, const std::string&, const RecordFormat&);
int sniff_esm(const Probe&);
Record parse_esm(std::string_view, const std::string&, const RecordFormat&);
int sniff_dmg(const Probe&);
Record parse_dmg(std::string_view, const std::string&, const RecordFormat&);

}  // namespace adjoin::readers
