#pragma once
// What one run reports (study/run.hpp), whatever the scene. Values are in the spec's solver
// units: SI for a building, dimensionless for a two-block spec (io/summary.hpp converts with
// the spec's scales); spectra are in the scene's units.
//
//  - every run: the solver's summary, the in-structure spectra asked for;
//  - a building run: the modes, the peak of every channel (structure/channels.hpp), each link's
//    extremes and switches, each contact pair's gap and impacts, the energy balance;
//  - a two-block spec: the same report of its 1 + 1 structure (structure/two_block.hpp), from
//    the two-block observers of that structure (observe/peaks.hpp, phases.hpp, pounding.hpp,
//    energy.hpp: the paper's refinements), plus its phases and last values; io presents it
//    under the names of SPEC §3 (io/two_block_names.hpp).
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/observe/energy.hpp"
#include "adjoin/observe/peaks.hpp"
#include "adjoin/observe/phases.hpp"
#include "adjoin/observe/pounding.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/structure/state.hpp"

namespace adjoin {

struct SignalSpectrum {
  std::string signal;  // "ground" or a floor's X.aN_abs (run_spec.hpp SpectraOutput)
  ResponseSpectrum spectrum;
};

// Channels (SPEC §5): A.x3, A.a3_abs (floor 3's displacement, absolute acceleration),
// A.drift2, A.shear2 (storey 2), A.base_shear, link1.force, link1.stroke; B likewise.
// Peaks (ChannelPeak, observe/peaks.hpp) are the largest samples; those of displacements,
// drifts and strokes are refined by a parabola through the three samples around them
// (accelerations, shears and link forces have kinks where a damper switches or saturates, and
// keep their samples). A two-block run's peaks are refined as observe/peaks.hpp says.

struct LinkReport {
  double force_max = 0.0, stroke_max = 0.0;
  std::size_t switches = 0;              // friction links: phase changes
  std::vector<double> switch_times;      // located instants [s]
  // The work dissipated in the link [J] (trapezoidal in time), whatever its type: a friction
  // link's or a dashpot's is all the work done on it; a spring dissipates nothing (0); a Zener
  // link's is the work done on it less 1/2 F s at the last grid point (what a spring carrying
  // its last force at its last stroke holds: its stored energy once it has relaxed).
  double energy = 0.0;
};

// Contact pairs (SPEC §6): each pair's gap on the grid and, with a contact law, its impacts as
// the solver reports them (StructureObserver::impact), their totals and the energy the
// contact dissipated. A pair with model none lets the floors pass through each other: from
// its first contact on every value of the run is outside the model (unmodelled_from).
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

// Collapse (SPEC §7): a storey's drift ratio passed its building's collapse_drift_ratio and the
// run stopped there, an outcome (exit 0), the capacity event of incremental dynamic analysis.
// The run's outputs end at the grid point that ends the step the crossing was located in.
struct Collapse {
  char building = 'A';
  int storey = 1;
  double t = 0.0;            // the located crossing [s], inside the run's last step
  double drift_ratio = 0.0;  // the limit crossed, with the drift's sign
};

// A channel's value at the run's last grid point (`residual` in summary.json: the drifts and
// drift ratios at t_end, or at the collapse).
struct ChannelValue {
  std::string channel;
  double value = 0.0;
};

// A yielding storey (SPEC §7, summary.json `yield`): whether and when it first yielded (the
// located instant; NaN if never), its excursions (elastic -> plastic transitions), its largest
// ductility |d|max / u_y and the work its law dissipated [J].
struct StoreyYield {
  int storey = 1;
  bool yielded = false;
  double t_first = std::numeric_limits<double>::quiet_NaN();
  int excursions = 0;
  double ductility_max = 0.0;
  double plastic_work = 0.0;
};
struct BuildingYield {
  char building = 'A';
  std::vector<StoreyYield> storeys;
};

// An isolated base (SPEC §7, summary.json `base`): the peak of X.x0 and its value at t_end,
// the slider's phase changes and the work it dissipated [J].
struct BaseReport {
  char building = 'A';
  double max_abs = 0.0, t = 0.0, residual = 0.0;
  std::size_t switches = 0;
  double energy = 0.0;
};

struct Report {
  SolverSummary solver;
  // The structure's channels, links, contact pairs and energy (a two-block run's: its 1 + 1
  // structure's peaks as observe/peaks.hpp names them, its one contact pair, and its energy
  // when output.energy asks).
  std::vector<structure::Modes> modes;   // A, then B
  std::optional<structure::CoupledModes> coupled;
  std::vector<ChannelPeak> peaks;
  std::vector<LinkReport> links;
  std::vector<ContactReport> contacts;
  BuildingEnergy energy;
  std::optional<Collapse> collapse;  // the run stopped at a collapse (SPEC §7)
  std::vector<ChannelValue> residual;  // each drift and drift-ratio channel at the last grid point
  std::vector<BuildingYield> yield;  // the buildings whose storeys have a bilinear law
  std::vector<BaseReport> bases;     // the isolated buildings, A's first
  // In-structure spectra ([output.spectra]).
  std::vector<SignalSpectrum> spectra;
  // A two-block run (the 1 + 1 structure on the two-block solver): the friction link's phases
  // (without a link: the sign of the floors' relative velocity), with located switches, and
  // the last grid point's values (A.x1, B.x1, A.v1, B.v1, A.shear1, B.shear1, link1.force) and
  // phase. Empty when not asked for (output.phases) or for a building run.
  std::vector<PhaseInterval> phases;
  std::vector<ChannelValue> last;
  Phase last_phase = Phase::stick;
  double t_last = 0.0;

  // The peak of `channel`, or a zero peak if the report has none by that name.
  Peak peak(const std::string& channel) const;
  // The value of `channel` in `last`, 0 if none.
  double last_value(const std::string& channel) const;
  // The work on link k (0-based), 0 if the run has no such link.
  double link_energy(std::size_t k = 0) const { return k < energy.links.size() ? energy.links[k] : 0.0; }

  // The earliest time from which the run's values are outside its model (a contact pair
  // without a law whose floors met), NaN if none.
  double unmodelled_from() const;
};

}  // namespace adjoin
