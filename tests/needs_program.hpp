#pragma once
// A test case that needs a program from outside the project (gnuplot draws the figures,
// script(1) gives a command a terminal) starts with needs_program("gnuplot"). Without that
// program on PATH the case stops at once with a message that starts "ADJOIN_TEST_SKIPPED";
// tests/CMakeLists.txt tells CTest to report such a case as Skipped, and a test program run by
// hand fails with the message. A missing program is always seen: never a silent pass.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

namespace adjoin::test {

inline void needs_program(const std::string& name) {
  if (std::system(("command -v '" + name + "' >/dev/null 2>&1").c_str()) != 0)
    FAIL("ADJOIN_TEST_SKIPPED: " << name << " is not on PATH and this case needs it (scripts/setup.sh installs it)");
}

}  // namespace adjoin::test
