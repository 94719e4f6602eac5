// Fuzzes the record readers: any bytes must parse or raise InputError, never crash, hang or
// trip a sanitizer. The first byte picks the declared format and units, as a user would.
#include <cstdint>
#include <string_view>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  using Kind = adjoin::RecordFormat::Kind;
  adjoin::RecordFormat format;
  const std::uint8_t pick = data[0];
  const Kind kinds[] = {Kind::automatic, Kind::at2, Kind::one_column, Kind::two_column, Kind::delimited,
                        Kind::smc, Kind::cosmos, Kind::knet, Kind::esm, Kind::dmg, Kind::automatic};
  format.kind = kinds[pick % 11];
  if (pick & 0x80) format.channel = 1 + (pick >> 5) % 3;  // multi-channel files
  if (pick & 0x08) format.units = adjoin::AccelUnit::g;
  if (pick & 0x10) format.dt = 0.01;
  if (pick & 0x20) { format.time_column = "t"; format.accel_column = "2"; }
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const adjoin::Record r = adjoin::parse_record(text, (pick & 0x40) ? "fuzz.AT2" : "fuzz.txt", format);
    (void)r;
  } catch (const adjoin::InputError&) {
  }
  return 0;
}
