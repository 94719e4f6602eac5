#pragma once
// The channels of a structure (SPEC §5): what a building run can observe, write and sweep over,
// named as the outputs name them. One table (quantities()) says, for each kind of quantity,
// its name pattern, unit, which element it belongs to, how its peak is found and whether the
// time series carries it; channels(structure) lists the structure's channels from it. The
// peaks in summary.json, the columns of timeseries.csv, the in-structure spectra's signals
// and the error estimate all iterate over this list, so adding a quantity is one row here
// and one case where its value is read (observe/channel_values.hpp).
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

namespace adjoin::structure {

// What a channel's element is.
enum class ChannelScope { floor, storey, building, link, contact };

enum class Quantity {
  displacement,           // floor: x [m]
  absolute_acceleration,  // floor: a_abs [m/s^2]
  drift,                  // storey: x_i - x_{i-1} [m]
  drift_ratio,            // storey: drift / h_i [-] (a building with storey heights only)
  storey_shear,           // storey: spring + devices [N]
  base_shear,             // building: -sum m_i a_i,abs [N]
  link_force,             // link [N]
  link_stroke,            // link: x_A,i - x_B,j [m]
  contact_gap,            // contact pair: gap - s [m] (negative: overlap)
  contact_force,          // contact pair: compressive force [N]
  hysteretic,             // storey: its bilinear law's z [m] (only for a building whose storeys yield)
};

// How the peak of a channel is found from its grid samples. Smooth signals (displacements,
// drifts, strokes, gaps) are refined by the parabola through the three samples around the
// largest; signals with kinks where a damper switches or saturates (accelerations, shears,
// link forces) keep their largest sample. A contact pair's gap and force have no peak here:
// its report gives the smallest gap and the impacts' located peak forces instead.
enum class PeakRule { refined, sampled, none };

struct QuantityInfo {
  Quantity quantity;
  ChannelScope scope;
  const char* stem;    // the name's stem: A.<stem><i><suffix>, link<k>.<stem>
  const char* suffix;  // "_abs" for absolute accelerations
  const char* unit;
  PeakRule peak;
  bool timeseries;     // a column of timeseries.csv
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
