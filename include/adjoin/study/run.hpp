#pragma once
// One run of a scene: simulate() with the standard observers attached, and everything a
// single run reports. Studies (convergence, sweeps) are loops over run_scene().
//
//     RunReport report = run_scene(scene, &csv_writer);   // extra observer optional
//
// All values in RunReport are dimensionless; io/summary.hpp converts them to the scene's units.
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/observe/energy.hpp"
#include "adjoin/observe/peaks.hpp"
#include "adjoin/observe/phases.hpp"
#include "adjoin/observe/pounding.hpp"
#include "adjoin/solver/simulate.hpp"

namespace adjoin {

struct RunReport {
  SolverSummary solver;
  std::vector<PhaseInterval> phases;
  Peaks peaks;
  State final;
  PoundingMargin pounding;
  EnergyBalance energy;
};

// `extra` (optional, not owned) also sees every grid point, e.g. a time-series writer.
RunReport run_scene(const Scene& scene, Observer* extra = nullptr);

}  // namespace adjoin
