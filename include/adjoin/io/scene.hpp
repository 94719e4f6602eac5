#pragma once
// Scenes: a whole run described in one TOML file (SPEC §3 "Scenes").
//
//     Scene scene = load_scene("records/scenes/paper-strong.toml", {"solver.h=0.001"});
//
// load_scene reads the file, applies `--set KEY=VALUE` overrides by dotted path, checks every
// key against the known ones (an unknown key is an error naming the nearest known key), checks
// types and the model's restrictions, and converts an SI scene to the solver's dimensionless
// form. Every problem is an InputError whose message starts with "FILE:LINE:" (or
// "--set KEY=VALUE:") and names the key and what is expected.
//
// Record and synthetic grounds are built once per process: scenes whose [ground] section (and
// time scale) are the same share one immutable GroundMotion, so a sweep reads, processes or
// synthesises and matches its motions once, not once per run. A record or target-table file
// whose size or modification time changed is read again. At most 32 grounds are kept.
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/study/run_spec.hpp"

namespace adjoin {

// The run description itself is study's (study/run_spec.hpp); io reads files into it.
using Scene = RunSpec;

// Reads and checks a scene file, a building scene (SPEC §5: io/building_scene.hpp) or a
// two-block one (SPEC §3); `overrides` are "dotted.key=value" strings (TOML values; a
// bare word is taken as a string), `unsets` dotted keys or sections removed first (`--unset`;
// each must exist). Overrides restructure the scene as a sweep's edits do
// (implied_unsets): `ground.source` set to another source drops the old source's [ground]
// keys, `model.rodN.elastic = true` drops the rod's order and relaxation times.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {},
                 const std::vector<std::string>& unsets = {});

// The keys an edit `key = value` (value as TOML text) makes obsolete in a scene whose current
// ground source is `current_source`: one rule for --set and for sweeps.
std::vector<std::string> implied_unsets(const std::string& key, const std::string& value,
                                        const std::string& current_source);
// The same from TOML text; `name` stands for the file in messages. `removed` are dotted keys
// taken out of the text before the overrides apply (sweeps' `unset`); messages about the rest
// still cite the text's own lines.
Scene parse_scene(const std::string& text, const std::string& name,
                  const std::vector<std::string>& overrides = {}, const std::vector<std::string>& removed = {});

// The [ground], [solver] and [output] of a building scene (SPEC §5) as a Scene without a
// structure (its reader adds it), in SI scales of 1: times in seconds, a_g in g.
// `overrides` are --set edits of those sections, `unsets` keys of them removed first.
// io/building_scene.hpp uses it.
Scene parse_building_base(const std::string& text, const std::string& name, const std::vector<std::string>& overrides = {},
                          const std::vector<std::string>& unsets = {});

// Every key a scene may hold, as dotted paths (for documentation and error messages).
const std::vector<std::string>& known_scene_keys();

}  // namespace adjoin
