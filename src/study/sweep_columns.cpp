#include "adjoin/study/sweep_columns.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"

namespace adjoin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();


const structure::Building& building(const RunSpec& scene, std::size_t k) {
  return k == 0 ? scene.structure.a : *scene.structure.b;
}

// The peak of channel `name` (0 if the report has none).
double peak(const Report& r, const std::string& name) {
  for (const auto& p : r.peaks)
    if (p.channel == name) return p.peak.max_abs;
  return 0.0;
}

// The largest peak of the channels X.<stem>1 ... X.<stem>n<suffix>, and where (1-based).
std::pair<double, int> largest(const RunSpec& scene, const Report& r, std::size_t k, const std::string& stem,
                               const std::string& suffix = "") {
  const structure::Building& b = building(scene, k);
  double best = 0.0;
  int where = 0;
  for (int i = 1; i <= b.floors(); ++i) {
    const double v = peak(r, b.name + "." + stem + std::to_string(i) + suffix);
    if (where == 0 || v > best) { best = v; where = i; }
  }
  return {best, where};
}

double share(double work, const Report& r) { return r.energy.input != 0.0 ? work / r.energy.input : kNaN; }

std::string expand(const std::string& name, ChannelScope scope, std::size_t k) {
  std::string out = name;
  if (scope == ChannelScope::building) out.replace(0, 1, k == 0 ? "A" : "B");
  if (scope == ChannelScope::link) out.replace(4, 1, std::to_string(k + 1));
  if (scope == ChannelScope::contact) out.replace(7, 1, std::to_string(k + 1));
  return out;
}

// How many elements of `scope` a structure has.
std::size_t count(const structure::Structure& s, ChannelScope scope) {
  switch (scope) {
    case ChannelScope::building: return s.b ? 2 : 1;
    case ChannelScope::link: return s.links.size();
    case ChannelScope::contact: return s.contacts.size();
    case ChannelScope::whole: return 1;
  }
  return 0;
}

// Columns are grouped: A, B, links, contacts, whole; `each` sees (channel, element).
template <class F>
void for_each_column(const structure::Structure& s, F each) {
  const auto& channels = building_sweep_channels();
  auto scope = [&](ChannelScope which, std::size_t k) {
    for (const auto& c : channels)
      if (c.scope == which) each(c, k);
  };
  for (std::size_t k = 0; k < count(s, ChannelScope::building); ++k) scope(ChannelScope::building, k);
  for (std::size_t k = 0; k < s.links.size(); ++k) scope(ChannelScope::link, k);
  for (std::size_t k = 0; k < s.contacts.size(); ++k) scope(ChannelScope::contact, k);
  scope(ChannelScope::whole, 0);
}

// A value as its column's cell; NaN: empty.
std::string cell(ColumnType type, double v) {
  if (std::isnan(v)) return "";
  switch (type) {
    case ColumnType::integer: return std::to_string(static_cast<std::size_t>(v));
    case ColumnType::boolean: return v != 0.0 ? "true" : "false";
    default: return sweep_number_cell(v);
  }
}

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

// The line of the first setting whose edits touch `prefix` (e.g. "link"), or 0.
std::size_t line_of_edit(const std::vector<SweepSetting>& settings, const std::string& prefix) {
  for (const auto& s : settings) {
    for (const auto& [key, value] : s.set)
      if (key == prefix || starts_with(key, prefix + ".")) return s.line;
    for (const auto& key : s.unset)
      if (key == prefix || starts_with(key, prefix + ".")) return s.line;
  }
  return 0;
}

std::string at(const SweepSpec& spec, std::size_t line) {
  return spec.file.string() + (line ? ":" + std::to_string(line) : std::string()) + ": ";
}

}  // namespace

const std::vector<SweepChannel>& building_sweep_channels() {
  using S = ChannelScope;
  using T = ColumnType;
  static const std::vector<SweepChannel> channels = {
      {S::building, "X.T1", T::number, "s", "fundamental period of building X alone (static stiffness; with P-Delta its tangent's, empty if unstable)",
       [](const RunSpec&, const Report& r, std::size_t k) { return std::isfinite(r.modes[k].periods[0]) ? r.modes[k].periods[0] : kNaN; }},
      {S::building, "X.roof_max", T::number, "m", "peak roof displacement relative to the ground (peak of X.xN, N the top floor)",
       [](const RunSpec& s, const Report& r, std::size_t k) {
         const auto& b = building(s, k);
         return peak(r, b.name + ".x" + std::to_string(b.floors()));
       }},
      {S::building, "X.drift_max", T::number, "m", "largest peak interstorey drift over the storeys (of X.drift1 ... X.driftN)",
       [](const RunSpec& s, const Report& r, std::size_t k) { return largest(s, r, k, "drift").first; }},
      {S::building, "X.drift_storey", T::integer, "", "the storey where X.drift_max occurs (1 = ground storey)",
       [](const RunSpec& s, const Report& r, std::size_t k) {
         return static_cast<double>(largest(s, r, k, "drift").second);
       }},
      {S::building, "X.drift_ratio_max", T::number, "", "largest peak storey drift ratio |drift| / h (of X.drift_ratio1 ...; empty without storey heights)",
       [](const RunSpec& s, const Report& r, std::size_t k) {
         return building(s, k).has_heights() ? largest(s, r, k, "drift_ratio").first : kNaN;
       }},
      {S::building, "X.accel_max", T::number, "m/s^2", "largest peak absolute floor acceleration (of X.a1_abs ... X.aN_abs)",
       [](const RunSpec& s, const Report& r, std::size_t k) { return largest(s, r, k, "a", "_abs").first; }},
      {S::building, "X.base_shear_max", T::number, "N", "peak base shear (X.base_shear: the floors' inertia forces summed)",
       [](const RunSpec& s, const Report& r, std::size_t k) { return peak(r, building(s, k).name + ".base_shear"); }},
      {S::building, "X.share_inherent", T::number, "", "work of X's inherent (Rayleigh or modal) damping / total input energy",
       [](const RunSpec&, const Report& r, std::size_t k) { return share(r.energy.buildings[k].inherent, r); }},
      {S::link, "linkN.force_max", T::number, "N", "peak force of link N",
       [](const RunSpec&, const Report& r, std::size_t k) { return r.links[k].force_max; }},
      {S::link, "linkN.stroke_max", T::number, "m", "peak stroke of link N (relative displacement of its two floors)",
       [](const RunSpec&, const Report& r, std::size_t k) { return r.links[k].stroke_max; }},
      {S::link, "linkN.switches", T::integer, "", "stick/slip phase changes of link N (friction; 0 for other link types)",
       [](const RunSpec&, const Report& r, std::size_t k) { return static_cast<double>(r.links[k].switches); }},
      {S::link, "linkN.energy_share", T::number, "", "work done on link N / total input energy (friction: dissipated)",
       [](const RunSpec&, const Report& r, std::size_t k) { return share(r.energy.links[k], r); }},
      {S::contact, "contactN.min_gap", T::number, "m", "smallest gap of contact pair N (negative: the floors overlapped)",
       [](const RunSpec&, const Report& r, std::size_t k) { return r.contacts[k].min_gap; }},
      {S::contact, "contactN.contact", T::boolean, "", "whether the floors of pair N touched (an impact, or the gap reached 0)",
       [](const RunSpec&, const Report& r, std::size_t k) { return r.contacts[k].contact ? 1.0 : 0.0; }},
      {S::contact, "contactN.impacts", T::integer, "", "impacts of pair N (0 without a contact law)",
       [](const RunSpec&, const Report& r, std::size_t k) { return static_cast<double>(r.contacts[k].impacts); }},
      {S::contact, "contactN.force_max", T::number, "N", "largest peak force of pair N's impacts",
       [](const RunSpec&, const Report& r, std::size_t k) { return r.contacts[k].force_max; }},
      {S::contact, "contactN.penetration_max", T::number, "m", "largest penetration of pair N's impacts",
       [](const RunSpec&, const Report& r, std::size_t k) { return r.contacts[k].penetration_max; }},
      {S::contact, "contactN.energy_share", T::number, "", "energy dissipated by pair N's impacts / total input energy",
       [](const RunSpec&, const Report& r, std::size_t k) { return share(r.contacts[k].dissipated, r); }},
      {S::contact, "contactN.outside_model", T::boolean, "",
       "pair N has no contact law and its floors overlapped: the row's values are outside the model",
       [](const RunSpec&, const Report& r, std::size_t k) { return r.contacts[k].outside_model() ? 1.0 : 0.0; }},
      {S::whole, "energy_input", T::number, "J", "input energy of the ground motion, both buildings",
       [](const RunSpec&, const Report& r, std::size_t) { return r.energy.input; }},
      {S::whole, "share_residual", T::number, "", "energy balance residual / input (closes at the scheme's order)",
       [](const RunSpec&, const Report& r, std::size_t) { return share(r.energy.residual, r); }},
      {S::whole, "collapse_t", T::number, "s",
       "the located time a storey's drift ratio passed its building's collapse_drift_ratio, where the run stopped (empty: no collapse)",
       [](const RunSpec&, const Report& r, std::size_t) { return r.collapse ? r.collapse->t : kNaN; }},
  };
  return channels;
}

// A scene written with the two-block keys: SPEC §3's names, in the scene's units. A two-block
// sweep's run asks for every part of the report (study/sweep.cpp run_sweep_point).
const std::vector<SweepChannel>& two_block_sweep_channels() {
  using T = ColumnType;
  using Value = std::function<double(const TwoBlockReport&, const Scales&)>;
  const auto column = [](const char* name, T type, const char* meaning, Value v, bool may_be_empty = false) {
    return SweepChannel{ChannelScope::whole, name, type, "", meaning,
                        [v = std::move(v)](const RunSpec& s, const Report& r, std::size_t) { return v(*r.two_block, s.scales); },
                        may_be_empty};
  };
  // A contact law's results; without one the cells stay empty.
  const auto with_law = [](const TwoBlockReport& r, double v) { return r.pounding->has_law() ? v : kNaN; };
  // A share of the input energy (NaN for zero input).
  const auto of_input = [](const TwoBlockReport& r, double work) { return work / (r.energy->input != 0.0 ? r.energy->input : kNaN); };
  const auto intervals = [](const TwoBlockReport& r, bool stick) {
    std::size_t n = 0;
    for (const auto& interval : r.phases) n += (interval.state == Phase::stick) == stick ? 1 : 0;
    return static_cast<double>(n);
  };
  static const std::vector<SweepChannel> channels = {
      column("x1", T::number, "peak |x1| (block 1's displacement)", [](const TwoBlockReport& r, const Scales& k) { return r.peaks.x1.max_abs * k.length; }),
      column("x2", T::number, "peak |x2|", [](const TwoBlockReport& r, const Scales& k) { return r.peaks.x2.max_abs * k.length; }),
      column("drift", T::number, "peak |x1 - x2| (the damper's stroke)", [](const TwoBlockReport& r, const Scales& k) { return r.peaks.drift.max_abs * k.length; }),
      column("f1", T::number, "peak |f1| (rod 1's force)", [](const TwoBlockReport& r, const Scales& k) { return r.peaks.f1.max_abs * k.force; }),
      column("f2", T::number, "peak |f2|", [](const TwoBlockReport& r, const Scales& k) { return r.peaks.f2.max_abs * k.force; }),
      column("a1_abs", T::number, "peak absolute acceleration of block 1", [](const TwoBlockReport& r, const Scales& k) { return r.peaks.a1.max_abs * k.acceleration; }),
      column("a2_abs", T::number, "peak absolute acceleration of block 2", [](const TwoBlockReport& r, const Scales& k) { return r.peaks.a2.max_abs * k.acceleration; }),
      column("min_gap", T::number, "the pounding margin", [](const TwoBlockReport& r, const Scales& k) { return r.pounding->min_gap * k.length; }),
      column("contact", T::boolean, "whether the gap closed", [](const TwoBlockReport& r, const Scales&) { return r.pounding->contact ? 1.0 : 0.0; }),
      column("outside_model", T::boolean, "no contact law and the gap closed: values after the first contact are outside the model",
             [](const TwoBlockReport& r, const Scales&) { return r.pounding->outside_model() ? 1.0 : 0.0; }),
      column("contact.impacts", T::integer, "impacts (with a contact law)",
             [with_law](const TwoBlockReport& r, const Scales&) { return with_law(r, static_cast<double>(r.pounding->impacts.size())); }, true),
      column("contact.force_max", T::number, "peak contact force (with a contact law)",
             [with_law](const TwoBlockReport& r, const Scales& k) { return with_law(r, r.pounding->force_max * k.force); }),
      column("contact.penetration_max", T::number, "largest penetration (with a contact law)",
             [with_law](const TwoBlockReport& r, const Scales& k) { return with_law(r, r.pounding->penetration_max * k.length); }),
      column("energy_input", T::number, "input energy (per unit m1, or J)", [](const TwoBlockReport& r, const Scales& k) { return r.energy->input * k.energy; }),
      column("share_rod1", T::number, "work on rod 1 / input", [of_input](const TwoBlockReport& r, const Scales&) { return of_input(r, r.energy->rod1); }),
      column("share_rod2", T::number, "work on rod 2 / input", [of_input](const TwoBlockReport& r, const Scales&) { return of_input(r, r.energy->rod2); }),
      column("share_friction", T::number, "friction work / input", [of_input](const TwoBlockReport& r, const Scales&) { return of_input(r, r.energy->friction); }),
      column("share_residual", T::number, "balance residual / input", [of_input](const TwoBlockReport& r, const Scales&) { return of_input(r, r.energy->residual); }),
      column("stick_intervals", T::integer, "stick phases", [intervals](const TwoBlockReport& r, const Scales&) { return intervals(r, true); }),
      column("slip_intervals", T::integer, "slip phases", [intervals](const TwoBlockReport& r, const Scales&) { return intervals(r, false); }),
      column("switches", T::integer, "phase changes",
             [](const TwoBlockReport& r, const Scales&) { return r.phases.empty() ? 0.0 : static_cast<double>(r.phases.size() - 1); }),
  };
  return channels;
}

std::vector<SweepColumn> building_channel_columns(const structure::Structure& s) {
  std::vector<SweepColumn> columns;
  for_each_column(s, [&](const SweepChannel& c, std::size_t k) {
    columns.push_back({expand(c.name, c.scope, k), c.type, c.scope != ChannelScope::whole && !(c.scope == ChannelScope::building && k == 0)});
  });
  return columns;
}

std::vector<std::string> building_channel_cells(const structure::Structure& base, const RunSpec& scene,
                                                const Report& report) {
  std::vector<std::string> cells;
  for_each_column(base, [&](const SweepChannel& c, std::size_t k) {
    if (k >= count(scene.structure, c.scope)) {
      cells.emplace_back();  // a group the run removed
      return;
    }
    cells.push_back(cell(c.type, c.value(scene, report, k)));
  });
  return cells;
}

void prepare_building_sweep(SweepSpec& spec, const structure::Structure& base) {
  spec.base_structure = std::make_shared<const structure::Structure>(base);
  spec.channel_columns = building_channel_columns(base);
}

// A run's structure keeps the base's groups or drops a whole group (its cells are then empty).
void check_groups(const SweepSpec& spec, std::size_t index, const structure::Structure& run) {
  const structure::Structure& base = *spec.base_structure;
  const std::vector<SweepSetting> settings = spec.settings(index);
  struct Group {
    const char* key;
    const char* what;
    std::size_t base, run;
  };
  const Group groups[] = {{"building.B", "building B", base.b ? 1u : 0u, run.b ? 1u : 0u},
                          {"link", "link", base.links.size(), run.links.size()},
                          {"contact", "contact", base.contacts.size(), run.contacts.size()}};
  for (const auto& g : groups) {
    if (g.run == g.base || g.run == 0) continue;
    const std::string plural = std::string(g.what) + (g.base == 1 ? "" : "s");
    throw InputError(at(spec, line_of_edit(settings, g.key)) + "run " + std::to_string(index) + " (" + spec.describe(index) +
                     "): its structure has " + std::to_string(g.run) + " " + g.what + (g.run == 1 ? "" : "s") +
                     " but the base scene has " + std::to_string(g.base) + " " +
                     (g.base == 1 ? std::string(g.what) : plural) +
                     "; a building sweep's columns are the base structure's: a run keeps every " + g.what +
                     " of the base, or removes them all (unset = [\"" + g.key + "\"]), whose cells it leaves empty");
  }
}


std::vector<SweepColumn> channel_columns(const SweepSpec& spec) {
  if (spec.building()) return spec.channel_columns;
  std::vector<SweepColumn> columns;
  for (const auto& c : two_block_sweep_channels()) columns.push_back({c.name, c.type, c.may_be_empty});
  return columns;
}

std::vector<std::string> channel_cells(const SweepSpec& spec, const RunSpec& scene, const Report& report) {
  if (spec.building()) return building_channel_cells(*spec.base_structure, scene, report);
  std::vector<std::string> cells;
  for (const auto& c : two_block_sweep_channels()) cells.push_back(cell(c.type, c.value(scene, report, 0)));
  return cells;
}

}  // namespace adjoin
