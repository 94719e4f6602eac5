#pragma once
// A building scene (SPEC §5) read whole: its structure (io/structure_file.hpp) and its ground,
// solver and output sections (the two-block scene's keys, read by the same code), with the
// step and horizon chosen when not given (the rules are said in `h_rule`, `t_end_rule`).
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin {

// The run description itself is study's (study/run_spec.hpp); io reads files into it.
using BuildingScene = RunSpec;

// Without solver.h and solver.tolerance a building scene's step is chosen for
// kBuildingDefaultTolerance (study/builder.hpp, with the other run-level rules).

// `overrides`: --set edits by dotted path of any key: the structure's (building.A.period,
// building.B.damping.ratio, link.1.slip_ratio, contact.1.gap; io/structure_file.hpp) and
// [ground], [solver], [output] and name. `unsets`: --unset keys or sections removed first
// (link.1, link, building.A.device.2, ground.scale_pga).
BuildingScene load_building_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {},
                                  const std::vector<std::string>& unsets = {});
// The same from the scene's text; `file` names it in messages and its folder is where the
// scene's relative paths (ground.file) start. (A sweep parses its base once and reads each run
// from a copy of the tree: src/io/sweep_scene_tree.hpp building_scene_from_tree.)
BuildingScene parse_building_scene(const std::string& text, const std::filesystem::path& file,
                                   const std::vector<std::string>& overrides = {},
                                   const std::vector<std::string>& unsets = {});

}  // namespace adjoin
