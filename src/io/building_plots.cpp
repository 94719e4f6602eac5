// Figures of a building run's folder (io/plots.hpp: plot_run hands building runs here): the
// floor profiles of the peaks, both buildings side by side, the roofs' and links' histories,
// and the contact pairs' gaps and forces with their impacts.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adjoin/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/plots.hpp"

namespace adjoin {
// (plots.cpp) summary.json parsed; InputError naming the file if it is not JSON.
nlohmann::json read_summary_json(const std::filesystem::path& file);
}  // namespace adjoin

namespace adjoin {
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
  const fs::path summary_file = dir / "summary.json";
  const nlohmann::json j = read_summary_json(summary_file);
  const std::string ext = plot_extension(style.format);
  const std::string scene = j.value("scene", dir.filename().string());
  const nlohmann::json& peaks = j["peaks"];
  RunPlots result;
  FigureSet figures;  // all inputs read and every figure drawn before any file is written
  auto target = [&](const std::string& name) { return fs::path(prefix + name + ext); };

  // (1) Floor profiles: peak displacement by floor and peak drift by storey, floors upwards.
  {
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
      << " noenhanced font ',12'\n"
      << "set ytics 1\nset yrange [0:*]\nset offsets 0, graph 0.08, 0.3, 0\nset key bottom right\n"
      << "set xlabel 'peak displacement relative to the base [m]'\nset ylabel 'floor'\nplot ";
    for (std::size_t k = 0; k < buildings.size(); ++k)
      s << (k ? ", " : "") << "$x" << buildings[k] << " using 1:2 with linespoints lt " << k + 1 << " pt 7 title "
        << gnuplot_quote("building " + buildings[k]);
    s << "\nset xlabel 'peak storey drift [m]'\nset ylabel 'storey'\nset yrange [0.5:*]\nplot ";
    for (std::size_t k = 0; k < buildings.size(); ++k)
      s << (k ? ", " : "") << "$d" << buildings[k] << " using 1:2 with linespoints lt " << k + 1 << " pt 7 title "
        << gnuplot_quote("building " + buildings[k]);
    s << "\nunset multiplot\n";
    figures.draw(s.str(), target("profiles"), style);
  }

  // (2) Roof displacements and link forces against time, from timeseries.csv.
  const fs::path csv = dir / "timeseries.csv";
  if (!fs::exists(csv)) {
    result.notes.push_back("no " + csv.string() + " (output.timeseries = true writes it): the roof histories are not drawn");
    result.images = figures.commit();
    return result;
  }
  const CsvTable ts = read_csv_table(csv);
  const std::vector<double> t = ts.numbers("t");
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
    << gnuplot_quote(scene + ": roof displacements" + (links.empty() ? "" : " and link forces")) << " noenhanced font ',12'\n"
    << "set xrange [" << gnuplot_number(t.front()) << ":" << gnuplot_number(t.back()) << "]\nset key top right\n"
    << "set xlabel 'time t [s]'\nset ylabel 'roof displacement [m]'\nplot ";
  for (std::size_t k = 0; k < roofs.size(); ++k)
    s << (k ? ", " : "") << "$d using 1:" << k + 2 << " with lines lt " << k + 1 << " noenhanced title " << gnuplot_quote(roofs[k]);
  s << "\n";
  if (!links.empty()) {
    s << "set ylabel 'link force [N]'\nplot ";
    for (std::size_t k = 0; k < links.size(); ++k)
      s << (k ? ", " : "") << "$d using 1:" << roofs.size() + k + 2 << " with lines lt " << k + 3 << " noenhanced title "
        << gnuplot_quote(links[k]);
    s << "\n";
  }
  s << "unset multiplot\n";
  figures.draw(s.str(), target("roofs"), style);

  // (3) Contact pairs: gap and (with a contact law) contact force against time, each impact
  // marked at its start (gap 0) and at its peak force (impacts.csv); a pair without a contact
  // law marks the time from which the run is outside the model.
  std::vector<std::string> pairs;
  for (int k = 1; ts.has("contact" + std::to_string(k) + ".gap"); ++k) pairs.push_back("contact" + std::to_string(k));
  if (!pairs.empty()) {
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
                     (std::find(marked.begin(), marked.end(), true) != marked.end() ? ", impacts marked" : "")) << " noenhanced font ',12'\n"
      << "set xrange [" << gnuplot_number(t.front()) << ":" << gnuplot_number(t.back()) << "]\nset key top right\n"
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
      c << "set ylabel 'contact force [N]'\nplot ";
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        c << (k ? ", " : "") << "$c using 1:" << pairs.size() + k + 2 << " with lines lt " << k + 1 << " noenhanced title "
          << gnuplot_quote(pairs[k] + ".force");
        if (marked[k])
          c << ", $i" << k + 1 << " using 3:4 with points lt " << k + 1 << " pt 7 title " << gnuplot_quote(pairs[k] + " peak forces");
      }
      c << "\n";
    }
    c << "unset multiplot\n";
    figures.draw(c.str(), target("contacts"), style);
  }
  result.images = figures.commit();
  return result;
}

void plot_run_channels(const fs::path& dir, const std::vector<std::string>& channels, const fs::path& image,
                       const PlotStyle& style, const std::string& option) {
  constexpr std::size_t kMostPanels = 8;
  if (channels.empty()) throw InputError(option + ": expected one or more channel names, comma separated");
  if (channels.size() > kMostPanels)
    throw InputError(option + ": " + std::to_string(channels.size()) + " channels given; at most " +
                     std::to_string(kMostPanels) + " panels fit one figure");
  const fs::path csv = dir / "timeseries.csv";
  if (!fs::exists(csv))
    throw InputError(option + ": " + csv.string() + " does not exist (output.timeseries = true writes it)");
  const CsvTable ts = read_csv_table(csv);
  // Every name is checked before anything is drawn, so a typo names itself and lists the rest.
  for (const auto& name : channels) (void)ts.column(name, option);
  const std::vector<double> t = ts.numbers("t");
  if (t.empty()) throw InputError(csv.string() + ": no rows");
  std::vector<std::vector<double>> data{t};
  for (const auto& name : channels) data.push_back(ts.numbers(name));
  std::string scene = dir.filename().string();
  if (fs::exists(dir / "summary.json")) {
    const nlohmann::json j = read_summary_json(dir / "summary.json");
    if (j.is_object() && j.contains("scene") && j["scene"].is_string()) scene = j["scene"].get<std::string>();
  }
  std::ostringstream s;
  s << kGnuplotPreamble;
  gnuplot_datablock(s, "d", data);
  s << "set multiplot layout " << channels.size() << ",1 title " << gnuplot_quote(scene + ": chosen channels")
    << " noenhanced font ',12'\n"
    << "set xrange [" << gnuplot_number(t.front()) << ":" << gnuplot_number(t.back()) << "]\nset key top right\n"
    << "set format x ''\nunset xlabel\n";
  for (std::size_t k = 0; k < channels.size(); ++k) {
    if (k + 1 == channels.size()) s << "set format x '%g'\nset xlabel 'time t [s]'\n";
    s << "set ylabel " << gnuplot_quote(channels[k]) << " noenhanced\nplot $d using 1:" << k + 2 << " with lines lt "
      << k + 1 << " noenhanced title " << gnuplot_quote(channels[k]) << "\n";
  }
  s << "unset multiplot\n";
  render_gnuplot(s.str(), image, style);
}

}  // namespace adjoin
