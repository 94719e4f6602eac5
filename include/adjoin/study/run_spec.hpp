#pragma once
// What a run is, typed and free of any file format (SPEC §4): the structure, the scales between
// the solver's dimensionless numbers and the user's units, the ground, the solver's options and
// what the run computes and writes. io/ reads scene files into these (io/scene.hpp,
// io/building_scene.hpp); study/ runs them (study/run.hpp, study/building_run.hpp) and sweeps
// edit them (study/sweep.hpp).
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
  // output.every: keep every n-th grid point in the CSV files; 0: not given, the run's rule
  // (1 for two-block runs; building runs with a chosen step: io/building_files.hpp).
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

struct RunSpec {
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
  // Sees every run made from this spec, none if null (not owned): a command's RunWatch
  // (study/run_watch.hpp).
  Observer* watch = nullptr;
};

// A building scene's run (SPEC §5): its structure, and its ground, solver and output sections
// (the two-block keys, read by the same code), with the step and horizon chosen when not given
// (the rules are said in `h_rule`, `t_end_rule`).
struct BuildingRunSpec {
  std::string name;
  std::filesystem::path file;
  structure::Structure structure;
  RunSpec base;  // ground (a_g in g, time in s), output; its model is a unit placeholder
  StructureSolverOptions solver;
  std::string h_rule, t_end_rule;
  std::vector<std::string> warnings;
  // Sees every run made from this spec, none if null (not owned): a command's RunWatch
  // (study/run_watch.hpp) estimates each run's time, refuses the clearly unintended, shows
  // progress.
  StructureObserver* watch = nullptr;
};

}  // namespace adjoin
