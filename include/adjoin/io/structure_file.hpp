#pragma once
// Building scenes (SPEC §5 keys: [building.A], [building.B], [[building.X.device]], [[link]],
// [[contact]]) read into a structure::Structure, and the two-block scenes of SPEC §3 seen as
// the smallest structure (one floor each, Zener storeys, one friction link, one contact).
//
// Errors are InputError naming "file:line: key" and what was expected.
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/structure/building.hpp"

namespace adjoin {

// True if the scene text has a [building] table (a building scene, not a two-block one).
bool is_building_scene(const std::filesystem::path& file);

// Reads the structure of a building scene (SI units); `file` names it in messages.
structure::Structure read_structure(const std::filesystem::path& file);
structure::Structure parse_structure(const std::string& text, const std::string& file);
// The same after edits by dotted path: `unsets` ("link.2", "building.B") removed first, then
// the `overrides` ("building.A.period=0.8", "link.1.slip_ratio=0.1"); only the structure's keys
// (building, link, contact) are taken, the others are left to the caller. A value an edit put
// there is blamed on its --set in messages.
structure::Structure parse_structure(const std::string& text, const std::string& file,
                                     const std::vector<std::string>& overrides, const std::vector<std::string>& unsets);
// True if the dotted key (of a --set or --unset) is one of the structure's (building, link,
// contact).
bool is_structure_key(const std::string& key);

// The two-block system of a (two-block) scene as a structure, in the scene's units: SI for SI
// scenes; for dimensionless ones m1 = k1 = 1 (periods in the scene's time unit).
structure::Structure structure_of(const Scene& scene);

}  // namespace adjoin
