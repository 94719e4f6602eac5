// The table of ground sources: names, keys and builders in one place, so that the scene
// schema, the check of [ground]'s keys, the messages and the choice of builder cannot disagree.
#include "registry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "../../detail/nearest.hpp"
#include "adjoin/io/text_file.hpp"

namespace adjoin::detail {

std::span<const GroundSource> ground_sources() {
#define ADJOIN_GROUND_SOURCE_ENTRY(id) id##_source(),
  static const std::vector<GroundSource> sources = {ADJOIN_GROUND_SOURCES(ADJOIN_GROUND_SOURCE_ENTRY)};
#undef ADJOIN_GROUND_SOURCE_ENTRY
  return sources;
}

namespace {

// "\"decaying-sine\", \"record\" or \"filtered-noise\"".
std::string source_names() {
  const std::span<const GroundSource> sources = ground_sources();
  std::string out;
  for (std::size_t i = 0; i < sources.size(); ++i)
    out += (i == 0 ? "" : i + 1 == sources.size() ? " or " : ", ") + ("\"" + std::string(sources[i].name) + "\"");
  return out;
}

}  // namespace

std::shared_ptr<const GroundMotion> read_ground(const SceneReader& r, const Scales& scales) {
  const std::span<const GroundSource> sources = ground_sources();
  const std::string source = r.string("ground.source", "");
  if (source.empty()) r.fail("ground", "missing key ground.source (" + source_names() + ")");
  const auto entry = std::find_if(sources.begin(), sources.end(), [&](const GroundSource& s) { return s.name == source; });
  if (entry == sources.end()) {
    std::vector<std::string> names;
    for (const GroundSource& s : sources) names.emplace_back(s.name);
    std::sort(names.begin(), names.end());
    r.fail("ground.source", "ground.source = " + escaped_excerpt(source) + " is not a known source; did you mean \"" +
                                nearest(source, names) + "\"?");
  }
  const std::span<const KeySpec> allowed = entry->keys();
  for (const auto& [key, node] : *r.table()["ground"].as_table()) {
    const std::string k(key.str()), path = "ground." + k;
    if (k != "source" && k != "scale" && std::none_of(allowed.begin(), allowed.end(), [&](const KeySpec& s) { return path == s.path; }))
      r.fail(path, text_excerpt(path) + " is not a key of source \"" + source + "\"");
  }
  return scale_ground(entry->read(r, scales), read_ground_scale(r));
}

double read_ground_scale(const SceneReader& r) {
  const double factor = r.number("ground.scale", 1.0);
  if (!(std::isfinite(factor) && factor > 0.0))
    r.fail("ground.scale", "ground.scale = " + format_scene_number(factor) +
                               " must be a finite number > 0 (a plain factor on the ground's acceleration)");
  return factor;
}

std::string ground_key(const SceneReader& r, double time_scale, const std::string& extra) {
  std::ostringstream key;
  // Without ground.scale, applied after the cache (read_ground): a record read once serves
  // every scale of it (an IDA's levels, a suite's factors).
  toml::table ground = *r.table()["ground"].as_table();
  ground.erase("scale");
  key << toml::toml_formatter(ground);
  char scale[32];
  std::snprintf(scale, sizeof scale, "%.17g", time_scale);
  key << "\n" << scale << "\n" << extra;
  return key.str();
}

double record_time_scale(const SceneReader& r, const Scales& scales) {
  if (scales.si) {
    if (r.has("ground.time_scale")) r.fail("ground.time_scale", "ground.time_scale is set by m1 and k1 in an SI scene; remove it");
    return scales.time;
  }
  const double time_scale = r.number("ground.time_scale", 1.0);
  if (!(std::isfinite(time_scale) && time_scale > 0.0))
    r.fail("ground.time_scale", "ground.time_scale = " + format_scene_number(time_scale) + " must be a positive number of seconds");
  return time_scale;
}

}  // namespace adjoin::detail
