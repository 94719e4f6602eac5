// The table of record readers: names, content sniffers and parsers in one place, so that
// --format, ground.format, the automatic choice and the messages cannot disagree.
#include "registry.hpp"

#include <array>

namespace adjoin::readers {
namespace {

using Kind = RecordFormat::Kind;

// In the order of RecordFormat::Kind.
constexpr std::array<ReaderEntry, 10> kReaders = {{
    {Kind::automatic, "auto", "automatic", "automatic", true, nullptr, nullptr},
    {Kind::at2, "at2", "peer", "PEER AT2", false, sniff_at2, parse_at2},
    {Kind::one_column, "one-column", "one_column 1col", "one-column text", false, nullptr, parse_one_column},
    {Kind::two_column, "two-column", "two_column 2col", "two-column text", false, nullptr, parse_two_column},
    {Kind::delimited, "delimited", "csv", "delimited text", false, nullptr, parse_delimited},
    {Kind::smc, "smc", "usgs-smc", "USGS SMC", false, sniff_smc, parse_smc},
    {Kind::cosmos, "cosmos", "v1 v2 v1c v2c", "COSMOS V1/V2", true, sniff_cosmos, parse_cosmos},
    {Kind::knet, "knet", "kiknet k-net kik-net nied", "K-NET/KiK-net ASCII", false, sniff_knet, parse_knet},
    {Kind::esm, "esm", "itaca", "ESM ASCII", false, sniff_esm, parse_esm},
    {Kind::dmg, "dmg", "csmip cgs", "CSMIP/DMG V2", true, sniff_dmg, parse_dmg},
}};

}  // namespace

std::span<const ReaderEntry> reader_table() { return kReaders; }

const ReaderEntry& reader_entry(RecordFormat::Kind kind) {
  for (const ReaderEntry& entry : kReaders)
    if (entry.kind == kind) return entry;
  return kReaders[0];
}

}  // namespace adjoin::readers

namespace adjoin {

bool parse_record_kind(const std::string& name, RecordFormat::Kind* kind) {
  const std::string n = readers::to_lower(readers::trim(name));
  if (n.empty()) return false;
  for (const readers::ReaderEntry& entry : readers::reader_table()) {
    bool match = n == entry.name;
    std::vector<std::string_view> aliases;
    readers::split(entry.aliases, 0, aliases);
    for (std::string_view alias : aliases) match = match || n == alias;
    if (match) {
      if (kind) *kind = entry.kind;
      return true;
    }
  }
  return false;
}

std::string to_string(RecordFormat::Kind kind) { return std::string(readers::reader_entry(kind).name); }

std::string record_kind_names() {
  std::string out;
  for (const readers::ReaderEntry& entry : readers::reader_table()) out += (out.empty() ? "" : ", ") + std::string(entry.name);
  return out;
}

}  // namespace adjoin
