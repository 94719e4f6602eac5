#pragma once
// What a run is, typed and free of any file format (SPEC §4): the structure, the scales between
// the solver's numbers and the user's units, the ground, the solver's options and what the run
// computes and writes. io/ reads scene files into it (io/scene.hpp); study/ runs it
// (study/run.hpp) and sweeps edit it (study/sweep.hpp).
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/structure/parameters.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/solver/options.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/building.hpp"

namespace adjoin {

// Response spectra computed inside a run ([output.spectra]; its presence asks for them).
struct SpectraOutput {
  // "ground" (a_g) or a floor's absolute acceleration X.aN_abs (in-structure spectra). A
  // two-block scene's "block1" and "block2" are A.a1_abs and B.a1_abs (io presents them so).
  std::vector<std::string> signals{"ground", "A.a1_abs", "B.a1_abs"};
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
  // output.every: keep every n-th grid point in the CSV files; 0: not given, the run's rule
  // (1 for two-block runs; structure runs with a chosen step: io/timeseries_csv.hpp output_every).
  std::size_t every = 0;
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
  bool tolerance_given = false;  // solver.tolerance is the scene's (not a default)
  // How h and t_end were chosen, in words, when the scene did not give them ("" if it did).
  std::string h_rule, t_end_rule;
};

class RunWatch;  // study/run_watch.hpp

// One run, whatever the scene: a building pair (SPEC §5) in SI units, or the paper's two blocks
// (SPEC §1, a scene written with the two-block keys) as their 1 + 1 structure
// (structure/two_block.hpp) in the model's dimensionless units.
struct RunSpec {
  std::string name;
  std::filesystem::path file;  // where it was read from (empty if built in code)
  // The structure (SPEC §5) in the solver's numbers: SI, or a two-block spec's dimensionless.
  structure::Structure structure;
  // A two-block spec: `structure` is the paper's model's 1 + 1 structure (two_block_model()
  // reads the model back), the `paper` scheme may run it, and io presents its results under the
  // two-block names of SPEC §3. False: a building pair.
  bool two_block_scene = false;
  Scales scales;  // the solver's numbers <-> the scene's units (a building's: SI, all 1)
  // a_g against time: in g and seconds for a building; for a two-block spec in the model's
  // dimensionless units (SPEC §1).
  std::shared_ptr<const GroundMotion> ground;
  // The step and horizon (seconds, or dimensionless for a two-block spec), the scheme, the
  // history engine. A building's scheme is implicit or implicit-damped.
  StructureSolverOptions solver;
  OutputOptions output;
  AccuracyOptions accuracy;
  // Valid but probably unintended choices ("solver.h is coarser than the record's dt"): the
  // command line prints them on stderr as "warning: ..." and the run goes on.
  std::vector<std::string> warnings;
  // Sees every run made from this spec, none if null (not owned): a command's RunWatch
  // estimates each run's time, refuses the clearly unintended, shows progress.
  RunWatch* watch = nullptr;

  bool two_block() const { return two_block_scene; }
};

// A two-block spec's model (SPEC §1), read back from its structure; an InputError for a spec
// whose structure is not the 1 + 1 structure of a model.
Model two_block_model(const RunSpec& spec);
// The two-block solver's options of a two-block spec (solver/simulate.hpp).
SolverOptions two_block_options(const RunSpec& spec);

}  // namespace adjoin
