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
//
// Contact pairs (SPEC §6): each pair's gap on the grid and, with a contact law, its impacts as
// the solver reports them (StructureObserver::impact), their totals and the energy the
// contact dissipated. A pair with model none lets the floors pass through each other: from
// its first contact on every value of the run is outside the model (unmodelled_from).
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/study/run_spec.hpp"
#include "adjoin/structure/state.hpp"
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
  structure::ContactModel model = structure::ContactModel::none;
  double min_gap = 0.0, t_min_gap = 0.0;  // on the grid [m, s]
  // Whether the floors touched: a reported impact, or a grid gap <= 0; and when (the first
  // impact's located start, else the first grid point with gap <= 0) [s].
  bool contact = false;
  double t_first_contact = 0.0;
  // With a contact law: the impacts in the order they started, and their totals.
  std::vector<Impact> impact_list;
  std::size_t impacts = 0;
  double force_max = 0.0, t_force_max = 0.0;  // the largest impact force_max [N] and its time [s]
  double penetration_max = 0.0;               // [m]
  double impulse = 0.0, impulse_max = 0.0;    // all impacts' impulses summed, the largest [N s]
  double work = 0.0;        // work of the floors on the contact at t_end (stored + dissipated) [J]
  double dissipated = 0.0;  // the part dissipated [J]
  // Model none and the floors overlapped: every value from this time on is outside the model
  // (t_first_contact); NaN otherwise.
  double unmodelled_from = std::numeric_limits<double>::quiet_NaN();
  bool outside_model() const { return !std::isnan(unmodelled_from); }
};

// The energy balance of a building run [J], integrated from the grid's powers (trapezoidal):
// for each building the input a_g 1'M v, the kinetic energy 1/2 v'M v, the work dissipated by
// its inherent damping v'C v and the work done on each storey (springs' strain energy and the
// devices' stored and dissipated work together); each link's work; each contact pair's work
// (its stored energy plus what it dissipated, exact from the solver); and the residual
// input - kinetic - inherent - storeys - links - contacts, which tends to 0 at the scheme's order.
struct BuildingEnergy {
  struct Part {
    double input = 0.0, kinetic = 0.0, inherent = 0.0;
    std::vector<double> storeys;
  };
  std::vector<Part> buildings;  // A, then B
  std::vector<double> links;
  std::vector<double> contacts;
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
  // The earliest unmodelled_from of the contact pairs (NaN: every value is inside the model).
  double unmodelled_from() const;
  // In-structure spectra ([output.spectra]): of "ground" and of floors' absolute accelerations
  // (X.aN_abs), from their histories at the solver's step h; SI units.
  std::vector<SignalSpectrum> spectra;
};

// Refuses (InputError, exit 2) before it starts a run that could hold the step and horizon it
// needs only by using more memory than the machine can give: every run's rule
// (solver/simulate.hpp memory_problem). run_building checks each run (and so `run`, `joint`,
// `converge` and building sweeps); commands call it first to refuse before any work.
void check_building_memory(const BuildingRunSpec& scene);
// What a building run holds [bytes], known before it starts: each Zener element's history
// (weights and past values, 16 bytes a step with the direct engine, 64 with fft: the two-block
// rods' figures), the quadrature weights of each order (8 bytes a step), the histories kept
// for in-run spectra (8 bytes a step each) and the step's dense matrices.
double estimated_building_run_bytes(const BuildingRunSpec& scene);

BuildingReport run_building(const BuildingRunSpec& scene, StructureObserver* extra = nullptr);

// simulate_structure for a run of `scene` (with `s`, the scene's structure or an edit of it of
// the same size): its memory checked first (check_building_memory) and its steps shown to the
// scene's watch. Every building run goes through here.
StructureRunSummary simulate_building(const BuildingRunSpec& scene, const structure::Structure& s, StructureObserver& observer);

}  // namespace adjoin
