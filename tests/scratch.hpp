#pragma once
// Force-included into every test program (see tests/CMakeLists.txt). CTest runs test cases as
// separate processes in parallel, so each process gets its own scratch folder:
// ADJOIN_TEST_TMP is <build>/tests/tmp/p<pid>, created on first use.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace adjoin::test {

inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    const std::string d = std::string(ADJOIN_TEST_TMP_ROOT) + "/p" + std::to_string(::getpid());
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace adjoin::test

#define ADJOIN_TEST_TMP (::adjoin::test::scratch_dir())
