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
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/model/parameters.hpp"
#include "adjoin/model/units.hpp"
#include "adjoin/solver/options.hpp"

namespace adjoin {

// Response spectra computed inside a run ([output.spectra]; its presence asks for them).
struct SpectraOutput {
  // "ground" (a_g), "block1", "block2" (the blocks' absolute accelerations: in-structure spectra).
  std::vector<std::string> signals{"ground", "block1", "block2"};
  std::vector<double> damping{0.05};
  std::vector<double> periods;  // in the scene's time unit; empty: 100 log-spaced from 0.01 to 10
};

// What a run computes and writes ([output]). What is not asked is neither computed nor kept.
// The summary's parts are cheap (constant memory) and on by default; files are off unless asked.
struct OutputOptions {
  bool peaks = true;            // output.peaks: peaks in summary.json
  bool phases = true;           // output.phases: phase intervals in summary.json
  bool pounding = true;         // output.pounding: the pounding margin in summary.json
  bool energy = true;           // output.energy: the final energy balance in summary.json
  bool timeseries = false;      // output.timeseries: write timeseries.csv (streamed)
  bool energy_history = false;  // output.energy_history: write energy.csv (streamed)
  std::size_t every = 1;        // output.every: keep every n-th grid point in the CSV files
  std::optional<SpectraOutput> spectra;  // [output.spectra]: write spectra.csv
};

// How a run checks its own accuracy, and how its step and horizon were chosen.
struct AccuracyOptions {
  // solver.error_estimate (default true): `adjoin run` estimates the error of its reported
  // values from a companion run at about 2h (study/error_estimate.hpp). Sweeps and
  // convergence ladders do not (their own comparisons are the point, and sweeps are many).
  bool error_estimate = true;
  // solver.tolerance: the step is chosen to meet it (relative error of the peaks), instead of
  // solver.h. When neither is given the tolerance is 1e-6.
  std::optional<double> tolerance;
  // How h and t_end were chosen, in words, when the scene did not give them ("" if it did).
  std::string h_rule, t_end_rule;
};

struct Scene {
  std::string name;
  std::filesystem::path file;  // where it was read from (empty if built in code)
  Model model;                 // dimensionless, valid
  Scales scales;               // dimensionless <-> scene units
  std::shared_ptr<const GroundMotion> ground;
  SolverOptions solver;        // dimensionless h and t_end
  OutputOptions output;
  AccuracyOptions accuracy;
  // Valid but probably unintended choices ("solver.h is coarser than the record's dt"): the
  // command line prints them on stderr as "warning: ..." and the run goes on.
  std::vector<std::string> warnings;
};

// Reads and checks a scene file; `overrides` are "dotted.key=value" strings (TOML values; a
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

// The [ground], [solver] and [output] of a building scene (SPEC §5) as a Scene whose model is a
// unit two-block system (1 kg, 1 N/m, elastic, no damper): times in seconds, a_g in g.
// `overrides` are --set edits of those sections, `unsets` keys of them removed first.
// io/building_scene.hpp uses it.
Scene parse_building_base(const std::string& text, const std::string& name, const std::vector<std::string>& overrides = {},
                          const std::vector<std::string>& unsets = {});

// Every key a scene may hold, as dotted paths (for documentation and error messages).
const std::vector<std::string>& known_scene_keys();

}  // namespace adjoin
