// Figures of a building run's folder (io/run_plots.hpp: plot_run hands building runs here):
// the floor profiles of the peaks, both buildings side by side, the roofs' and links'
// histories, and the contact pairs' gaps and forces with their impacts.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/run_plots.hpp"
#include "figure_text.hpp"

namespace adjoin {
using figure::read_summary_json;
using figure::force_unit;

namespace {

namespace fs = std::filesystem;

// Peaks of channel `prefix` + i for i = 1, 2, ... while the summary has them.
std::vector<double> profile(const nlohmann::json& peaks, const std::string& prefix) {
  std::vector<double> out;
  for (int i = 1;; ++i) {
    const std::string key = prefix + std::to_string(i);
    if (!peaks.contains(key) || !peaks[key].is_object() || !peaks[key].contains("max_abs") ||
        !peaks[key]["max_abs"].is_number())
      break;
    out.push_back(peaks[key]["max_abs"].get<double>());
  }
  return out;
}

std::vector<double> counting(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<double>(i + 1);
  return v;
}

// What the figures of a building run are drawn from.
struct BuildingRun {
  fs::path dir, summary_file;
  nlohmann::json summary;
  std::string scene;  // the title: the scene's name, and "(no links)" for a run without
};

// Peak displacement by floor and peak drift by storey, floors upwards.
std::string profiles_script(const BuildingRun& run) {
  const nlohmann::json& peaks = run.summary["peaks"];
  const std::string& scene = run.scene;
  const fs::path& summary_file = run.summary_file;
  std::ostringstream s;
  s << kGnuplotPreamble;
  std::vector<std::string> buildings;
  for (const char* b : {"A", "B"}) {
    const std::vector<double> x = profile(peaks, std::string(b) + ".x"), d = profile(peaks, std::string(b) + ".drift");
    if (x.empty()) continue;
    buildings.push_back(b);
    // Floor 0 (the ground) at zero displacement, then the floors.
    std::vector<double> floors = counting(x.size()), xs = x;
    floors.insert(floors.begin(), 0.0);
    xs.insert(xs.begin(), 0.0);
    gnuplot_datablock(s, std::string("x") + b, {xs, floors});
    gnuplot_datablock(s, std::string("d") + b, {d, counting(d.size())});
  }
  if (buildings.empty()) throw InputError(summary_file.string() + ": no floor peaks (A.x1, ...) in \"peaks\"");
  s << "set multiplot layout 1,2 title " << gnuplot_quote(scene + ": peak floor displacements and storey drifts")
    << " noenhanced font ',12' margins 0.08,0.97,0.2,0.92 spacing 0.09,0\n"
    << "set ytics 1\nset yrange [0:*]\nset xrange [0:*]\nset offsets 0, graph 0.08, 0.3, 0\n"
    << "set key at screen 0.5, screen 0.04 center horizontal\n"
    << "set xlabel 'peak displacement relative to the ground [m]'\nset ylabel 'floor'\nplot ";
  for (std::size_t k = 0; k < buildings.size(); ++k)
    s << (k ? ", " : "") << "$x" << buildings[k] << " using 1:2 with linespoints lt " << k + 1 << " title "
      << gnuplot_quote("building " + buildings[k]);
  s << "\nset xlabel 'peak storey drift [m]'\nset ylabel 'storey'\nset yrange [0.5:*]\nset xrange [0:*]\nplot ";
  for (std::size_t k = 0; k < buildings.size(); ++k)
    s << (k ? ", " : "") << "$d" << buildings[k] << " using 1:2 with linespoints lt " << k + 1 << " title "
      << gnuplot_quote("building " + buildings[k]);
  s << "\nunset multiplot\n";
  return s.str();
}

// Roof displacements and link forces against time.
std::string roofs_script(const BuildingRun& run, const CsvTable& ts, const std::vector<double>& t) {
  const nlohmann::json& peaks = run.summary["peaks"];
  const std::string& scene = run.scene;
  std::vector<std::string> roofs, links;
  for (const char* b : {"A", "B"}) {
    const std::size_t floors = profile(peaks, std::string(b) + ".x").size();
    if (floors > 0 && ts.has(std::string(b) + ".x" + std::to_string(floors))) roofs.push_back(std::string(b) + ".x" + std::to_string(floors));
  }
  for (int l = 1; ts.has("link" + std::to_string(l) + ".force"); ++l) links.push_back("link" + std::to_string(l) + ".force");
  std::ostringstream s;
  s << kGnuplotPreamble;
  std::vector<std::vector<double>> columns{t};
  for (const auto& r : roofs) columns.push_back(ts.numbers(r));
  for (const auto& l : links) columns.push_back(ts.numbers(l));
  gnuplot_datablock(s, "d", columns);
  s << "set multiplot layout " << (links.empty() ? 1 : 2) << ",1 title "
    << gnuplot_quote(scene + ": roof displacements" + (links.empty() ? "" : " and link forces")) << " noenhanced font ',12'"
    << " margins 0.1,0.74,0.1,0.92 spacing 0,0.12\n"
    << "set xrange [" << gnuplot_number(t.front()) << ":" << gnuplot_number(t.back()) << "]\n"
    << "set key outside right top vertical Left reverse noenhanced\n"
    << "set xlabel 'time t [s]'\nset ylabel 'roof displacement [m]'\nplot ";
  for (std::size_t k = 0; k < roofs.size(); ++k) {
    const std::string building = roofs[k].substr(0, 1), floor = roofs[k].substr(3);
    s << (k ? ", " : "") << "$d using 1:" << k + 2 << " with lines lt " << k + 1 << " title "
      << gnuplot_quote(building + ": roof, floor " + floor);
  }
  s << "\n";
  if (!links.empty()) {
    // Forces of buildings in kN or MN: tick labels that read at a glance.
    double peak = 0.0;
    for (std::size_t c = 1 + roofs.size(); c < columns.size(); ++c)
      for (double v : columns[c])
        if (std::isfinite(v)) peak = std::max(peak, std::abs(v));
    const auto [scale, unit] = force_unit(peak);
    s << "set ylabel " << gnuplot_quote("link force [" + unit + "]") << "\nplot ";
    for (std::size_t k = 0; k < links.size(); ++k)
      s << (k ? ", " : "") << "$d using 1:($" << roofs.size() + k + 2 << "/" << gnuplot_number(scale) << ") with lines lt "
        << k + 3 << " title " << gnuplot_quote("link " + links[k].substr(4, links[k].find('.') - 4));
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

// Contact pairs: gap and (with a contact law) contact force against time, each impact
// marked at its start (gap 0) and at its peak force (impacts.csv); a pair without a contact
// law marks the time from which the run is outside the model. Nothing without contact pairs.
std::string contacts_script(const BuildingRun& run, const CsvTable& ts, const std::vector<double>& t) {
  const nlohmann::json& j = run.summary;
  const std::string& scene = run.scene;
  const fs::path& dir = run.dir;
  std::vector<std::string> pairs;
  for (int k = 1; ts.has("contact" + std::to_string(k) + ".gap"); ++k) pairs.push_back("contact" + std::to_string(k));
  if (pairs.empty()) return "";
  // The force panel for runs with a contact law (they write impacts.csv); without one the
  // force is 0 throughout.
  const fs::path impacts_file = dir / "impacts.csv";
  bool forces = fs::exists(impacts_file);
  for (const auto& p : pairs) forces = forces && ts.has(p + ".force");
  std::ostringstream c;
  c << kGnuplotPreamble;
  std::vector<std::vector<double>> data{t};
  for (const auto& p : pairs) data.push_back(ts.numbers(p + ".gap"));
  if (forces)
    for (const auto& p : pairs) data.push_back(ts.numbers(p + ".force"));
  gnuplot_datablock(c, "c", data);
  // Impacts of each pair: start, then t_force_max and force_max.
  std::vector<bool> marked(pairs.size(), false);
  if (fs::exists(impacts_file)) {
    const CsvTable im = read_csv_table(impacts_file);
    const std::vector<double> which = im.numbers("contact"), start = im.numbers("t_start"), tf = im.numbers("t_force_max"),
                              f = im.numbers("force_max");
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      std::vector<double> s0, zero, t1, f1;
      for (std::size_t i = 0; i < which.size(); ++i)
        if (which[i] == static_cast<double>(k + 1)) {
          s0.push_back(start[i]);
          zero.push_back(0.0);
          t1.push_back(tf[i]);
          f1.push_back(f[i]);
        }
      if (s0.empty()) continue;
      marked[k] = true;
      gnuplot_datablock(c, "i" + std::to_string(k + 1), {s0, zero, t1, f1});
    }
  }
  // From summary.json: where the run leaves the model (a pair without a contact law).
  if (j.contains("outside_model_from") && j["outside_model_from"].is_number()) {
    const double from = j["outside_model_from"].get<double>();
    c << "set arrow from " << gnuplot_number(from) << ", graph 0 to " << gnuplot_number(from)
      << ", graph 1 nohead dt 2 lc rgb '#c0392b'\n"
      << "set label " << gnuplot_quote("outside the model from here (no contact law)") << " at "
      << gnuplot_number(from) << ", graph 0.06 offset 0.5,0 textcolor rgb '#c0392b' noenhanced\n";
  }
  c << "set multiplot layout " << (forces ? 2 : 1) << ",1 title "
    << gnuplot_quote(scene + ": contact gaps" + (forces ? " and forces" : "") +
                   (std::find(marked.begin(), marked.end(), true) != marked.end() ? ", impacts marked" : "")) << " noenhanced font ',12' margins 0.1,0.74,0.1,0.92 spacing 0,0.12\n"
    << "set xrange [" << gnuplot_number(t.front()) << ":" << gnuplot_number(t.back()) << "]\n"
    << "set key outside right top vertical Left reverse noenhanced\n"
    << "set xlabel 'time t [s]'\nset ylabel 'gap [m]'\nplot 0 with lines lc rgb '#888888' dt 3 notitle";
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    c << ", $c using 1:" << k + 2 << " with lines lt " << k + 1 << " noenhanced title " << gnuplot_quote(pairs[k] + ".gap");
    if (marked[k])
      c << ", $i" << k + 1 << " using 1:2 with points lt " << k + 1 << " pt 6 title " << gnuplot_quote(pairs[k] + " impacts");
  }
  c << "\n";
  if (forces) {
    c << "unset label\nunset arrow\n";
    if (j.contains("outside_model_from") && j["outside_model_from"].is_number()) {
      const double from = j["outside_model_from"].get<double>();
      c << "set arrow from " << gnuplot_number(from) << ", graph 0 to " << gnuplot_number(from)
        << ", graph 1 nohead dt 2 lc rgb '#c0392b'\n";
    }
    // Impact forces in kN or MN, as the link forces.
    double peak = 0.0;
    for (std::size_t col = 1 + pairs.size(); col < data.size(); ++col)
      for (double v : data[col])
        if (std::isfinite(v)) peak = std::max(peak, std::abs(v));
    const auto [scale, unit] = force_unit(peak);
    const std::string divisor = gnuplot_number(scale);
    c << "set ylabel " << gnuplot_quote("contact force [" + unit + "]") << "\nplot ";
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      c << (k ? ", " : "") << "$c using 1:($" << pairs.size() + k + 2 << "/" << divisor << ") with lines lt " << k + 1
        << " noenhanced title " << gnuplot_quote(pairs[k] + ".force");
      if (marked[k])
        c << ", $i" << k + 1 << " using 3:($4/" << divisor << ") with points lt " << k + 1 << " pt 7 title "
          << gnuplot_quote(pairs[k] + " peak forces");
    }
    c << "\n";
  }
  c << "unset multiplot\n";
  return c.str();
}

}  // namespace

bool is_building_run(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  if (!in) return false;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    return j.is_object() && j.contains("structure") && j.contains("peaks") && j["peaks"].contains("A.x1");
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

RunPlots plot_building_run(const fs::path& dir, const std::string& prefix, const PlotStyle& style) {
  BuildingRun run{dir, dir / "summary.json", {}, ""};
  run.summary = read_summary_json(run.summary_file);
  const nlohmann::json& j = run.summary;
  const std::string ext = plot_extension(style.format);
  // A run whose scene lost its links (--unset link, a sweep's "no damper" point) says so.
  const bool unlinked = j.contains("links") && j["links"].is_array() && j["links"].empty();
  run.scene = j.value("scene", dir.filename().string()) + (unlinked ? " (no links)" : "");
  RunPlots result;
  FigureSet figures;  // all inputs read and every figure drawn before any file is written
  auto target = [&](const std::string& name) { return fs::path(prefix + name + ext); };
  figures.draw(profiles_script(run), target("profiles"), style);

  // The histories, from timeseries.csv.
  const fs::path csv = dir / "timeseries.csv";
  if (!fs::exists(csv)) {
    result.notes.push_back("no " + csv.string() + " (output.timeseries = true writes it): the roof histories are not drawn");
    result.images = figures.commit();
    return result;
  }
  CsvTable ts = read_csv_table(csv);
  keep_time_window(ts, style);
  const std::vector<double> t = ts.numbers("t");
  figures.draw(roofs_script(run, ts, t), target("roofs"), style);
  if (const std::string script = contacts_script(run, ts, t); !script.empty()) figures.draw(script, target("contacts"), style);
  result.images = figures.commit();
  return result;
}

}  // namespace adjoin
