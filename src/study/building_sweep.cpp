#include "adjoin/study/building_sweep.hpp"

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

// A run's structure keeps the base's groups or drops a whole group (its cells are then empty).
void check_groups(const SweepSpec& spec, std::size_t index, const std::vector<SweepSetting>& settings,
                  const structure::Structure& run) {
  const structure::Structure& base = *spec.base_structure;
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

// a_g at every grid point [m/s^2], for the intensity measures.
class GroundHistory final : public StructureObserver {
 public:
  explicit GroundHistory(bool keep) : keep_(keep) {}
  void begin(const structure::Structure&, const StructureSolverOptions& o) override {
    pga = 0.0;
    ag.clear();
    if (keep_) ag.reserve(o.steps() + 1);
  }
  void observe(const StructureState& st) override {
    pga = std::max(pga, std::abs(st.ag));
    if (keep_) ag.push_back(st.ag);
  }
  double pga = 0.0;
  std::vector<double> ag;

 private:
  bool keep_;
};

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
    const double v = c.value(scene, report, k);
    switch (c.type) {
      case ColumnType::integer: cells.push_back(std::to_string(static_cast<std::size_t>(v))); break;
      case ColumnType::boolean: cells.push_back(v != 0.0 ? "true" : "false"); break;
      default: cells.push_back(sweep_number_cell(v)); break;
    }
  });
  return cells;
}

void prepare_building_sweep(SweepSpec& spec, const structure::Structure& base) {
  spec.base_structure = std::make_shared<const structure::Structure>(base);
  spec.channel_columns = building_channel_columns(base);
}

RunSpec building_sweep_scene(const SweepSpec& spec, std::size_t index) {
  if (!spec.scenes)
    throw std::logic_error("building_sweep_scene: the sweep has no SweepScenes (read it with load_sweep or parse_sweep)");
  RunSpec scene = spec.scenes->scene(spec, index);
  check_groups(spec, index, spec.settings(index), scene.structure);
  return scene;
}

SweepRow run_building_sweep_point(const SweepSpec& spec, std::size_t index) {
  const auto start = std::chrono::steady_clock::now();
  SweepRow row;
  row.index = index;
  row.units = "SI";
  RunSpec scene = building_sweep_scene(spec, index);
  scene.output.spectra.reset();  // a sweep writes no run files: no in-structure spectra
  GroundHistory ground(!spec.im_periods.empty());
  try {
    const Report report = run(scene, {&ground});
    row.channels = building_channel_cells(*spec.base_structure, scene, report);
    row.pga_g = ground.pga / kStandardGravity;
    SpectrumOptions options;
    options.dampings = {spec.im_damping};
    options.threads = 1;
    for (double period : spec.im_periods)
      row.sa_g.push_back(spectral_values(scene.solver.h, ground.ag, period, spec.im_damping, options).sa);
  } catch (const NumericalError& e) {
    row.channels.assign(spec.channel_columns.size(), "");
    row.pga_g = kNaN;
    row.sa_g.assign(spec.im_periods.size(), kNaN);
    std::string message = e.what();
    for (char& c : message)
      if (c == '\n' || c == '\r') c = ' ';
    row.error = message.empty() ? "numerical failure" : message;
  }
  row.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

}  // namespace adjoin
