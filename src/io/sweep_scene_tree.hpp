#pragma once
// Scenes read from their parsed TOML tree (internal to io): a sweep parses its base scene once
// and reads each run's scene from a copy of the tree with the run's edits
// (src/io/sweep_scenes.cpp); parse_scene() and parse_building_scene() are the same after
// parsing the text.
#include <filesystem>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <toml++/toml.h>

#include "adjoin/structure/building.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin::detail {

// One `--set` edit: its text "KEY=VALUE" (what messages cite), and the value already typed
// ({"v" = value}) when the caller has it, so that the text's value is not parsed again.
struct SceneEdit {
  std::string text;
  const toml::table* typed = nullptr;
};

// The scene of `table` (the scene file's tree, `name` its file in messages) after removing the
// dotted keys `removed` (those that are there) and applying `edits` in order, with every check
// and message of parse_scene(). `lines`: when `table` is a copy of the parsed file (a copy's
// nodes lose their lines), the parsed file, whose lines messages cite; else null.
RunSpec scene_from_tree(toml::table table, const std::string& name, const std::vector<SceneEdit>& edits,
                        const std::vector<std::string>& removed, const toml::table* lines = nullptr);

// Each node of a copy of a parsed tree -> the parsed node it was copied from: toml++ copies do
// not keep source lines, and a building scene's arrays of tables ([[link]]) shift under
// --unset link.1, so its reader finds a copied node's line through the node, not its path.
// Edits replace the nodes they set (new nodes, absent here) and leave the others in place.
using CopiedFrom = std::unordered_map<const toml::node*, const toml::node*>;
CopiedFrom copied_from(const toml::node& copy, const toml::node& parsed);

// A building scene (SPEC §5, io/building_scene.hpp) from `parsed`, its file's tree as parsed:
// read from a copy after the `unsets` and `overrides` (--unset / --set strings), with every
// check and message of parse_building_scene(), which is this after parsing the text.
RunSpec building_scene_from_tree(const toml::table& parsed, const std::filesystem::path& file,
                                         const std::vector<std::string>& overrides,
                                         const std::vector<std::string>& unsets);

// The structure of `root` after the structure's edits (made on `root`; io/structure_file.hpp
// parse_structure). `copied`: when `root` is a copy, where its nodes came from (their lines).
structure::Structure structure_from_tree(toml::table& root, const std::string& file,
                                         const std::vector<std::string>& overrides,
                                         const std::vector<std::string>& unsets, const CopiedFrom* copied = nullptr);

// parse_building_base() (io/scene.hpp) of a tree; `lines` as for scene_from_tree.
RunSpec building_base_from_tree(toml::table table, const std::string& name, const std::vector<std::string>& overrides,
                                const std::vector<std::string>& unsets, const toml::table* lines = nullptr);

}  // namespace adjoin::detail
