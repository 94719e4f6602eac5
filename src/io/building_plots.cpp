// Figures of a building run's folder (io/plots.hpp: plot_run hands building runs here): the
// floor profiles of the peaks, both buildings side by side, the roofs' and links' histories,
// and the contact pairs' gaps and forces with their impacts.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <tuple>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/plots.hpp"
#include "adjoin/structure/channels.hpp"

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

// A force axis in N, kN or MN by the largest value: the divisor and the unit.
std::pair<double, std::string> force_unit(double peak) {
  if (peak >= 1e6) return {1e6, "MN"};
  if (peak >= 1e3) return {1e3, "kN"};
  return {1.0, "N"};
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
  // A run whose scene lost its links (--unset link, a sweep's "no damper" point) says so.
  const bool unlinked = j.contains("links") && j["links"].is_array() && j["links"].empty();
  const std::string scene = j.value("scene", dir.filename().string()) + (unlinked ? " (no links)" : "");
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
    figures.draw(s.str(), target("profiles"), style);
  }

  // (2) Roof displacements and link forces against time, from timeseries.csv.
  const fs::path csv = dir / "timeseries.csv";
  if (!fs::exists(csv)) {
    result.notes.push_back("no " + csv.string() + " (output.timeseries = true writes it): the roof histories are not drawn");
    result.images = figures.commit();
    return result;
  }
  CsvTable ts = read_csv_table(csv);
  keep_time_window(ts, style);
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
    figures.draw(c.str(), target("contacts"), style);
  }
  result.images = figures.commit();
  return result;
}

namespace {

// "m/s^2" as it reads on an axis.
std::string pretty_unit(const std::string& unit) { return unit == "m/s^2" ? "m/s²" : unit; }

// What a time-series column is and its SI unit: a building's channels from the channel table
// (structure/channels.hpp), a two-block run's from its own list; else the name, no unit.
struct ChannelText {
  std::string what, unit;
};
ChannelText channel_text(const std::string& name) {
  using structure::ChannelScope;
  using structure::Quantity;
  auto with_unit = [](const std::string& label, const std::string& unit) { return ChannelText{label, pretty_unit(unit)}; };
  static const std::vector<std::tuple<const char*, const char*, const char*>> two_block{
      {"x1", "displacement x_1", "m"}, {"x2", "displacement x_2", "m"},  {"v1", "velocity v_1", "m/s"},
      {"v2", "velocity v_2", "m/s"},   {"f1", "rod force f_1", "N"},     {"f2", "rod force f_2", "N"},
      {"q", "damper force q", "N"},    {"ag", "ground acceleration a_g", "m/s^2"}, {"gap", "gap ξ", "m"},
      {"fc", "contact force f_c", "N"}};
  for (const auto& [column, label, unit] : two_block)
    if (name == column) return with_unit(label, unit);
  const auto dot = name.find('.');
  if (dot == std::string::npos) return {name, ""};
  const std::string head = name.substr(0, dot), tail = name.substr(dot + 1);
  auto number_after = [](const std::string& text, std::size_t from) -> int {
    const auto digit = [](char c) { return c >= '0' && c <= '9'; };  // (isdigit on a UTF-8 byte is undefined)
    if (from >= text.size() || !std::all_of(text.begin() + static_cast<long>(from), text.end(), digit) ||
        text.size() - from > 6)
      return -1;
    return std::stoi(text.substr(from));
  };
  for (const auto& q : structure::quantities()) {
    const std::string stem = q.stem, suffix = q.suffix;
    std::string element;
    if ((q.scope == ChannelScope::floor || q.scope == ChannelScope::storey) && (head == "A" || head == "B") &&
        tail.rfind(stem, 0) == 0 && tail.size() > stem.size() + suffix.size() &&
        tail.compare(tail.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const int i = number_after(tail.substr(0, tail.size() - suffix.size()), stem.size());
      if (i < 0) continue;
      element = (q.scope == ChannelScope::floor ? "floor " : "storey ") + std::to_string(i) + ", building " + head;
    } else if (q.scope == ChannelScope::building && (head == "A" || head == "B") && tail == stem) {
      element = "building " + head;
    } else if ((q.scope == ChannelScope::link || q.scope == ChannelScope::contact) && tail == stem) {
      const std::string kind = q.scope == ChannelScope::link ? "link" : "contact";
      const int k = head.rfind(kind, 0) == 0 ? number_after(head, kind.size()) : -1;
      if (k < 0) continue;
      element = (kind == "link" ? "link " : "contact pair ") + std::to_string(k);
    } else {
      continue;
    }
    static const std::map<Quantity, const char*> what{
        {Quantity::displacement, "displacement"},       {Quantity::absolute_acceleration, "absolute acceleration"},
        {Quantity::drift, "drift"},                     {Quantity::storey_shear, "shear"},
        {Quantity::base_shear, "base shear"},           {Quantity::link_force, "force"},
        {Quantity::link_stroke, "stroke"},              {Quantity::contact_gap, "gap"},
        {Quantity::contact_force, "force"}};
    return with_unit(std::string(what.at(q.quantity)) + ", " + element, q.unit);
  }
  return {name, ""};
}

struct ChannelRun {
  fs::path dir;
  std::string scene;
  bool si = true;
  CsvTable series;
};

ChannelRun load_channel_run(const fs::path& dir, const std::vector<std::string>& channels, const PlotStyle& style,
                            const std::string& option) {
  ChannelRun run{dir, dir.filename().string(), true, {}};
  if (run.scene.empty()) run.scene = dir.parent_path().filename().string();
  const fs::path csv = dir / "timeseries.csv";
  if (!fs::exists(csv))
    throw InputError(option + ": " + csv.string() + " does not exist (output.timeseries = true writes it)");
  run.series = read_csv_table(csv);
  // Every name is checked before anything is drawn, so a typo names itself and lists the rest.
  for (const auto& name : channels) (void)run.series.column(name, option);
  keep_time_window(run.series, style);
  if (fs::exists(dir / "summary.json")) {
    const nlohmann::json j = read_summary_json(dir / "summary.json");
    if (j.is_object() && j.contains("scene") && j["scene"].is_string()) run.scene = j["scene"].get<std::string>();
    if (j.is_object() && j.contains("units") && j["units"].is_string()) run.si = j["units"].get<std::string>() != "dimensionless";
    if (j.is_object() && j.contains("structure") && j.contains("links") && j["links"].is_array() && j["links"].empty())
      run.scene += " (no links)";
  }
  return run;
}

}  // namespace

void plot_runs_channels(const std::vector<fs::path>& dirs, const std::vector<std::string>& channels,
                        const fs::path& image, const PlotStyle& style, const std::string& option) {
  constexpr std::size_t kMostPanels = 8, kMostRuns = 24;
  if (channels.empty()) throw InputError(option + ": expected one or more channel names, comma separated");
  if (channels.size() > kMostPanels)
    throw InputError(option + ": " + std::to_string(channels.size()) + " channels given; at most " +
                     std::to_string(kMostPanels) + " panels fit one figure");
  if (dirs.size() > kMostRuns)
    throw InputError(std::to_string(dirs.size()) + " run folders given; at most " + std::to_string(kMostRuns) +
                     " curves per panel can be told apart");
  std::vector<ChannelRun> runs;
  for (const auto& dir : dirs) runs.push_back(load_channel_run(dir, channels, style, option));
  std::ostringstream s;
  s << kGnuplotPreamble;
  double t0 = INFINITY, t1 = -INFINITY;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    std::vector<std::vector<double>> data{runs[r].series.numbers("t")};
    for (const auto& name : channels) data.push_back(runs[r].series.numbers(name));
    t0 = std::min(t0, data[0].front());
    t1 = std::max(t1, data[0].back());
    gnuplot_datablock(s, "r" + std::to_string(r), data);
  }
  const bool overlay = runs.size() > 1;
  // Two runs a key row when two labels fit side by side (about 9 pixels a character at the
  // figures' font, 60 for the sample line), else one a row.
  std::size_t longest = 0;
  for (const auto& run : runs) longest = std::max(longest, run.scene.size() + run.dir.filename().string().size() + 3);
  const bool two_columns = 2.0 * (9.0 * static_cast<double>(longest) + 60.0) < 0.85 * style.width;
  const std::size_t key_rows = two_columns ? (runs.size() + 1) / 2 : runs.size();
  // Legend entries: the scene and its folder (two runs of one scene differ by folder).
  auto run_label = [&](const ChannelRun& run) {
    return overlay ? run.scene + " (" + run.dir.filename().string() + ")" : run.scene;
  };
  const std::string title = overlay ? "chosen channels of " + std::to_string(runs.size()) + " runs"
                                    : runs[0].scene + ": chosen channels";
  s << "set multiplot layout " << channels.size() << ",1 title " << gnuplot_quote(title) << " noenhanced font ',12'"
    << (overlay ? " margins 0.12,0.97," + gnuplot_number(0.12 + 0.035 * static_cast<double>(key_rows)) + ",0.92 spacing 0,0.03" : "")
    << "\n"
    << "set xrange [" << gnuplot_number(t0) << ":" << gnuplot_number(t1) << "]\n"
    // An overlay's key under the panels, two runs a row: long folder names need the width.
    << (overlay ? "set key at screen 0.5, screen 0.005 center bottom horizontal maxcols 2 maxrows " +
                      std::to_string(key_rows) + " Left reverse noenhanced\n"
                : std::string("unset key\n"))
    << "set format x ''\nunset xlabel\n";
  // Each panel: the column's name and unit on the axis, what it is in the panel's corner;
  // forces in kN or MN when large.
  s << "set style textbox opaque noborder\n";
  for (std::size_t k = 0; k < channels.size(); ++k) {
    if (k + 1 == channels.size()) s << "set format x '%g'\nset xlabel 'time t" << (runs[0].si ? " [s]'" : " (dimensionless)'") << "\n";
    if (overlay && k == 1) s << "unset key\n";
    std::vector<double> all;
    for (const auto& run : runs) {
      const std::vector<double> v = run.series.numbers(channels[k]);
      all.insert(all.end(), v.begin(), v.end());
    }
    ChannelText text = channel_text(channels[k]);
    double scale = 1.0;
    if (text.unit == "N" && runs[0].si) {
      double peak = 0.0;
      for (double v : all)
        if (std::isfinite(v)) peak = std::max(peak, std::abs(v));
      std::tie(scale, text.unit) = force_unit(peak);
      for (double& v : all) v /= scale;
    }
    const std::string unit = text.unit.empty() ? "" : runs[0].si ? " [" + text.unit + "]" : " (dimensionless)";
    s << gnuplot_tick_format("y", all) << gnuplot_tick_step("y", all) << "set ylabel " << gnuplot_quote(channels[k] + unit) << " noenhanced\n"
      << "set label 1 " << gnuplot_quote(text.what + unit) << " at graph 0.01, graph 0.9 left front boxed noenhanced font ',9'\n"
      << "plot ";
    for (std::size_t r = 0; r < runs.size(); ++r)
      s << (r ? ", " : "") << "$r" << r << " using 1:($" << k + 2 << "/" << gnuplot_number(scale) << ") with lines lt "
        << (overlay ? r : k) % 12 + 1 << " dt " << (overlay ? r / 12 + 1 : 1) << " title "
        << gnuplot_quote(overlay ? run_label(runs[r]) : channels[k]) << " noenhanced";
    s << "\n";
  }
  s << "unset multiplot\n";
  render_gnuplot(s.str(), image, style);
}

void plot_run_channels(const fs::path& dir, const std::vector<std::string>& channels, const fs::path& image,
                       const PlotStyle& style, const std::string& option) {
  plot_runs_channels({dir}, channels, image, style, option);
}

}  // namespace adjoin
