#pragma once
// The building reader's message for a scene text with one edit: for the tests of messages that
// name a file, line and key.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"

namespace adjoin::test {

// The InputError's message for `text` with `from` replaced by `to`, read as if from
// `file_name` in the test's scratch folder; FAILs if `from` is not in `text` or the reader
// accepts the edited scene.
inline std::string building_scene_error(std::string text, const std::string& from, const std::string& to,
                                        const std::string& file_name) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  try {
    parse_building_scene(text, std::filesystem::path(ADJOIN_TEST_TMP) / file_name);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("the building reader accepted " << to);
  return {};
}

}  // namespace adjoin::test
