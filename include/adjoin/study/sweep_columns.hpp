#pragma once
// A sweep's result columns (study/sweep.hpp): between `units` and `pga_g`, the cells a run's
// Report gives, from one registry per presentation of the base scene:
//
//  - a structure (SPEC §5, any scene not written with the two-block keys): building_sweep_channels(),
//    column templates ("X.drift_max", "linkN.stroke_max") expanded over the base structure's
//    buildings (A, then B), links and contacts, in scene order, then the whole's;
//  - a base io presents under names of its own (a scene written with the two-block keys): the
//    table its SweepScenes gives (SweepScenes::presented_channels; io/two_block_names.hpp).
//
// A column is one table row: its name, type, unit and meaning (docs/reference/outputs.md and
// --help) and how it is read from the Report.
//
// A structure's runs must keep the base's buildings, links and contacts, or drop a whole group
// (B, every link or every contact: `unset = ["link"]`), whose cells they then leave empty; a
// run that adds or removes some of them (2 links -> 1) is refused with an InputError naming the
// sweep file, the line of the edit and the run, since its columns would describe other elements.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "adjoin/study/run.hpp"
#include "adjoin/study/run_spec.hpp"
#include "adjoin/study/sweep.hpp"

namespace adjoin {

enum class ChannelScope { building, link, contact, whole };

// One column template.
struct SweepChannel {
  ChannelScope scope;
  std::string name;     // "X.roof_max" (X: A or B), "linkN.force_max" (N from 1), "energy_input"
  ColumnType type;      // number, integer (a count, a storey) or boolean
  std::string unit;     // "m", "N", "m/s^2", "J", "s", or "" (a ratio, a count; two-block: the scene's units)
  std::string meaning;  // for docs/reference/outputs.md and --help
  // The value for element k (building 0 = A, 1 = B; link or contact k counted from 0; 0 for
  // `whole`), in the scene's units. Counts and booleans as 0/1...; NaN for "no value" (a share
  // of zero input energy; a two-block run's impact cells without a contact law): an empty cell.
  std::function<double(const RunSpec&, const Report&, std::size_t k)> value;
  bool may_be_empty = false;  // (whole scope) an integer or boolean cell a successful run may leave empty
};

// The registries, in column order within each scope.
const std::vector<SweepChannel>& building_sweep_channels();

// How many of each group a table has columns for.
struct ChannelCounts {
  std::size_t buildings = 1, links = 0, contacts = 0;
};
ChannelCounts channel_counts(const structure::Structure& s);

// The channel columns of a structure: A's, B's, each link's, each contact's, then the whole's
// (`counts`: for that many links and contacts, e.g. more than the base has).
std::vector<SweepColumn> building_channel_columns(const structure::Structure& s);
std::vector<SweepColumn> building_channel_columns(const ChannelCounts& counts);

// The cells of those columns for a run of `scene` (the run's own structure) with its report;
// groups the base has and the run does not are empty (the run's link N fills the linkN columns).
std::vector<std::string> building_channel_cells(const structure::Structure& base, const RunSpec& scene,
                                                const Report& report);
std::vector<std::string> building_channel_cells(const ChannelCounts& counts, const RunSpec& scene, const Report& report);

// The columns between `units` and `pga_g` of a sweep, and a run's cells in them.
std::vector<SweepColumn> channel_columns(const SweepSpec& spec);
std::vector<std::string> channel_cells(const SweepSpec& spec, const RunSpec& scene, const Report& report);

// Sets spec.base_structure, spec.link_columns, spec.contact_columns and spec.channel_columns
// from the base scene's structure and the sweep's edits (the sweep file's reader calls it for
// a structure's base once it has checked the base scene as `adjoin run` would). The link
// columns are for the base's links, or for link.N where an edit sets link.N.KEY with N beyond
// them (adding a damper); the same for contacts.
void prepare_building_sweep(SweepSpec& spec, const structure::Structure& base);

// Refuses a structure run whose groups do not fit the table's columns: building B kept or
// removed, links and contacts at most the columns' count, and none renumbered (an unset of
// link.1 that keeps link.2 would put the base's link 2 in the link1 columns).
void check_groups(const SweepSpec& spec, std::size_t index, const structure::Structure& run);

}  // namespace adjoin
