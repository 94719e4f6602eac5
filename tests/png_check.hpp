#pragma once
// Checks that a file is a drawn PNG of the requested size: the signature, the IHDR chunk's
// width and height, and enough bytes for a real drawing rather than an empty canvas.
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <string>

#include "cli_helpers.hpp"

namespace adjoin::test {

inline std::uint32_t big_endian(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

inline void require_png(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height) {
  INFO(file.string());
  REQUIRE(std::filesystem::exists(file));
  const std::string bytes = slurp(file);
  REQUIRE(bytes.size() > 33);
  CHECK(bytes.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
  CHECK(bytes.substr(12, 4) == "IHDR");
  CHECK(big_endian(bytes, 16) == width);
  CHECK(big_endian(bytes, 20) == height);
  CHECK(bytes.size() > 10000);  // a real drawing, not an empty canvas
}

}  // namespace adjoin::test
