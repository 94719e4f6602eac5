#pragma once
// adjoin.Scene: a scene the library's readers accepted, with the TOML it came from and its
// set/unset edits (for to_dict and to_toml). Shared by io.cpp (which makes it) and study.cpp
// and structure.cpp (which run it and compute its modes).
#include <filesystem>
#include <string>
#include <vector>

#include "run_facade.hpp"

namespace adjoin::python {

struct SceneObject {
  LoadedScene loaded;
  std::string text;             // the TOML as given (a file's text, or a dict's as toml++ writes it)
  std::filesystem::path file;   // names it in messages; its folder is where relative paths start
  std::vector<std::string> overrides, unsets;  // load_scene(set=, unset=), as --set/--unset text
};

}  // namespace adjoin::python
