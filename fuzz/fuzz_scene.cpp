// Fuzzes the scene loader (TOML, key checking, validation, SI scaling): any text must load or
// raise InputError, never crash, hang or trip a sanitizer. Scenes that load are not solved.
#include <cstdint>
#include <string>

#include "adjoin/errors.hpp"
#include "adjoin/io/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const adjoin::Scene scene = adjoin::parse_scene(text, "/nonexistent/fuzz.toml");
    (void)scene;
  } catch (const adjoin::InputError&) {
  }
  return 0;
}
