// Fuzzes the scene loader (TOML, key checking, validation, SI scaling): any text must load or
// raise InputError, never crash, hang or trip a sanitizer. Scenes that load are not solved.
//
// Scenes whose ground is a record or synthetic noise are skipped: loading them reads a file
// named by the input (which could be /dev/zero) or synthesizes up to 2^26 samples, work that
// is valid but unbounded; the record readers have their own fuzzer (fuzz_record.cpp) and the
// synthesis its own tests.
#include <cstdint>
#include <string>
#include <toml++/toml.h>

#include "adjoin/errors.hpp"
#include "adjoin/io/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const toml::table table = toml::parse(text);
    const auto source = table.at_path("ground.source").value<std::string>();
    if (source && (*source == "record" || *source == "filtered-noise")) return 0;
  } catch (const toml::parse_error&) {
    // not TOML: the loader must say so
  }
  try {
    const adjoin::Scene scene = adjoin::parse_scene(text, "/nonexistent/fuzz.toml");
    (void)scene;
  } catch (const adjoin::InputError&) {
  }
  return 0;
}
