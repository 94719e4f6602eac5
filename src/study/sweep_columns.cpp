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
void for_each_column(const ChannelCounts& n, F each) {
  const auto& channels = building_sweep_channels();
  auto scope = [&](ChannelScope which, std::size_t k) {
    for (const auto& c : channels)
      if (c.scope == which) each(c, k);
  };
  for (std::size_t k = 0; k < n.buildings; ++k) scope(ChannelScope::building, k);
  for (std::size_t k = 0; k < n.links; ++k) scope(ChannelScope::link, k);
  for (std::size_t k = 0; k < n.contacts; ++k) scope(ChannelScope::contact, k);
  scope(ChannelScope::whole, 0);
}

// The largest N of the keys `group`.N.KEY the sweep's edits set (0: none).
std::size_t largest_index_set(const SweepSpec& spec, const std::string& group) {
  std::size_t most = 0;
  const auto look = [&](const SweepSetting& s) {
    for (const auto& [key, value] : s.set) {
      if (key.rfind(group + ".", 0) != 0) continue;
      const std::string rest = key.substr(group.size() + 1);
      std::size_t n = 0;
      const auto dot = rest.find('.');
      const auto [end, ec] = std::from_chars(rest.data(), rest.data() + (dot == std::string::npos ? rest.size() : dot), n);
      if (ec == std::errc() && dot != std::string::npos && end == rest.data() + dot && n <= 999999) most = std::max(most, n);
    }
  };
  look(spec.common);
  for (const auto& axis : spec.axes)
    for (const auto& v : axis.values) look(v);
  for (const auto& m : spec.motions) look(m);
  return most;
}

// Whether the run's unsets of numbered tables (link.1 of two) leave a table of the base under
// another number; sets `removed` and `kept` (1-based, in the base) when they do.
bool renumbers(const std::vector<SweepSetting>& settings, const std::string& group, std::size_t base, std::size_t* removed,
               std::size_t* kept) {
  std::vector<std::size_t> left(base);
  for (std::size_t i = 0; i < base; ++i) left[i] = i + 1;
  std::vector<std::size_t> gone;
  for (const auto& s : settings)
    for (const auto& key : s.unset) {
      if (key == group) left.clear();
      if (key.rfind(group + ".", 0) != 0) continue;
      std::size_t n = 0;
      const std::string rest = key.substr(group.size() + 1);
      const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), n);
      if (ec != std::errc() || end != rest.data() + rest.size() || n < 1 || n > left.size()) continue;
      gone.push_back(left[n - 1]);
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(n - 1));
    }
  for (std::size_t i = 0; i < left.size(); ++i)
    if (left[i] != i + 1) {
      *kept = left[i];
      *removed = *std::min_element(gone.begin(), gone.end());
      return true;
    }
  return false;
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

ChannelCounts channel_counts(const structure::Structure& s) {
  return {count(s, ChannelScope::building), s.links.size(), s.contacts.size()};
}

std::vector<SweepColumn> building_channel_columns(const ChannelCounts& counts) {
  std::vector<SweepColumn> columns;
  for_each_column(counts, [&](const SweepChannel& c, std::size_t k) {
    columns.push_back({expand(c.name, c.scope, k), c.type, c.scope != ChannelScope::whole && !(c.scope == ChannelScope::building && k == 0)});
  });
  return columns;
}

std::vector<SweepColumn> building_channel_columns(const structure::Structure& s) {
  return building_channel_columns(channel_counts(s));
}

std::vector<std::string> building_channel_cells(const ChannelCounts& counts, const RunSpec& scene, const Report& report) {
  std::vector<std::string> cells;
  for_each_column(counts, [&](const SweepChannel& c, std::size_t k) {
    if (k >= count(scene.structure, c.scope)) {
      cells.emplace_back();  // a group the run removed, or a link another run adds
      return;
    }
    cells.push_back(cell(c.type, c.value(scene, report, k)));
  });
  return cells;
}

std::vector<std::string> building_channel_cells(const structure::Structure& base, const RunSpec& scene,
                                                const Report& report) {
  return building_channel_cells(channel_counts(base), scene, report);
}

namespace {
ChannelCounts sweep_counts(const SweepSpec& spec) {
  return {count(*spec.base_structure, ChannelScope::building), spec.link_columns, spec.contact_columns};
}
}  // namespace

void prepare_building_sweep(SweepSpec& spec, const structure::Structure& base) {
  spec.base_structure = std::make_shared<const structure::Structure>(base);
  spec.link_columns = std::max(base.links.size(), largest_index_set(spec, "link"));
  spec.contact_columns = std::max(base.contacts.size(), largest_index_set(spec, "contact"));
  spec.channel_columns = building_channel_columns(sweep_counts(spec));
}

// A run's structure keeps the base's building B or drops it; its links and contacts fit the
// columns, each under its own number (see the header).
void check_groups(const SweepSpec& spec, std::size_t index, const structure::Structure& run) {
  const structure::Structure& base = *spec.base_structure;
  const std::vector<SweepSetting> settings = spec.settings(index);
  const auto refuse = [&](const char* key, const std::string& why) {
    throw InputError(at(spec, line_of_edit(settings, key)) + "run " + std::to_string(index) + " (" + spec.describe(index) +
                     "): " + why);
  };
  if (!base.b && run.b)
    refuse("building.B", "its structure has a building B the base scene has not; a building sweep's columns are the "
                         "base structure's: add building B to the base scene");
  struct Group {
    const char* key;
    std::size_t base, columns, run;
  };
  const Group groups[] = {{"link", base.links.size(), spec.link_columns, run.links.size()},
                          {"contact", base.contacts.size(), spec.contact_columns, run.contacts.size()}};
  for (const auto& g : groups) {
    const std::string key = g.key;
    if (g.run > g.columns)  // (an edit that adds one names its number, which sized the columns)
      refuse(g.key, "its structure has " + std::to_string(g.run) + " " + key + "s, more than the table's " +
                        std::to_string(g.columns) + " " + key + " columns");
    if (std::size_t removed = 0, kept = 0; renumbers(settings, key, g.base, &removed, &kept))
      refuse(g.key, "it removes " + key + "." + std::to_string(removed) + " but keeps " + key + "." + std::to_string(kept) +
                        ", which would become " + key + "." + std::to_string(kept - 1) + " and fill the " + key +
                        std::to_string(kept - 1) + " columns of another " + key +
                        "; remove the last ones (unset = [\"" + key + "." + std::to_string(g.base) +
                        "\"]) and set the keys of those kept, or unset = [\"" + key + "\"] and add each with " + key +
                        ".N.KEY");
  }
}


// The table io presents a base under (a two-block scene's), or null.
const std::vector<SweepChannel>* presented(const SweepSpec& spec) {
  return spec.building() || !spec.scenes ? nullptr : spec.scenes->presented_channels();
}

std::vector<SweepColumn> channel_columns(const SweepSpec& spec) {
  if (spec.building()) return spec.channel_columns;
  std::vector<SweepColumn> columns;
  if (const auto* table = presented(spec))
    for (const auto& c : *table) columns.push_back({c.name, c.type, c.may_be_empty});
  return columns;
}

std::vector<std::string> channel_cells(const SweepSpec& spec, const RunSpec& scene, const Report& report) {
  if (spec.building()) return building_channel_cells(sweep_counts(spec), scene, report);
  std::vector<std::string> cells;
  if (const auto* table = presented(spec))
    for (const auto& c : *table) cells.push_back(cell(c.type, c.value(scene, report, 0)));
  return cells;
}

}  // namespace adjoin
