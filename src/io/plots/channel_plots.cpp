// Chosen channels of run folders against time, one panel each (io/run_plots.hpp:
// plot_run_channels): a two-block run's columns, or a building run's from the channel table.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "adjoin/core/parse_number.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/run_plots.hpp"
#include "adjoin/structure/channels.hpp"
#include "figure_text.hpp"

namespace adjoin {
using figure::read_summary_json;
using figure::force_unit;

namespace fs = std::filesystem;

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
    std::size_t n = 0;
    if (from >= text.size() || text.size() - from > 6 || !parse_count(std::string_view(text).substr(from), &n)) return -1;
    return static_cast<int>(n);
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
    return with_unit(std::string(q.label) + ", " + element, q.unit);
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
