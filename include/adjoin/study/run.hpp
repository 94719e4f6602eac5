#pragma once
// One run of a scene: simulate() with the observers the scene's [output] asks for, and
// everything a single run reports. Studies (convergence, sweeps) are loops over run_scene().
//
//     RunReport report = run_scene(scene, &csv_writer);   // extra observer optional
//
// Parts the scene did not ask for are neither computed nor kept (their optionals are empty).
// Values are dimensionless, except the spectra, which are in the scene's units (periods in
// its time unit, SD in its length unit, SV and PSV in length per time, SA and PSA in g);
// io/summary.hpp converts the rest.
#include <optional>
#include <string>
#include <vector>

#include "adjoin/study/run_spec.hpp"
#include "adjoin/observe/energy.hpp"
#include "adjoin/observe/peaks.hpp"
#include "adjoin/observe/phases.hpp"
#include "adjoin/observe/pounding.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/solver/simulate.hpp"

namespace adjoin {

struct SignalSpectrum {
  std::string signal;  // "ground", "block1", "block2"
  ResponseSpectrum spectrum;
};

struct RunReport {
  SolverSummary solver;
  State final;
  std::vector<PhaseInterval> phases;  // empty if output.phases = false
  Peaks peaks;                        // all zero if output.peaks = false
  std::optional<PoundingMargin> pounding;
  // The model has no contact law and the gap closed: the first contact time, from which every
  // value of the run is outside the model (set [model.contact]). Kept even when the pounding
  // margin was not asked for (output.pounding = false).
  std::optional<double> outside_model_from;
  std::optional<EnergyBalance> energy;
  std::vector<SignalSpectrum> spectra;
};

// `extra` (optional, not owned) also sees every grid point, e.g. a time-series writer.
RunReport run_scene(const RunSpec& scene, Observer* extra = nullptr);

}  // namespace adjoin
