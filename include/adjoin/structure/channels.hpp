#pragma once
// The channels of a structure (SPEC §5): what a building run can observe, write and sweep over,
// named as the outputs name them. One table (quantities()) says, for each kind of quantity,
// its name pattern, unit, which element it belongs to, how its peak is found and whether the
// time series carries it; channels(structure) lists the structure's channels from it. The
// peaks in summary.json, the columns of timeseries.csv, the in-structure spectra's signals
// and the error estimate all iterate over this list, so adding a quantity is one row of
// ADJOIN_QUANTITIES (below): the row says where its value is in the state.
//
// Names: A.x3 (floor 3's displacement relative to the ground), A.a3_abs (its absolute
// acceleration), A.drift2 (storey 2's drift x_2 - x_1; A.drift_ratio2 = A.drift2 / h_2 when the
// building has storey heights), A.shear2 (storey 2's shear: spring +
// devices), A.base_shear (-sum m_i a_i,abs); link1.force, link1.stroke (x_A,i - x_B,j);
// contact1.gap, contact1.force; A.hyst2 (storey 2's hysteretic variable z, SPEC §7, when A's
// storeys yield); A.x0 (an isolated base's displacement relative to the ground, SPEC §7). B
// likewise; elements are numbered from 1.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "adjoin/structure/building.hpp"
#include "adjoin/structure/state.hpp"

namespace adjoin::structure {

// What a channel's element is.
enum class ChannelScope { floor, storey, building, link, contact };

// How the peak of a channel is found from its grid samples. Smooth signals (displacements,
// drifts, strokes, gaps) are refined by the parabola through the three samples around the
// largest; signals with kinks where a damper switches or saturates (accelerations, shears,
// link forces) keep their largest sample. A contact pair's gap and force have no peak here:
// its report gives the smallest gap and the impacts' located peak forces instead.
enum class PeakRule { refined, sampled, none };

struct Channel;

// Where a quantity's value is in the state (observe/channel_values.hpp reads it so, in one
// place): `entry`, one entry of one of the state's vectors (a floor's or storey's: the
// channel's dof; a link's or contact pair's: its index); `drift`, a storey's floor's entry less
// the floor below's (storey 1: the isolated base's, or 0), `drift_over_height` that over the
// storey's height; `function`, computed by `value` (a function of channels.cpp).
struct StateRead {
  enum Form { entry, drift, drift_over_height, function };
  Form form = function;
  const Eigen::VectorXd StructureState::*vector = nullptr;
  double (*value)(const Structure&, const Channel&, const StructureState&) = nullptr;
};
constexpr StateRead entry(const Eigen::VectorXd StructureState::*v) { return {StateRead::entry, v, nullptr}; }
constexpr StateRead drift(const Eigen::VectorXd StructureState::*v) { return {StateRead::drift, v, nullptr}; }
constexpr StateRead drift_over_height(const Eigen::VectorXd StructureState::*v) { return {StateRead::drift_over_height, v, nullptr}; }
constexpr StateRead computed(double (*f)(const Structure&, const Channel&, const StructureState&)) { return {StateRead::function, nullptr, f}; }

// Which buildings have a floor or storey quantity's channels.
inline bool every_building(const Building&) { return true; }
inline bool with_heights(const Building& b) { return b.has_heights(); }
inline bool yielding(const Building& b) { return b.hysteresis.model != HysteresisModel::elastic; }

// Every quantity, one row each, in the order a building's, a link's or a contact pair's
// channels are listed: its value (Quantity::<value>), its element, the name's stem and suffix
// (A.<stem><i><suffix>, link<k>.<stem>), unit, peak rule, whether timeseries.csv carries it,
// where its value is read (StateRead; a `computed` one's function is in channels.cpp), which
// buildings have it, a plot's label and what it is (docs/reference/channels.md). A new
// quantity is its row here: the peaks in summary.json, timeseries.csv, the observers, the
// channel recorder, the plots and the reference follow the table.
#define ADJOIN_QUANTITIES(ROW)                                                                                      \
  ROW(displacement, floor, "x", "", "m", refined, true, entry(&StructureState::x), every_building, "displacement",   \
      "floor displacement relative to the ground")                                                                   \
  ROW(drift, storey, "drift", "", "m", refined, false, drift(&StructureState::x), every_building, "drift",           \
      "storey drift x_i - x_(i-1)")                                                                                  \
  ROW(drift_ratio, storey, "drift_ratio", "", "-", refined, false, drift_over_height(&StructureState::x), with_heights, \
      "drift ratio", "storey drift ratio (x_i - x_(i-1)) / h_i (buildings with storey heights)")                   \
  ROW(absolute_acceleration, floor, "a", "_abs", "m/s^2", sampled, true, entry(&StructureState::a_abs), every_building, \
      "absolute acceleration", "floor absolute acceleration")                                                        \
  ROW(storey_shear, storey, "shear", "", "N", sampled, false, entry(&StructureState::storey_force), every_building,  \
      "shear", "storey shear (spring and devices)")                                                                  \
  ROW(base_shear, building, "base_shear", "", "N", sampled, false, computed(base_shear_value), every_building,       \
      "base shear", "base shear -sum m_i a_i,abs")                                                                   \
  ROW(link_force, link, "force", "", "N", sampled, true, entry(&StructureState::link_force), every_building, "force", \
      "link force (-q on A's floor, +q on B's)")                                                                     \
  ROW(link_stroke, link, "stroke", "", "m", refined, true, entry(&StructureState::link_stroke), every_building,      \
      "stroke", "link stroke x_A,i - x_B,j")                                                                        \
  ROW(contact_gap, contact, "gap", "", "m", none, true, computed(contact_gap_value), every_building, "gap",          \
      "contact pair's gap (negative: overlap)")                                                                      \
  ROW(contact_force, contact, "force", "", "N", none, true, computed(contact_force_value), every_building, "force",  \
      "contact pair's compressive force")                                                                            \
  ROW(hysteretic, storey, "hyst", "", "m", sampled, false, computed(hysteretic_value), yielding, "hysteretic variable", \
      "storey's hysteretic variable z of a yielding storey (bilinear: at most F_y / k in size; Bouc-Wen: its z)")    \
  ROW(link_velocity, link, "velocity", "", "m/s", sampled, false, entry(&StructureState::link_velocity), every_building, \
      "velocity", "link velocity, the stroke's rate (a damper's design speed)")                                     \
  /* a new quantity: its row above this line */

#define ADJOIN_QUANTITY_VALUE(value, ...) value,
enum class Quantity { ADJOIN_QUANTITIES(ADJOIN_QUANTITY_VALUE) };
#undef ADJOIN_QUANTITY_VALUE

struct QuantityInfo {
  Quantity quantity;
  ChannelScope scope;
  const char* stem;    // the name's stem: A.<stem><i><suffix>, link<k>.<stem>
  const char* suffix;  // "_abs" for absolute accelerations
  const char* unit;
  PeakRule peak;
  bool timeseries;     // a column of timeseries.csv
  StateRead read;
  bool (*applies)(const Building&);  // a floor or storey quantity: whether the building has it
  const char* label;                 // a plot's axis: "<label>, floor 3, building A [unit]"
  const char* meaning;
};

// Every quantity, in the order a building's, a link's or a contact pair's channels are listed.
std::span<const QuantityInfo> quantities();
const QuantityInfo& info(Quantity q);

struct Channel {
  std::string name;
  Quantity quantity;
  char building = 'A';  // floors, storeys, buildings: 'A' or 'B'
  int index = 1;        // floor or storey (1-based), link or contact pair (1-based)
  int dof = -1;         // floors and storeys: the floor's index in the stacked state
};

// The structure's channels: A's (each quantity of building scope in the table's order, each
// over its floors or storeys), then B's, then each link's, then each contact pair's.
std::vector<Channel> channels(const Structure& s);

// The channel called `name` ("A.a5_abs", "link1.force"), if the structure has it.
std::optional<Channel> find_channel(const Structure& s, const std::string& name);

}  // namespace adjoin::structure
