#pragma once
// What one run reports (study/run.hpp), whatever the scene. Values are in the spec's solver
// units: SI for a building, dimensionless for a two-block spec (io/summary.hpp converts with
// the spec's scales); spectra are in the scene's units.
//
//  - every run: the solver's summary, the in-structure spectra asked for;
//  - a building run (and a two-block run asked for its channels): the modes, the peak of every
//    channel (structure/channels.hpp), each link's extremes and switches, each contact pair's
//    gap and impacts, the energy balance;
//  - a two-block spec: the paper's values (SPEC §3), refined by its own observers
//    (observe/peaks.hpp, phases.hpp, pounding.hpp, energy.hpp).
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
  std::string signal;  // "ground", a floor's X.aN_abs, or a two-block scene's "block1", "block2"
  ResponseSpectrum spectrum;
};

// Channels (SPEC §5): A.x3, A.a3_abs (floor 3's displacement, absolute acceleration),
// A.drift2, A.shear2 (storey 2), A.base_shear, link1.force, link1.stroke; B likewise.
// Peaks are the largest samples; those of displacements, drifts and strokes are refined by a
// parabola through the three samples around them (accelerations, shears and link forces have
// kinks where a damper switches or saturates, and keep their samples).
struct ChannelPeak {
  std::string channel;
  Peak peak;
};

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

// The energy balance of a run [J], integrated from the grid's powers (trapezoidal): for each
// building the input a_g 1'M v, the kinetic energy 1/2 v'M v, the work dissipated by its
// inherent damping v'C v and the work done on each storey (springs' strain energy and the
// devices' stored and dissipated work together); each link's work; each contact pair's work
// (its stored energy plus what it dissipated, exact from the solver); and the residual
// input - kinetic - inherent - storeys - links - contacts, which tends to 0 at the scheme's order.
struct BuildingEnergy {
  struct Part {
    double input = 0.0, kinetic = 0.0, inherent = 0.0;
    std::vector<double> storeys;
    // Bilinear storeys (SPEC §7): the plastic work of each storey's law (a part of its storey's
    // work, dissipated); empty for an elastic building.
    std::vector<double> hysteretic;
    // An isolated base (SPEC §7): the work done on its isolator, the slider's dissipated work
    // plus a friction pendulum's stored energy (0 without a base), and the slider's part.
    double isolator = 0.0, isolator_dissipated = 0.0;
  };
  std::vector<Part> buildings;  // A, then B
  std::vector<double> links;
  std::vector<double> contacts;
  double input = 0.0, residual = 0.0;
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

// The paper's values of a two-block run (SPEC §3), dimensionless. Parts the scene did not ask
// for ([output]) are neither computed nor kept (their optionals are empty).
struct TwoBlockReport {
  State final;
  std::vector<PhaseInterval> phases;  // empty if output.phases = false
  Peaks peaks;                        // all zero if output.peaks = false
  std::optional<PoundingMargin> pounding;
  // The model has no contact law and the gap closed: the first contact time, from which every
  // value of the run is outside the model (set [model.contact]). Kept even when the pounding
  // margin was not asked for (output.pounding = false).
  std::optional<double> outside_model_from;
  std::optional<EnergyBalance> energy;
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
  // The structure's channels (a building run; a two-block run when output.channels is set).
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
  // A two-block spec's values under the paper's names.
  std::optional<TwoBlockReport> two_block;

  // The earliest time from which the run's values are outside its model (a contact pair
  // without a law whose floors met), NaN if none.
  double unmodelled_from() const;
};

}  // namespace adjoin
