#include "adjoin/study/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_motion.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/study/sweep_columns.hpp"

namespace adjoin {

std::string sweep_number_cell(double v) {
  if (std::isnan(v)) return "";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

namespace {

// A double as a TOML float ("1.0", not "1", so that it stays a float).
std::string toml_float(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::string s = sweep_number_cell(v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char code[8];
          std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(c));
          out += code;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

}  // namespace

std::string sweep_value_text(const SweepScalar& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&v)) return toml_float(*d);
  if (const auto* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  return toml_string(std::get<std::string>(v));
}

SweepValue sweep_value(double v) { return SweepValue{v, toml_float(v)}; }
SweepValue sweep_value(std::int64_t v) { return SweepValue{v, std::to_string(v)}; }
SweepValue sweep_value(bool v) { return SweepValue{v, v ? "true" : "false"}; }
SweepValue sweep_value(const std::string& v) { return SweepValue{v, toml_string(v)}; }
SweepValue sweep_value(std::vector<SweepScalar> items) {
  std::string text = "[";
  for (const auto& item : items) text += (text.size() > 1 ? ", " : "") + sweep_value_text(item);
  return SweepValue{std::move(items), text + "]"};
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- numbers as text: shortest round-trip form, so text -> double -> text is the identity ----

std::string shortest(double v) { return sweep_number_cell(v); }

// What a sweep holds in memory, per axis value (its edits) and per run (its row: the cells, then
// the CSV and JSON texts built from them): measured 6.0 kB a run at 26 columns (40,000 runs,
// peak RSS), rounded up to 256 bytes a column (docs/reference/sweep-file.md).
constexpr double kBytesPerValue = 256.0;
double bytes_per_run(std::size_t columns) { return 256.0 * static_cast<double>(columns); }

// "478 GB": sizes in messages.
std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  return text;
}

// What a sweep may use: 80 % of the machine's memory (0: unknown, no limit), as `adjoin run`.
double memory_budget() { return 0.8 * physical_memory_bytes(); }

std::string budget_text() {
  return "more than the " + gigabytes(memory_budget()) + " this machine can give (80 % of " +
         gigabytes(physical_memory_bytes()) + ")";
}

std::string sa_column(double period) { return "sa_" + shortest(period); }

// ---- the runs ----

// Keeps what the intensity measures need: max |a_g| always, the history (m/s^2) only for Sa.
// A two-block run's a_g is in g (State), a structure's in m/s^2 (StructureState).
class GroundRecorder final : public StructureObserver {
 public:
  // two_block: the run's 1 + 1 structure is dimensionless (a_g in g).
  GroundRecorder(bool keep, bool two_block) : keep_(keep), two_block_(two_block) {}
  // (pga_g: a two-block run's a_g is in g already, a building's in m/s^2.)
  void begin(const structure::Structure&, const StructureSolverOptions& o) override {
    start(o.steps(), two_block_ ? 1.0 : kStandardGravity);
  }
  void observe(const StructureState& st) override { take(st.ag, two_block_ ? st.ag * kStandardGravity : st.ag); }
  double pga_g() const { return pga_ / unit_; }
  std::vector<double> ag;  // m/s^2

 private:
  void start(std::size_t steps, double unit) {
    pga_ = 0.0;
    unit_ = unit;
    ag.clear();
    if (keep_) ag.reserve(steps + 1);
  }
  void take(double own, double si) {
    pga_ = std::max(pga_, std::abs(own));
    if (keep_) ag.push_back(si);
  }
  bool keep_, two_block_;
  double pga_ = 0.0, unit_ = 1.0;  // max |a_g| in the run's own unit, and g in it
};

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

std::string sweep_axis_memory_problem(std::size_t n, std::size_t columns) {
  // Sized before the points are made: a huge axis is refused now, not by bad_alloc later.
  const double need = static_cast<double>(n) * (kBytesPerValue + bytes_per_run(columns + 1));
  if (memory_budget() > 0.0 && need > memory_budget())
    return "would need about " + gigabytes(need) + " of memory for the sweep's table alone, " + budget_text();
  return "";
}

std::vector<std::string> SweepSetting::overrides() const {
  std::vector<std::string> out;
  for (const auto& [key, value] : set) out.push_back(key + "=" + value.text);
  return out;
}

std::size_t SweepSpec::runs() const {
  std::size_t n = motions.size();
  for (const auto& a : axes) n *= a.values.size();
  return n;
}

std::vector<std::size_t> SweepSpec::coordinates(std::size_t index) const {
  std::vector<std::size_t> c(axes.size() + 1, 0);
  c[axes.size()] = index % motions.size();
  index /= motions.size();
  for (std::size_t k = axes.size(); k-- > 0;) {
    c[k] = index % axes[k].values.size();
    index /= axes[k].values.size();
  }
  return c;
}

std::vector<SweepSetting> SweepSpec::settings(std::size_t index) const {
  const auto c = coordinates(index);
  std::vector<SweepSetting> s;
  if (!common.set.empty() || !common.unset.empty()) s.push_back(common);
  for (std::size_t k = 0; k < axes.size(); ++k) s.push_back(axes[k].values[c[k]]);
  s.push_back(motions[c.back()]);
  return s;
}

std::string SweepSpec::describe(std::size_t index) const {
  const auto c = coordinates(index);
  std::string text;
  for (std::size_t k = 0; k < axes.size(); ++k) text += axes[k].name + "=" + axes[k].values[c[k]].label + ", ";
  return text + "motion=" + motions[c.back()].label;
}

void check_sweep_memory(const SweepSpec& spec, std::size_t runs) {
  double values = 0.0;
  for (const auto& a : spec.axes) values += static_cast<double>(a.values.size());
  const double per_run = bytes_per_run(sweep_columns(spec).size());
  const double need = values * kBytesPerValue + static_cast<double>(runs) * per_run;
  if (memory_budget() <= 0.0 || need <= memory_budget()) return;
  char per[32];
  std::snprintf(per, sizeof per, "%.2g", per_run / 1e3);
  throw InputError(spec.file.string() + ": the sweep's table of " + std::to_string(runs) + " runs would need about " +
                   gigabytes(need) + " of memory (about " + per + " kB a run), " + budget_text() +
                   "; use fewer points on the axes, or split it with --shard I/N over several machines");
}

RunSpec sweep_scene(const SweepSpec& spec, std::size_t index) {
  if (!spec.scenes) throw std::logic_error("sweep_scene: the sweep has no SweepScenes (read it with load_sweep or parse_sweep)");
  RunSpec scene = spec.scenes->scene(spec, index);
  if (spec.building()) check_groups(spec, index, scene.structure);  // its columns are the base's
  return scene;
}

SweepRow run_sweep_point(const SweepSpec& spec, std::size_t index) {
  const auto start = std::chrono::steady_clock::now();
  SweepRow row;
  row.index = index;
  const RunSpec scene = sweep_scene(spec, index);
  row.units = scene.scales.units_name();

  // Every row has the same columns, whatever the scene's [output] asks of `adjoin run`; a sweep
  // writes no run files, so no in-structure spectra.
  RunSpec asked = scene;
  asked.output.peaks = asked.output.phases = asked.output.pounding = asked.output.energy = true;
  asked.output.spectra.reset();
  GroundRecorder ground(!spec.im_periods.empty(), scene.two_block());
  try {
    const Report report = run(asked, RunObservers{&ground});
    row.channels = channel_cells(spec, asked, report);
    // Intensity measures of the forcing as the solver saw it.
    row.pga_g = ground.pga_g();
    if (!spec.im_periods.empty()) {
      // The step in seconds (a dimensionless scene's time unit: a record's time scale).
      const auto* record = dynamic_cast<const RecordMotion*>(&unscaled_ground(*scene.ground));
      const double seconds = !scene.two_block() ? 1.0 : record ? record->time_scale() : scene.scales.time;
      SpectrumOptions options;
      options.dampings = {spec.im_damping};
      options.threads = 1;
      for (double period : spec.im_periods)
        row.sa_g.push_back(spectral_values(scene.solver.h * seconds, ground.ag, period, spec.im_damping, options).sa);
    }
  } catch (const NumericalError& e) {
    row.channels.assign(channel_columns(spec).size(), "");
    row.pga_g = kNaN;
    row.sa_g.assign(spec.im_periods.size(), kNaN);
    row.error = one_line(e.what());
    if (row.error.empty()) row.error = "numerical failure";
  }
  row.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

std::vector<SweepRow> run_sweep(const SweepSpec& spec, const SweepOptions& options) {
  std::vector<std::size_t> indices = options.indices;
  if (indices.empty()) {
    indices.resize(spec.runs());
    for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
  } else {
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    if (indices.back() >= spec.runs())
      throw InputError(spec.file.string() + ": run " + std::to_string(indices.back()) + " does not exist (the sweep has " +
                       std::to_string(spec.runs()) + " runs)");
  }
  std::vector<SweepRow> rows(indices.size());
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex lock;
  std::exception_ptr failure;
  std::size_t failure_index = std::numeric_limits<std::size_t>::max();

  auto work = [&] {
    for (;;) {
      if (stop.load()) return;
      const std::size_t k = next.fetch_add(1);
      if (k >= indices.size()) return;
      try {
        rows[k] = run_sweep_point(spec, indices[k]);
        if (options.sink || options.on_row) {
          std::lock_guard<std::mutex> guard(lock);
          if (options.sink) options.sink->take(rows[k]);
          if (options.on_row) options.on_row(rows[k]);
        }
      } catch (...) {
        std::lock_guard<std::mutex> guard(lock);
        if (indices[k] < failure_index) {
          failure_index = indices[k];
          failure = std::current_exception();
        }
        stop.store(true);
        return;
      }
    }
  };
  unsigned jobs = options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  jobs = static_cast<unsigned>(std::min<std::size_t>(jobs, indices.size()));
  if (jobs <= 1) {
    work();
  } else {
    std::vector<std::thread> threads;
    for (unsigned j = 0; j < jobs; ++j) threads.emplace_back(work);
    for (auto& t : threads) t.join();
  }
  if (failure) std::rethrow_exception(failure);
  return rows;
}

// ---- the table ----

std::vector<SweepColumn> sweep_columns(const SweepSpec& spec) {
  std::vector<SweepColumn> c{{"index", ColumnType::integer}};
  for (const auto& a : spec.axes) {
    const bool numeric = std::all_of(a.values.begin(), a.values.end(), [](const SweepSetting& s) { return s.number.has_value(); });
    c.push_back({a.name, numeric ? ColumnType::number : ColumnType::string});
  }
  c.push_back({"motion", ColumnType::string});
  c.push_back({"units", ColumnType::string});
  const auto channels = channel_columns(spec);  // x1 ... switches, or a structure's (study/sweep_columns.hpp)
  c.insert(c.end(), channels.begin(), channels.end());
  c.push_back({"pga_g", ColumnType::number});
  for (double t : spec.im_periods) c.push_back({sa_column(t), ColumnType::number});
  c.push_back({"wall_seconds", ColumnType::number});
  c.push_back({"error", ColumnType::string});
  return c;
}

std::vector<std::string> sweep_cells(const SweepSpec& spec, const SweepRow& row) {
  std::vector<std::string> cells{std::to_string(row.index)};
  const auto coordinates = spec.coordinates(row.index);
  for (std::size_t k = 0; k < spec.axes.size(); ++k) cells.push_back(spec.axes[k].values[coordinates[k]].label);
  cells.push_back(spec.motions[coordinates.back()].label);
  cells.push_back(row.units);
  const std::size_t columns = channel_columns(spec).size();
  for (std::size_t i = 0; i < columns; ++i) cells.push_back(i < row.channels.size() ? row.channels[i] : "");
  cells.push_back(shortest(row.pga_g));
  for (std::size_t i = 0; i < spec.im_periods.size(); ++i) cells.push_back(i < row.sa_g.size() ? shortest(row.sa_g[i]) : "");
  cells.push_back(shortest(row.wall_seconds));
  cells.push_back(one_line(row.error));
  return cells;
}

SweepTable sweep_table(const SweepSpec& spec, const std::vector<SweepRow>& rows) {
  SweepTable table;
  table.columns = sweep_columns(spec);
  std::vector<const SweepRow*> ordered;
  for (const auto& r : rows) ordered.push_back(&r);
  std::sort(ordered.begin(), ordered.end(), [](const SweepRow* a, const SweepRow* b) { return a->index < b->index; });
  for (const auto* r : ordered) table.rows.push_back(sweep_cells(spec, *r));
  return table;
}

std::string sweep_csv(const SweepTable& table) {
  std::vector<std::string> header;
  for (const auto& c : table.columns) header.push_back(c.name);
  std::string out = csv_line(header) + "\n";
  for (const auto& r : table.rows) out += csv_line(r) + "\n";
  return out;
}

}  // namespace adjoin
