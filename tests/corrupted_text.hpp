#pragma once
// For the readers' random-corruption tests: a corrupted text either parses into a usable
// record or is refused with an InputError naming the file; nothing else may happen.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"

namespace adjoin::test {

// True if `text` parsed (positive dt, samples, all finite), false if refused as "fuzz: ...".
inline bool parses_or_is_refused(const std::string& text, const RecordFormat& format) {
  try {
    const Record r = parse_record(text, "fuzz", format);
    CHECK(r.dt > 0.0);
    CHECK(!r.accel.empty());
    for (double a : r.accel) REQUIRE(std::isfinite(a));
    return true;
  } catch (const InputError& e) {
    REQUIRE(std::string(e.what()).rfind("fuzz", 0) == 0);
    return false;
  }
}

}  // namespace adjoin::test
