#pragma once
// Ground motions already built in this process, by what they were built from. Reading and
// processing a record, or synthesising and spectrum-matching a motion, can cost far more than
// the run it drives; sweeps load the same ground for every run. Used by the scene loader only.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "adjoin/ground/ground_motion.hpp"

namespace adjoin::detail {

// The motion stored under `key`, or make() stored under it and returned. The key must hold
// everything the motion depends on (file_stamp for files). Thread-safe; make() runs outside
// the lock (two threads may both make a missing motion; either result is kept). At most
// kGroundCacheSize motions are kept, the oldest dropped first.
inline constexpr std::size_t kGroundCacheSize = 32;
std::shared_ptr<const GroundMotion> cached_ground(const std::string& key,
                                                  const std::function<std::shared_ptr<const GroundMotion>()>& make);

// "path|size|modification time" of a file (its absolute path if it exists), so that a key
// changes when the file does.
std::string file_stamp(const std::filesystem::path& path);

}  // namespace adjoin::detail
