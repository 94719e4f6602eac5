#pragma once
// A run's values by channel name, for the tests that compare runs.
#include <catch2/catch.hpp>

#include <string>

#include "adjoin/study/report.hpp"

namespace adjoin::test {

// The peak |value| of `channel` in the report; the test fails if the run has no such channel.
inline double peak(const Report& r, const std::string& channel) {
  for (const auto& p : r.peaks)
    if (p.channel == channel) return p.peak.max_abs;
  FAIL("no peak of " << channel);
  return 0.0;
}

}  // namespace adjoin::test
