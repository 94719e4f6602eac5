// toml++'s implementation, compiled once into the library: every file includes toml++ with
// TOML_HEADER_ONLY=0 (as its package's CMake target sets), so the definitions come from here
// and the program needs no libtomlplusplus.so, nor through it libstdc++.so, at start (the
// dynamic linker's look-ups; docs/explanation/benchmarks.md).
#define TOML_IMPLEMENTATION
#include <toml++/toml.h>
