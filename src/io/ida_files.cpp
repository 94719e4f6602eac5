#include "adjoin/io/ida_files.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include <toml++/toml.h>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/io/sweep_scenes.hpp"
#include "adjoin/io/table_plots.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/study/sweep_columns.hpp"

namespace adjoin {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();


SweepValue text_value(const std::string& text) { return SweepValue{text, "\"" + text + "\""}; }
SweepValue number_value(double v) { return SweepValue{v, sweep_number_cell(v)}; }

// The base scene's ground.source ("" if it has none) and ground.time_scale (a dimensionless
// scene's unit of time, which its records keep). Its syntax errors are the scene reader's.
struct BaseGround {
  std::string source;
  std::optional<double> time_scale;
};
BaseGround base_ground(const std::string& text, const fs::path& scene) {
  try {
    const toml::table t = toml::parse(text, scene.string());
    return {t.at_path("ground.source").value_or(std::string()), t.at_path("ground.time_scale").value<double>()};
  } catch (const toml::parse_error&) {
    return {};
  }
}

}  // namespace

// ---- the suite ----

std::vector<fs::path> ida_suite(const std::vector<std::string>& inputs, std::vector<std::string>* skipped) {
  std::vector<fs::path> files;
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (!fs::is_directory(input, ec)) {
      if (!fs::is_regular_file(input, ec)) throw InputError("--suite " + text_excerpt(input) + ": no such record file or folder");
      files.emplace_back(input);
      continue;
    }
    std::vector<fs::path> found;
    for (auto it = fs::directory_iterator(input, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
      if (it->is_regular_file(ec) && it->path().filename().string().front() != '.') found.push_back(it->path());
    if (ec) throw InputError("--suite " + input + ": cannot list the folder: " + ec.message());
    std::sort(found.begin(), found.end());
    std::size_t taken = 0;
    for (const fs::path& file : found) {
      if (detect_record_format(file) == RecordFormat::Kind::automatic) {
        if (skipped) skipped->push_back(file.string());
        continue;
      }
      files.push_back(file);
      ++taken;
    }
    if (taken == 0)
      throw InputError("--suite " + input + ": no record file in it that a reader recognises by its header (give column files by name)");
  }
  std::map<std::string, std::string> names, paths;
  for (const fs::path& f : files) {
    std::error_code ec;
    const std::string canonical = fs::weakly_canonical(f, ec).string();
    if (const auto [at, fresh] = paths.emplace(ec ? f.string() : canonical, f.string()); !fresh)
      throw InputError("--suite: " + f.string() + " given twice (also as " + at->second + ")");
    if (const auto [at, fresh] = names.emplace(f.filename().string(), f.string()); !fresh)
      throw InputError("--suite: " + f.string() + " and " + at->second +
                       " have the same file name, which names a record in ida.csv (rename one)");
  }
  if (files.empty()) throw InputError("--suite: expected record files or folders of them");
  return files;
}

// ---- the sweep ----

SweepSpec ida_sweep(const fs::path& scene, const std::vector<IdaMotion>& motions, const std::string& units,
                    const std::string& name) {
  SweepSpec spec;
  spec.file = name;
  spec.name = "ida";
  spec.base = scene;
  const std::string base_text = read_text_file(scene, "scene");
  // The base's own record, its processing and scale_pga do not carry over: its [ground] goes
  // (setting another source than the base's drops it already, io/scene.hpp implied_unsets).
  const BaseGround base = base_ground(base_text, scene);
  const bool base_is_record = base.source == "record";
  std::string described;
  for (const IdaMotion& m : motions) {
    SweepSetting s;
    s.label = m.record;
    if (base_is_record) s.unset = {"ground"};
    s.set = {{"ground.source", text_value("record")},
             {"ground.file", text_value(fs::absolute(m.file).lexically_normal().string())},
             {"ground.scale", number_value(m.scale)}};
    if (!units.empty()) s.set.emplace_back("ground.units", text_value(units));
    if (base_is_record && base.time_scale) s.set.emplace_back("ground.time_scale", number_value(*base.time_scale));
    for (const auto& o : s.overrides()) described += o + "\n";
    spec.motions.push_back(std::move(s));
  }
  const auto scenes = std::make_shared<const SceneSweepScenes>(spec, base_text);
  spec.scenes = scenes;
  if (scenes->building()) prepare_building_sweep(spec, scenes->base().structure);
  else (void)scenes->base();  // checked as `adjoin run` would
  spec.fingerprint = sweep_fingerprint("adjoin ida\n" + described, base_text);
  return spec;
}

void set_ida_scale(SweepSpec& spec, std::size_t motion, double scale) {
  for (auto& [key, value] : spec.motions.at(motion).set)
    if (key == "ground.scale") value = number_value(scale);
}

// ---- the demands ----

std::vector<std::string> ida_default_edps(const SweepSpec& spec) {
  std::vector<std::string> wanted;
  if (!spec.building()) return {"x1", "x2", "drift", "f1", "f2", "min_gap"};
  const structure::Structure& s = *spec.base_structure;
  for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr}) {
    if (!b) continue;
    wanted.push_back(b->name + (b->has_heights() ? ".drift_ratio_max" : ".drift_max"));
    wanted.push_back(b->name + ".roof_max");
    wanted.push_back(b->name + ".accel_max");
  }
  for (std::size_t k = 1; k <= s.links.size(); ++k)
    for (const char* c : {".force_max", ".stroke_max"}) wanted.push_back("link" + std::to_string(k) + c);
  for (std::size_t k = 1; k <= s.contacts.size(); ++k)
    for (const char* c : {".min_gap", ".impacts"}) wanted.push_back("contact" + std::to_string(k) + c);
  wanted.push_back("collapse_t");
  return wanted;
}

void check_ida_edps(const SweepSpec& spec, const std::vector<std::string>& edps, const std::string& option) {
  const auto columns = sweep_columns(spec);
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  if (edps.empty()) throw InputError(option + ": expected column names separated by commas");
  for (const auto& e : edps)
    if (std::find(names.begin(), names.end(), e) == names.end()) {
      std::string all;
      for (const auto& c : channel_columns(spec)) all += (all.empty() ? "" : ", ") + c.name;
      throw InputError(option + " " + text_excerpt(e) + ": not a column of this scene's sweep table; its demands are " + all);
    }
}

std::string ida_csv(const std::vector<std::string>& edps, const std::vector<IdaRow>& rows) {
  std::vector<std::string> header{"record", "im", "scale"};
  header.insert(header.end(), edps.begin(), edps.end());
  std::string out = csv_line(header) + "\n";
  for (const auto& r : rows) {
    std::vector<std::string> cells{r.record, sweep_number_cell(r.im), sweep_number_cell(r.scale)};
    cells.insert(cells.end(), r.edps.begin(), r.edps.end());
    out += csv_line(cells) + "\n";
  }
  return out;
}

// ---- the figure ----

void plot_ida(const std::vector<IdaRow>& rows, std::size_t edp, const std::string& edp_name, const std::string& im,
              bool si, const std::string& title, const fs::path& image, const PlotStyle& style) {
  // The curves by record, in the order the records first appear.
  std::vector<std::string> records;
  std::vector<IdaCurve> curves;
  std::vector<double> levels;
  double largest = 0.0;
  for (const auto& r : rows) {
    auto at = std::find(records.begin(), records.end(), r.record);
    if (at == records.end()) {
      records.push_back(r.record);
      curves.emplace_back();
      at = records.end() - 1;
    }
    IdaCurve& c = curves[static_cast<std::size_t>(at - records.begin())];
    double v = kNaN;
    if (r.event || !r.error.empty()) v = kInf;
    else if (edp < r.edps.size() && !r.edps[edp].empty()) v = std::strtod(r.edps[edp].c_str(), nullptr);
    c.im.push_back(r.im);
    c.edp.push_back(v);
    levels.push_back(r.im);
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  if (largest == 0.0) largest = 1.0;
  // A capacity event is drawn as a flat line to the right of the figure's data.
  const double flat = 1.15 * largest;
  const auto clip = [&](double v) { return std::isinf(v) ? flat : v; };

  std::ostringstream s;
  s << kGnuplotPreamble;
  for (std::size_t k = 0; k < curves.size(); ++k) {
    std::vector<std::size_t> order(curves[k].im.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return curves[k].im[a] < curves[k].im[b]; });
    std::vector<std::vector<double>> cols(2);
    cols[0].push_back(0.0), cols[1].push_back(0.0);
    for (std::size_t i : order) {
      if (std::isnan(curves[k].edp[i])) continue;
      // The curve ends at its first capacity event: a flat line at the last IM without it.
      const bool event = std::isinf(curves[k].edp[i]);
      cols[0].push_back(clip(curves[k].edp[i]));
      cols[1].push_back(event ? cols[1].back() : curves[k].im[i]);
      if (event) break;
    }
    gnuplot_datablock(s, "r" + std::to_string(k), cols);
  }
  const double ps[] = {0.16, 0.5, 0.84};
  for (std::size_t f = 0; f < 3; ++f) {
    const auto values = ida_fractile(curves, levels, ps[f]);
    std::vector<std::vector<double>> cols(2);
    for (std::size_t i = 0; i < levels.size(); ++i) {
      if (std::isnan(values[i])) continue;
      const bool event = std::isinf(values[i]);  // flat, as the curves
      cols[0].push_back(clip(values[i]));
      cols[1].push_back(event ? (cols[1].empty() ? 0.0 : cols[1].back()) : levels[i]);
      if (event) break;
    }
    gnuplot_datablock(s, "f" + std::to_string(f), cols);
  }
  const std::string im_label = im == "pga" ? "peak ground acceleration [g]" : "S_a(T = " + im.substr(3) + " s, 5 %) [g]";
  s << "set title " << gnuplot_quote(title + ": " + std::to_string(records.size()) + " records") << " noenhanced font ',12'\n"
    << "set xlabel " << gnuplot_quote(table_column_label(edp_name, si)) << " noenhanced\n"
    << "set ylabel " << gnuplot_quote(im_label) << "\n"
    << "set key outside right top vertical Left reverse noenhanced\n"
    << "set xrange [0:" << gnuplot_number(1.2 * largest) << "]\nset yrange [0:*]\n"
    << "set arrow from " << gnuplot_number(flat) << ", graph 0 to " << gnuplot_number(flat)
    << ", graph 1 nohead dt 3 lc rgb 'gray50'\n"
    << "set label " << gnuplot_quote("capacity") << " at " << gnuplot_number(flat) << ", graph 0.03 right offset -0.5,0 font ',9' textcolor rgb 'gray40'\n"
    << "plot ";
  for (std::size_t k = 0; k < curves.size(); ++k)
    s << "$r" << k << " using 1:2 with linespoints lc rgb 'gray70' lw 1 pt 7 ps 0.4 " << (k == 0 ? "title 'records'" : "notitle") << ", ";
  s << "$f0 using 1:2 with lines lc rgb '#1f77b4' lw 2.5 dt 2 title '16 %', "
    << "$f1 using 1:2 with lines lc rgb '#d62728' lw 3 title '50 %', "
    << "$f2 using 1:2 with lines lc rgb '#1f77b4' lw 2.5 dt 4 title '84 %'\n";
  render_gnuplot(s.str(), image, style);
}

// ---- the runs, without files ----

std::vector<IdaRecord> read_ida_suite(const std::vector<std::string>& inputs, const std::string& units,
                                      const IntensityMeasure& im, std::vector<std::string>* skipped,
                                      const std::string& units_option) {
  const auto files = ida_suite(inputs, skipped);
  RecordFormat format;
  if (!units.empty()) {
    AccelUnit unit;
    if (!parse_accel_unit(units, &unit))
      throw InputError(units_option + " " + text_excerpt(units) + ": expected g, m/s2, cm/s2 (or gal) or mm/s2");
    format.units = unit;
  }
  std::vector<IdaRecord> records;
  for (const auto& f : files) records.push_back({f, f.filename().string(), record_intensity(read_record(f, format), im)});
  return records;
}

namespace {
// The column index of `name` in the sweep's table (the count of columns if none).
std::size_t column_of(const SweepSpec& spec, const std::string& name) {
  const auto columns = sweep_columns(spec);
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].name == name) return c;
  return columns.size();
}
}  // namespace

bool IdaCapacity::operator()(const std::vector<std::string>& cells) const {
  if (!cells[error_column].empty()) return true;
  if (collapse && !cells[collapse_column].empty()) return true;
  if (!event) return false;
  std::vector<double> values(event_columns.size(), std::nan(""));
  for (std::size_t c : event->columns_used()) {
    const std::string& cell = cells[event_columns[c]];
    if (cell == "true" || cell == "false") values[c] = cell == "true" ? 1.0 : 0.0;  // a boolean reads as 1/0
    else parse_finite(cell, &values[c]);  // an empty cell stays NaN: unknown
  }
  return event->evaluate(values).value_or(false);
}

IdaCapacity ida_capacity(const SweepSpec& spec, const std::string& event, const std::string& option) {
  IdaCapacity c;
  const auto columns = sweep_columns(spec);
  c.error_column = columns.size() - 1;
  c.collapse_column = column_of(spec, "collapse_t");
  c.collapse = c.collapse_column < columns.size();
  if (!event.empty()) {
    std::vector<std::string> demands;
    for (const auto& d : channel_columns(spec)) {
      demands.push_back(d.name);
      c.event_columns.push_back(column_of(spec, d.name));
    }
    c.event = FragilityEvent::parse(event, demands, option);
  }
  return c;
}

IdaRow ida_row(const SweepSpec& spec, const std::vector<std::string>& cells, const std::vector<std::string>& edps,
               const IdaRecord& record, double level, double scale, const IdaCapacity& capacity) {
  IdaRow row;
  row.record = record.name;
  row.im = level;
  row.scale = scale;
  for (const auto& e : edps) row.edps.push_back(cells[column_of(spec, e)]);
  row.units = cells[column_of(spec, "units")];
  row.error = cells.back();
  row.event = capacity(cells);
  return row;
}

std::vector<IdaMotion> ida_stripe_motions(const std::vector<IdaRecord>& records, const std::vector<double>& levels) {
  std::vector<IdaMotion> motions;
  for (const auto& r : records)
    for (double level : levels) motions.push_back({r.name, r.file, level / r.im});
  return motions;
}

std::vector<IdaRow> ida_stripe_rows(const SweepSpec& spec, const std::vector<std::vector<std::string>>& cells,
                                    const std::vector<IdaRecord>& records, const std::vector<double>& levels,
                                    const std::vector<std::string>& edps, const IdaCapacity& capacity) {
  std::vector<IdaRow> rows;
  for (const auto& c : cells) {
    std::size_t index = 0;
    parse_count(c.at(0), &index);
    const IdaRecord& record = records[index / levels.size()];
    const double level = levels[index % levels.size()];
    rows.push_back(ida_row(spec, c, edps, record, level, level / record.im, capacity));
  }
  return rows;
}

std::vector<IdaRow> ida_traces(const IdaTraceRequest& request, const std::vector<IdaRecord>& records,
                               std::vector<std::string>* edps, std::vector<Trace>* found) {
  std::vector<SweepSpec> specs;
  for (const auto& r : records) specs.push_back(ida_sweep(request.scene, {{r.name, r.file, 1.0}}, request.units, request.name));
  if (edps->empty()) *edps = ida_default_edps(specs[0]);
  check_ida_edps(specs[0], *edps, request.edp_option);
  const IdaCapacity capacity = ida_capacity(specs[0], request.capacity, request.capacity_option);
  if (!capacity.collapse && !capacity.event)
    throw InputError(request.trace_option + ": this scene has no collapse check (storey heights give one: collapse_drift_ratio); "
                     "give the capacity event with " + request.capacity_option + " \"COLUMN OP X [and|or ...]\", e.g. " +
                     request.capacity_option + " \"drift > 0.05\"");
  std::vector<std::vector<IdaRow>> per_record(records.size());
  found->assign(records.size(), Trace{});
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  std::exception_ptr failure;
  auto work = [&] {
    for (std::size_t k; (k = next.fetch_add(1)) < records.size();) {
      try {
        SweepSpec spec = specs[k];
        (*found)[k] = hunt_and_fill(
            [&](double level) {
              const double scale = level / records[k].im;
              set_ida_scale(spec, 0, scale);
              const SweepRow row = run_sweep_point(spec, 0);
              per_record[k].push_back(ida_row(spec, sweep_cells(spec, row), *edps, records[k], level, scale, capacity));
              return per_record[k].back().event;
            },
            request.options);
        std::lock_guard<std::mutex> guard(lock);
        if (request.on_record) request.on_record();
      } catch (...) {
        std::lock_guard<std::mutex> guard(lock);
        if (!failure) failure = std::current_exception();
        next = records.size();
      }
    }
  };
  const unsigned jobs = std::max(1u, std::min<unsigned>(request.jobs ? request.jobs : std::thread::hardware_concurrency(),
                                                        static_cast<unsigned>(records.size())));
  std::vector<std::thread> threads;
  for (unsigned j = 0; j < jobs; ++j) threads.emplace_back(work);
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
  std::vector<IdaRow> rows;
  for (auto& r : per_record) {
    std::stable_sort(r.begin(), r.end(), [](const IdaRow& a, const IdaRow& b) { return a.im < b.im; });
    rows.insert(rows.end(), r.begin(), r.end());
  }
  return rows;
}

}  // namespace adjoin
