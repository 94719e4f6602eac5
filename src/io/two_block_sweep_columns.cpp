// The sweep columns of a scene written with the two-block keys (io/two_block_names.hpp): its
// 1 + 1 structure's report under SPEC §3's names.
#include <cstddef>
#include <functional>
#include <limits>
#include <utility>

#include "adjoin/io/two_block_names.hpp"

namespace adjoin {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

// A scene written with the two-block keys: its 1 + 1 structure's values (the channels of
// structure/two_block.hpp: A and B's floor 1 and storey 1, link 1, contact pair 1) under SPEC
// §3's names, one row each, in the scene's units. A two-block sweep's run asks for every part of
// the report (study/sweep.cpp run_sweep_point).
const std::vector<SweepChannel>& two_block_sweep_channels() {
  using T = ColumnType;
  using Value = std::function<double(const Report&, const Scales&)>;
  const auto column = [](const char* name, T type, const char* meaning, Value v, bool may_be_empty = false) {
    return SweepChannel{ChannelScope::whole, name, type, "", meaning,
                        [v = std::move(v)](const RunSpec& s, const Report& r, std::size_t) { return v(r, s.scales); },
                        may_be_empty};
  };
  // A channel's peak, in the scene's unit.
  const auto peak = [column](const char* name, const char* channel, double Scales::*unit, const char* meaning) {
    return column(name, T::number, meaning, [channel, unit](const Report& r, const Scales& k) { return r.peak(channel).max_abs * k.*unit; });
  };
  const auto pair = [](const Report& r) -> const ContactReport& { return r.contacts.at(0); };
  // A contact law's results; without one the cells stay empty.
  const auto with_law = [pair](const Report& r, double v) { return pair(r).model != structure::ContactModel::none ? v : kNaN; };
  // A share of the input energy (NaN for zero input).
  const auto of_input = [](const Report& r, double work) { return work / (r.energy.input != 0.0 ? r.energy.input : kNaN); };
  const auto storey = [](const Report& r, std::size_t building) { return r.energy.buildings.at(building).storeys.at(0); };
  const auto intervals = [](const Report& r, bool stick) {
    std::size_t n = 0;
    for (const auto& interval : r.phases) n += (interval.state == Phase::stick) == stick ? 1 : 0;
    return static_cast<double>(n);
  };
  static const std::vector<SweepChannel> channels = {
      peak("x1", "A.x1", &Scales::length, "peak |x1| (block 1's displacement)"),
      peak("x2", "B.x1", &Scales::length, "peak |x2|"),
      peak("drift", "link1.stroke", &Scales::length, "peak |x1 - x2| (the damper's stroke)"),
      peak("f1", "A.shear1", &Scales::force, "peak |f1| (rod 1's force)"),
      peak("f2", "B.shear1", &Scales::force, "peak |f2|"),
      peak("a1_abs", "A.a1_abs", &Scales::acceleration, "peak absolute acceleration of block 1"),
      peak("a2_abs", "B.a1_abs", &Scales::acceleration, "peak absolute acceleration of block 2"),
      column("min_gap", T::number, "the pounding margin", [pair](const Report& r, const Scales& k) { return pair(r).min_gap * k.length; }),
      column("contact", T::boolean, "whether the gap closed", [pair](const Report& r, const Scales&) { return pair(r).contact ? 1.0 : 0.0; }),
      column("outside_model", T::boolean, "no contact law and the gap closed: values after the first contact are outside the model",
             [pair](const Report& r, const Scales&) { return pair(r).outside_model() ? 1.0 : 0.0; }),
      column("contact.impacts", T::integer, "impacts (with a contact law)",
             [with_law, pair](const Report& r, const Scales&) { return with_law(r, static_cast<double>(pair(r).impacts)); }, true),
      column("contact.force_max", T::number, "peak contact force (with a contact law)",
             [with_law, pair](const Report& r, const Scales& k) { return with_law(r, pair(r).force_max * k.force); }),
      column("contact.penetration_max", T::number, "largest penetration (with a contact law)",
             [with_law, pair](const Report& r, const Scales& k) { return with_law(r, pair(r).penetration_max * k.length); }),
      column("energy_input", T::number, "input energy (per unit m1, or J)", [](const Report& r, const Scales& k) { return r.energy.input * k.energy; }),
      column("share_rod1", T::number, "work on rod 1 / input", [of_input, storey](const Report& r, const Scales&) { return of_input(r, storey(r, 0)); }),
      column("share_rod2", T::number, "work on rod 2 / input", [of_input, storey](const Report& r, const Scales&) { return of_input(r, storey(r, 1)); }),
      column("share_friction", T::number, "friction work / input", [of_input](const Report& r, const Scales&) { return of_input(r, r.link_energy(0)); }),
      column("share_residual", T::number, "balance residual / input", [of_input](const Report& r, const Scales&) { return of_input(r, r.energy.residual); }),
      column("stick_intervals", T::integer, "stick phases", [intervals](const Report& r, const Scales&) { return intervals(r, true); }),
      column("slip_intervals", T::integer, "slip phases", [intervals](const Report& r, const Scales&) { return intervals(r, false); }),
      column("switches", T::integer, "phase changes",
             [](const Report& r, const Scales&) { return r.phases.empty() ? 0.0 : static_cast<double>(r.phases.size() - 1); }),
  };
  return channels;
}

}  // namespace adjoin
