#pragma once
// One run of a building scene: the structure's modes, then the time integration with the
// observers of a building run (peaks by channel, links, contact pairs), streamed to `extra`
// too (a time-series writer).
//
// Channels (SPEC §5): A.x3, A.a3_abs (floor 3's displacement, absolute acceleration),
// A.drift2, A.shear2 (storey 2), A.base_shear, link1.force, link1.stroke; B likewise.
// Peaks are the largest samples; those of displacements, drifts and strokes are refined by a
// parabola through the three samples around them (accelerations, shears and link forces have
// kinks where a damper switches or saturates, and keep their samples).
#include <optional>
#include <string>
#include <vector>

#include "adjoin/io/building_scene.hpp"
#include "adjoin/observe/peaks.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {

struct ChannelPeak {
  std::string channel;
  Peak peak;
};

struct LinkReport {
  double force_max = 0.0, stroke_max = 0.0;
  std::size_t switches = 0;              // friction links: phase changes
  std::vector<double> switch_times;      // located instants [s]
  double friction_energy = 0.0;          // friction links: dissipated work [J] (trapezoidal)
};

struct ContactReport {
  double min_gap = 0.0, t_min_gap = 0.0;
  bool contact = false;
  double t_first_contact = 0.0;
};

// The energy balance of a building run [J], integrated from the grid's powers (trapezoidal):
// for each building the input a_g 1'M v, the kinetic energy 1/2 v'M v, the work dissipated by
// its inherent damping v'C v and the work done on each storey (springs' strain energy and the
// devices' stored and dissipated work together); each link's work; and the residual
// input - kinetic - inherent - storeys - links, which tends to 0 at the scheme's order.
struct BuildingEnergy {
  struct Part {
    double input = 0.0, kinetic = 0.0, inherent = 0.0;
    std::vector<double> storeys;
  };
  std::vector<Part> buildings;  // A, then B
  std::vector<double> links;
  double input = 0.0, residual = 0.0;
};

struct BuildingReport {
  std::vector<structure::Modes> modes;   // A, then B
  std::optional<structure::CoupledModes> coupled;
  StructureRunSummary solver;
  std::vector<ChannelPeak> peaks;
  std::vector<LinkReport> links;
  std::vector<ContactReport> contacts;
  BuildingEnergy energy;
  // In-structure spectra ([output.spectra]): of "ground" and of floors' absolute accelerations
  // (X.aN_abs), from their histories at the solver's step h; SI units.
  std::vector<SignalSpectrum> spectra;
};

BuildingReport run_building(const BuildingScene& scene, StructureObserver* extra = nullptr);

}  // namespace adjoin
