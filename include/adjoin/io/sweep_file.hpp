#pragma once
// The sweep file's reader (docs/reference/sweep-file.md; the sweep itself is study's, study/sweep.hpp):
//
//     SweepSpec spec = load_sweep("examples/sweeps/slip-force.toml");
//     std::vector<SweepRow> rows = run_sweep(spec);
//
// Every problem is an InputError "FILE:LINE: ...". The base scene is read and checked once (its
// own errors name its file and line), and the spec's `scenes` (io/sweep_scenes.hpp) make the
// runs' descriptions from it. The fingerprint hashes the sweep text, the base scene's text and
// the version.
#include <filesystem>
#include <string>

#include "adjoin/study/sweep.hpp"

namespace adjoin {

SweepSpec load_sweep(const std::filesystem::path& file);
// The same from text; `name` stands for the file in messages and paths are relative to its folder.
SweepSpec parse_sweep(const std::string& text, const std::string& name);
// A sweep's fingerprint (its journal's key: a resumed run must be the same sweep): 16 hex
// digits of FNV-1a over the study's text, the base scene's text and the version.
std::string sweep_fingerprint(const std::string& text, const std::string& base_text);

}  // namespace adjoin
