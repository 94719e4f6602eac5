// Fuzzes the scene loader (TOML, key checking, validation, SI scaling, and the ground sources
// with their processing): any input must load or raise InputError, never crash, hang or trip
// a sanitizer. Scenes that load are not solved.
//
// Input: a scene, optionally followed by a line "#---record---" and the text of a record
// file. A scene whose ground is a record reads that record (written to a scratch file the
// harness names in ground.file), so the readers are fuzzed together with the scene's
// processing keys (window, baseline, padding, filters, resampling, scaling). Work is bounded
// so each input runs in milliseconds: inputs are at most libFuzzer's -max_len, and scenes
// that ask for very long padding, very fine resampling, more than 2^15 synthetic samples or
// spectrum matching of more than 1024 samples are skipped (valid but slow, not interesting to
// the fuzzer), and a matching scene is loaded with ground.match_tolerance = 0.99 so that it
// stops after a few corrections.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <toml++/toml.h>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/scene.hpp"

namespace {

const std::string kSeparator = "#---record---\n";

double number_or(const toml::table& t, const char* path, double fallback) {
  const auto node = t.at_path(path);
  if (!node) return fallback;
  if (auto v = node.value<double>()) return *v;
  return fallback;
}

// Valid but slow grounds: skipped, see the header.
bool too_much_work(const toml::table& t, const std::string& source) {
  if (source == "record") {
    if (number_or(t, "ground.pad_before", 0) > 200 || number_or(t, "ground.pad_after", 0) > 200) return true;
    if (t.at_path("ground.resample_dt") && !(number_or(t, "ground.resample_dt", 1) >= 1e-3)) return true;
    if (t.at_path("ground.dt") && !(number_or(t, "ground.dt", 1) >= 1e-4)) return true;
  }
  if (source == "filtered-noise") {
    const double duration = number_or(t, "ground.duration", 20.0), dt = number_or(t, "ground.dt", 0.005);
    if (!(dt > 0) || !(duration / dt < 32768.0)) return true;
    // Matching repeats a response spectrum up to 100 times in each of 5 attempts (the harness
    // also loosens its tolerance, below).
    const bool matching = t.at_path("ground.match_ec8") || t.at_path("ground.match_table");
    if (matching && !(duration / dt <= 1024.0)) return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  std::string record;
  if (const auto at = text.find(kSeparator); at != std::string::npos) {
    record = text.substr(at + kSeparator.size());
    text.resize(at);
  }
  std::vector<std::string> overrides;
  try {
    const toml::table table = toml::parse(text);
    const std::string source = table.at_path("ground.source").value_or(std::string());
    if (too_much_work(table, source)) return 0;
    if (table.at_path("ground.match_ec8") || table.at_path("ground.match_table"))
      overrides.push_back("ground.match_tolerance=0.99");
    if (source == "record") {
      static const std::string file = "/tmp/adjoin-fuzz-scene-record." + std::to_string(::getpid());
      std::ofstream(file, std::ios::binary | std::ios::trunc) << record;
      overrides.push_back("ground.file=\"" + file + "\"");
    }
  } catch (const toml::parse_error&) {
    // not TOML: the loader must say so
  }
  try {
    const adjoin::Scene scene = adjoin::parse_scene(text, "/nonexistent/fuzz.toml", overrides);
    (void)scene;
  } catch (const adjoin::InputError&) {
  }
  return 0;
}
