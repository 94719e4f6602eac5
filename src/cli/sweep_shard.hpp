#pragma once
// Running a sweep's runs through its journal (cli-internal): `adjoin sweep` and `adjoin ida`'s
// stripes (both a SweepSpec) resume the same way. In sweep.cpp.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/study/sweep.hpp"

namespace adjoin::cli {

// The rows of a shard: those taken from the journal and those run now.
struct ShardRows {
  std::vector<std::vector<std::string>> rows;  // ordered by index
  std::size_t from_journal = 0;
};

// Runs the shard's runs that its journal does not hold yet; returns every row of the shard
// (journal + new), ordered by index. The journal (DIR/<stem>.partial.csv) stays until the
// caller removes it. Journal rows that are not this sweep's (a value that is not finite, an
// axis value the sweep does not have, ...) are dropped with a warning and run again.
ShardRows run_shard(const SweepSpec& spec, const SweepShard& shard, const std::filesystem::path& dir, unsigned jobs,
                    bool progress_bar, bool verbose);

}  // namespace adjoin::cli
