#pragma once
// Building scenes (SPEC §5 keys: [building.A], [building.B], [[building.X.device]], [[link]],
// [[contact]]) read into a structure::Structure, and the two-block scenes of SPEC §3 seen as
// the smallest structure (one floor each, Zener storeys, one friction link, one contact).
//
// Errors are InputError naming "file:line: key" and what was expected.
#include <filesystem>
#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/structure/building.hpp"

namespace adjoin {

// True if the scene text has a [building] table (a building scene, not a two-block one).
bool is_building_scene(const std::filesystem::path& file);

// Reads the structure of a building scene (SI units); `file` names it in messages.
structure::Structure read_structure(const std::filesystem::path& file);
structure::Structure parse_structure(const std::string& text, const std::string& file);

// The two-block system of a (two-block) scene as a structure, in the scene's units: SI for SI
// scenes; for dimensionless ones m1 = k1 = 1 (periods in the scene's time unit).
structure::Structure structure_of(const Scene& scene);

}  // namespace adjoin
