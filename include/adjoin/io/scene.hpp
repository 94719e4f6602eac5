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
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/model/parameters.hpp"
#include "adjoin/model/units.hpp"
#include "adjoin/solver/options.hpp"

namespace adjoin {

// What a run computes and writes beyond summary.json ([output]; absent keys mean "not needed").
struct OutputOptions {
  bool timeseries = false;    // output.timeseries: write timeseries.csv
  std::size_t every = 1;      // output.every: keep every n-th grid point in timeseries.csv
};

struct Scene {
  std::string name;
  std::filesystem::path file;  // where it was read from (empty if built in code)
  Model model;                 // dimensionless, valid
  Scales scales;               // dimensionless <-> scene units
  std::shared_ptr<const GroundMotion> ground;
  SolverOptions solver;        // dimensionless h and t_end
  OutputOptions output;
};

// Reads and checks a scene file; `overrides` are "dotted.key=value" strings (TOML values; a
// bare word is taken as a string).
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
// The same from TOML text; `name` stands for the file in messages.
Scene parse_scene(const std::string& text, const std::string& name,
                  const std::vector<std::string>& overrides = {});

// Every key a scene may hold, as dotted paths (for documentation and error messages).
const std::vector<std::string>& known_scene_keys();

}  // namespace adjoin
