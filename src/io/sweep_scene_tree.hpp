#pragma once
// A two-block scene read from its parsed TOML tree (internal to io): a sweep parses its base
// scene once and reads each run's scene from a copy of the tree with the run's edits set as
// typed values (src/io/sweep_scenes.cpp); parse_scene() is the same after parsing the text.
#include <string>
#include <vector>

#include <toml++/toml.h>

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

}  // namespace adjoin::detail
