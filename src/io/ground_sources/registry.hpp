#pragma once
// Internal to io: the scene's ground sources, one file each, behind one table (registry.cpp),
// as the record readers are (ground/readers/). Each entry has the name `ground.source` takes,
// the [ground] keys the source accepts (with their types: the scene schema draws its ground
// keys from here) and the function that builds the motion from them. A new source is one file
// here (defining `GroundSource <id>_source()`) and one row of ADJOIN_GROUND_SOURCES below.
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "../scene_reader.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/ground/ground_motion.hpp"

namespace adjoin::detail {

// A key of the scene schema: its dotted path and type.
struct KeySpec {
  const char* path;
  Kind kind;
};

// Builds the motion from the [ground] table (its keys already checked against the source's),
// in the solver's units; an InputError through r.fail names the key at fault.
using GroundReader = std::shared_ptr<const GroundMotion> (*)(const SceneReader& r, const Scales& scales);

struct GroundSource {
  std::string_view name;                 // what ground.source takes
  std::span<const KeySpec> (*keys)();    // the [ground] keys it takes (ground.source aside)
  GroundReader read;
};

// Every source, in the order the scene schema lists their keys.
std::span<const GroundSource> ground_sources();

// The scene's [ground]: checks ground.source and that every key belongs to it, then builds
// the motion with that source.
std::shared_ptr<const GroundMotion> read_ground(const SceneReader& r, const Scales& scales);

// ground.scale (default 1), which every source takes: a plain factor applied to the motion the
// source built (ScaledMotion, ground/ground_motion.hpp); r.fail names the key unless it is a
// finite number > 0.
double read_ground_scale(const SceneReader& r);

// Shared by the sources that build a motion once per process (ground_cache.hpp): the cache
// key (the [ground] table after the overrides, the time scale, and `extra`: file stamps).
std::string ground_key(const SceneReader& r, double time_scale, const std::string& extra);
// The time scale of a motion given in seconds: T0 for SI scenes, ground.time_scale (default
// 1 s) for dimensionless ones.
double record_time_scale(const SceneReader& r, const Scales& scales);

// The sources, one .cpp each, in the order the scene schema lists their keys: each row is the
// id of a file's `GroundSource <id>_source()`.
#define ADJOIN_GROUND_SOURCES(ROW) \
  ROW(decaying_sine)               \
  ROW(record)                      \
  ROW(filtered_noise)              \
  /* a new source: its row above this line */

#define ADJOIN_DECLARE_GROUND_SOURCE(id) GroundSource id##_source();
ADJOIN_GROUND_SOURCES(ADJOIN_DECLARE_GROUND_SOURCE)
#undef ADJOIN_DECLARE_GROUND_SOURCE

}  // namespace adjoin::detail
