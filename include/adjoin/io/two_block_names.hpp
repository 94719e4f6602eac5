#pragma once
// The presenter of a two-block run (SPEC §4): its report is the 1 + 1 structure's (study/report.hpp,
// by channel: A.x1, link1.force, ...), shown under SPEC §3's frozen names (x1, q, rod1, ...) in
// summary.json, the terminal report, timeseries.csv and energy.csv. The names of the values
// and their channels are structure/two_block.hpp's two_block_channel; their units are here.
#include <span>
#include <string>

#include "adjoin/core/units.hpp"
#include "adjoin/observe/energy.hpp"
#include "adjoin/study/report.hpp"
#include "adjoin/study/sweep_columns.hpp"

namespace adjoin {

// A frozen name and the scale that takes its value to the scene's units.
struct FrozenName {
  const char* name;
  double Scales::*unit;
};

// summary.json's "peaks", in its order: x1, x2, f1, f2, q, v1, v2, a1_abs, a2_abs, ag, drift.
std::span<const FrozenName> two_block_peak_names();
// summary.json's "final" after t: x1, x2, v1, v2, f1, f2, q.
std::span<const FrozenName> two_block_final_names();

// The energy balance under its frozen names (per unit m1; the scene's scale gives joules):
// rod1 and rod2 are the work on A's and B's storey, friction the work on the friction link,
// contact the contact pair's work and contact_dissipated its dissipated part, base_friction
// the base friction sliders' work (observe/energy.hpp).
struct TwoBlockEnergy {
  double input = 0.0, kinetic = 0.0, rod1 = 0.0, rod2 = 0.0, friction = 0.0;
  double contact = 0.0, contact_dissipated = 0.0, base_friction = 0.0, residual = 0.0;
};
TwoBlockEnergy two_block_energy(const EnergyTerms& terms);
TwoBlockEnergy two_block_energy(const Report& report);

// A convergence quantity of a two-block run (study/convergence.hpp: "peak A.x1", "t peak
// link1.stroke", "final link1.force") under SPEC §3's names ("peak x1", "t peak stroke",
// "final q"); any other name as it is.
std::string two_block_quantity_name(const std::string& name);

// The in-structure spectra's signals of a two-block scene (SPEC §3: "block1", "block2") and the
// 1 + 1 structure's floors they are (A.a1_abs, B.a1_abs); "ground" and any other name as it is.
std::string two_block_signal_channel(const std::string& signal);
std::string two_block_signal_name(const std::string& channel);
std::vector<SignalSpectrum> two_block_signal_names(std::vector<SignalSpectrum> spectra);

// A two-block sweep's columns between `units` and `pga_g` (SPEC §3: x1, x2, drift, f1, f2,
// a1_abs, a2_abs, min_gap, contact, outside_model, contact.impacts, contact.force_max,
// contact.penetration_max, energy_input, share_rod1, share_rod2, share_friction,
// share_residual, stick_intervals, slip_intervals, switches), one row each, in the scene's
// units (io/two_block_sweep_columns.cpp).
const std::vector<SweepChannel>& two_block_sweep_channels();

}  // namespace adjoin
