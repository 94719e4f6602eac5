#pragma once
// Sweeps whose base is a building scene (SPEC §5). A run is the base scene with the run's
// edits (spec.scenes, io's), exactly `adjoin run BASE --set KEY=VALUE ... --unset KEY ...`
// (structure keys by dotted path: building.A.period, link.1.slip_ratio,
// building.A.device.2.c, contact.1.gap; and the ground, solver and output keys), then
// run() without writing files, plus the motion's intensity measures (pga_g, sa_T).
//
// Columns. They are generated from one registry, building_sweep_channels(): each entry is a
// column template ("X.drift_max", "linkN.stroke_max"), its type, unit and meaning, and how it
// is read from the Report. The base structure decides the columns: one set per
// building present (A, then B), per link and per contact, in scene order. A run's structure
// must keep the base's buildings, links and contacts, or drop a whole group (B, every link or
// every contact: `unset = ["link"]`), whose cells it then leaves empty; a run that adds or
// removes some of them (2 links -> 1) is refused with an InputError naming the sweep file, the
// line of the edit and the run, since its columns would describe other elements.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "adjoin/study/run_spec.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/sweep.hpp"

namespace adjoin {

enum class ChannelScope { building, link, contact, whole };

// One column template of a building sweep.
struct SweepChannel {
  ChannelScope scope;
  std::string name;     // "X.roof_max" (X: A or B), "linkN.force_max" (N from 1), "energy_input"
  ColumnType type;      // number, integer (a count, a storey) or boolean
  std::string unit;     // "m", "N", "m/s^2", "J", "s", or "" (a ratio, a count)
  std::string meaning;  // for docs/reference/outputs.md and --help
  // The value for element k (building 0 = A, 1 = B; link or contact k counted from 0; 0 for
  // `whole`). Counts and booleans as 0/1...; NaN for "no value" (a share of zero input energy).
  std::function<double(const RunSpec&, const Report&, std::size_t k)> value;
};

// The registry, in column order within each scope.
const std::vector<SweepChannel>& building_sweep_channels();

// The channel columns of a structure: A's, B's, each link's, each contact's, then the whole's.
std::vector<SweepColumn> building_channel_columns(const structure::Structure& s);

// The cells of those columns for a run of `scene` (the run's own structure) with its report;
// groups the base has and the run does not are empty.
std::vector<std::string> building_channel_cells(const structure::Structure& base, const RunSpec& scene,
                                                const Report& report);

// Sets spec.base_structure and spec.channel_columns from the base scene's structure (the sweep
// file's reader calls it once it has checked the base scene as `adjoin run` would).
void prepare_building_sweep(SweepSpec& spec, const structure::Structure& base);

// The building scene of run `index` (spec.scenes; InputError prefixed with the sweep file, the
// line of the edit that caused it and the run), its groups checked against the base's.
RunSpec building_sweep_scene(const SweepSpec& spec, std::size_t index);

// One run (InputError propagates; NumericalError is caught into row.error).
SweepRow run_building_sweep_point(const SweepSpec& spec, std::size_t index);

}  // namespace adjoin
