// The figures of a two-block run's folder (io/run_plots.hpp; io/plots.hpp lists them): the
// seed paper's displacements, excitation and rod forces, the gap, the impacts with a contact
// law and the energy balance. Each figure is one function of the run's data, listed in one
// table (kRunFigures) in the order they are drawn.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/run_plots.hpp"
#include "figure_text.hpp"

namespace adjoin {
using figure::join;
using figure::read_summary_json;

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Interval {
  std::string state;
  double t0, t1;
};

struct RunData {
  std::string scene;
  bool si = false;
  std::vector<Interval> phases;
  std::optional<double> min_gap, t_min_gap, t_first_contact;
  CsvTable series;
};

// Axis-label units of one kind of quantity.
std::string unit(bool si, const std::string& si_unit) {
  return si ? " [" + si_unit + "]" : " (dimensionless)";
}

std::optional<double> json_number(const nlohmann::json& j, const char* a, const char* b) {
  if (!j.contains(a) || !j[a].is_object() || !j[a].contains(b) || !j[a][b].is_number()) return std::nullopt;
  return j[a][b].get<double>();
}

// A string member of a JSON object, or `fallback` when it is absent or not a string. (Not
// json::value, whose inlined type checks GCC 12 flags with -Wnull-dereference.)
std::string json_text(const nlohmann::json& j, const char* key, const std::string& fallback) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get_ref<const std::string&>() : fallback;
}

RunData load_run(const fs::path& dir, const PlotStyle& style) {
  if (!fs::is_directory(dir))
    throw InputError(dir.string() + ": not a folder (expected the output folder of `adjoin run`)");
  RunData run;
  const fs::path summary_file = dir / "summary.json";
  if (!fs::exists(summary_file))
    throw InputError(summary_file.string() + ": not found (expected the summary.json written by `adjoin run`)");
  const nlohmann::json j = read_summary_json(summary_file);
  if (!j.is_object()) throw InputError(summary_file.string() + ": expected a JSON object");
  run.scene = json_text(j, "scene", dir.filename().string());
  const std::string units = json_text(j, "units", "dimensionless");
  if (units != "SI" && units != "dimensionless")
    throw InputError(summary_file.string() + ": \"units\" is '" + units + "', expected \"SI\" or \"dimensionless\"");
  run.si = units == "SI";
  if (j.contains("phases") && j["phases"].is_array())
    for (const auto& p : j["phases"])
      if (p.is_object() && p.contains("t_start") && p.contains("t_end") && p["t_start"].is_number() &&
          p["t_end"].is_number())
        run.phases.push_back({json_text(p, "state", ""), p["t_start"].get<double>(), p["t_end"].get<double>()});
  run.min_gap = json_number(j, "pounding", "min_gap");
  run.t_min_gap = json_number(j, "pounding", "t_min_gap");
  run.t_first_contact = json_number(j, "pounding", "t_first_contact");

  run.series = read_csv_table(dir / "timeseries.csv",
                              "the timeseries.csv of `adjoin run`; the scene needs output.timeseries = true");
  for (const char* c : {"t", "x1", "x2", "v1", "v2", "f1", "f2", "q", "ag", "gap"})
    run.series.column(c, "needed for the run figures");
  keep_time_window(run.series, style);
  if (run.series.rows.size() < 2)
    throw InputError(run.series.file.string() + ": fewer than two rows (expected a time history)");
  // Phases from the CSV when the summary has none.
  if (run.phases.empty() && run.series.has("phase")) {
    const std::size_t c = run.series.column("phase");
    const std::vector<double> t = run.series.numbers("t");
    for (std::size_t i = 0; i < t.size(); ++i) {
      const std::string& s = run.series.rows[i][c];
      if (!run.phases.empty() && run.phases.back().state == s) run.phases.back().t1 = t[i];
      else run.phases.push_back({s, t[i], t[i]});
    }
  }
  return run;
}

// Light bands behind the data for the stick intervals (objects persist across multiplot panels).
std::string stick_bands(const std::vector<Interval>& phases) {
  std::ostringstream s;
  int n = 0;
  for (const Interval& p : phases)
    if (p.state == "stick" && p.t1 > p.t0)
      s << "set object " << 100 + n++ << " rect from " << gnuplot_number(p.t0) << ", graph 0 to " << gnuplot_number(p.t1)
        << ", graph 1 behind fillcolor rgb '#dfe7f2' fillstyle solid 1.0 noborder\n";
  return s.str();
}

bool has_stick(const std::vector<Interval>& phases) {
  return std::any_of(phases.begin(), phases.end(), [](const Interval& p) { return p.state == "stick" && p.t1 > p.t0; });
}

// The key's corner with the fewest data points under it (the key box is about 35 % of the
// width and 25 % of the height, here of the data's range widened by `pad` on each side).
std::string key_corner(const std::vector<double>& t, const std::vector<std::vector<double>>& ys, double pad = 0.06,
                       std::optional<std::pair<double, double>> fixed = std::nullopt) {
  double t0 = INFINITY, t1 = -INFINITY, lo = INFINITY, hi = -INFINITY;
  for (double v : t)
    if (std::isfinite(v)) t0 = std::min(t0, v), t1 = std::max(t1, v);
  for (const auto& y : ys)
    for (double v : y)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (fixed) lo = fixed->first, hi = fixed->second, pad = 0.0;
  if (!(t1 > t0) || !(hi >= lo)) return "top right";
  const double span = hi - lo > 0 ? hi - lo : 1.0;
  lo -= pad * span;
  hi += pad * span;
  const double h = hi - lo;
  const char* names[] = {"top right", "top left", "bottom right", "bottom left"};
  std::size_t best = 0, best_count = SIZE_MAX;
  for (std::size_t c = 0; c < 4; ++c) {
    const bool right = c % 2 == 0, top = c < 2;
    const double a = right ? t1 - 0.35 * (t1 - t0) : t0, b = right ? t1 : t0 + 0.35 * (t1 - t0);
    const double y0 = top ? hi - 0.25 * h : lo, y1 = top ? hi : lo + 0.25 * h;
    std::size_t count = 0;
    for (const auto& y : ys)
      for (std::size_t i = 0; i < t.size() && i < y.size(); ++i)
        if (t[i] >= a && t[i] <= b && y[i] >= y0 && y[i] <= y1) ++count;
    if (count < best_count) best = c, best_count = count;
  }
  return names[best];
}

const char* kStickKey = "keyentry with boxes fillstyle solid 1.0 noborder fillcolor rgb '#dfe7f2' title 'stick'";

std::string title_line(const std::string& scene, const std::string& what) {
  return "set title " + gnuplot_quote(scene + ": " + what) + " noenhanced font ',12'\n";
}

// What every figure of a run is drawn from: the run, its columns and the lines they share.
struct RunFigureData {
  fs::path dir;
  RunData run;
  bool si = false;
  std::vector<double> t, x1, x2, v1, v2, f1, f2, q, ag, gap, dv;  // dv = v1 - v2
  std::string xrange, tlabel, bands;  // the t axis, its label, the stick intervals' bands
  bool stick = false;
};

RunFigureData figure_data(const fs::path& dir, const PlotStyle& style) {
  RunFigureData d;
  d.dir = dir;
  d.run = load_run(dir, style);
  d.si = d.run.si;
  const CsvTable& ts = d.run.series;
  for (auto [column, values] : {std::pair{"t", &d.t}, {"x1", &d.x1}, {"x2", &d.x2}, {"v1", &d.v1}, {"v2", &d.v2},
                                 {"f1", &d.f1}, {"f2", &d.f2}, {"q", &d.q}, {"ag", &d.ag}, {"gap", &d.gap}})
    *values = ts.numbers(column);
  d.dv.resize(d.t.size());
  for (std::size_t i = 0; i < d.t.size(); ++i) d.dv[i] = d.v1[i] - d.v2[i];
  // The t axis spans the run exactly; the data get a little headroom above and below.
  d.xrange = "set xrange [" + gnuplot_number(d.t.front()) + ":" + gnuplot_number(d.t.back()) +
             "]\nset offsets 0, 0, graph 0.06, graph 0.06\n";
  d.tlabel = "set xlabel 'time t" + unit(d.si, "s") + "'\n";
  d.bands = stick_bands(d.run.phases);
  d.stick = has_stick(d.run.phases);
  return d;
}

// ---- the figures: each a script, or nothing when its input is not in the folder

// Two histories against t with the stick bands: `what` in the title, the y axis' label (its SI
// unit added in an SI scene) and each curve's title.
struct TwoCurves {
  const char* what;
  const char* ylabel;
  const char* si_unit;
  const std::vector<double>& first;
  const std::vector<double>& second;
  const char* first_title;
  const char* second_title;
  bool second_dashed;  // (two displacements overlap where the blocks stick)
};

std::string two_curves(const RunFigureData& d, const TwoCurves& f) {
  std::ostringstream s;
  s << kGnuplotPreamble;
  gnuplot_datablock(s, "d", {d.t, f.first, f.second});
  s << title_line(d.run.scene, f.what) << d.xrange << d.tlabel << "set ylabel '" << f.ylabel << unit(d.si, f.si_unit) << "'\n"
    << "set key " << key_corner(d.t, {f.first, f.second}) << "\n" << d.bands << "plot $d using 1:2 with lines lt 1 title '"
    << f.first_title << "', $d using 1:3 with lines lt 2" << (f.second_dashed ? " dt 2" : "") << " title '"
    << f.second_title << "'" << (d.stick ? std::string(", ") + kStickKey : "") << "\n";
  return s.str();
}

// x1 and x2 against t (the paper's Fig. 3 / 6).
std::optional<std::string> displacements(const RunFigureData& d) {
  return two_curves(d, {"block displacements relative to the base", "displacement x_1, x_2", "m", d.x1, d.x2, "x_1", "x_2", true});
}

// Ground acceleration, damper force, relative velocity: three panels on one t axis (Fig. 4 / 7).
std::optional<std::string> excitation(const RunFigureData& d) {
  const auto& run = d.run;
  const bool si = d.si;
  const auto& t = d.t;
  const auto& q = d.q;
  const auto& ag = d.ag;
  const auto& dv = d.dv;
  const auto& xrange = d.xrange;
  const auto& tlabel = d.tlabel;
  const auto& bands = d.bands;
  const bool stick = d.stick;
  const CsvTable& ts = run.series;
  double mu = 0.0;
  bool slip = false;
  if (ts.has("phase")) {
    const std::size_t c = ts.column("phase");
    for (std::size_t i = 0; i < t.size(); ++i)
      if (ts.rows[i][c].rfind("slip", 0) == 0 && std::isfinite(q[i])) {
        slip = true;
        mu = std::max(mu, std::abs(q[i]));
      }
  }
  std::ostringstream s;
  s << kGnuplotPreamble;
  gnuplot_datablock(s, "d", {t, ag, q, dv});
  s << "set multiplot layout 3,1 title " << gnuplot_quote(run.scene + ": excitation, damper force and relative velocity")
    << " noenhanced font ',12' margins 0.11,0.97,0.09,0.91 spacing 0,0.025\n"
    << xrange << bands << "set key " << key_corner(t, {ag}) << "\n"
    << "set format x ''\nunset xlabel\n"
    << "set ylabel 'a_g" << unit(si, "m/s²") << "'\n"
    << "plot $d using 1:2 with lines lt 7 title 'ground acceleration a_g'"
    << (stick ? std::string(", ") + kStickKey : "") << "\n"
    << "set ylabel 'q" << unit(si, "N") << "'\n";
  if (slip && mu > 0.0) {
    s << "set key " << key_corner(t, {q}, 0.0, std::pair{-1.35 * mu, 1.35 * mu}) << "\nset yrange [" << gnuplot_number(-1.35 * mu) << ":" << gnuplot_number(1.35 * mu) << "]\n"
      << "plot $d using 1:3 with lines lt 2 title 'damper force q', " << gnuplot_number(mu)
      << " with lines lc rgb '#888888' dt 3 lw 1.5 title '±μ', " << gnuplot_number(-mu)
      << " with lines lc rgb '#888888' dt 3 lw 1.5 notitle\n"
      << "set autoscale y\n";
  } else {
    s << "set key " << key_corner(t, {q}) << "\nplot $d using 1:3 with lines lt 2 title 'damper force q'\n";
  }
  s << "set key " << key_corner(t, {dv}) << "\nset format x '%g'\n" << tlabel << "set ylabel 'v_1 − v_2" << unit(si, "m/s") << "'\n"
    << "plot $d using 1:4 with lines lt 1 title 'relative velocity v_1 − v_2', 0 with lines lc rgb '#888888' "
       "lw 1 notitle\n"
    << "unset multiplot\n";
  return s.str();
}

// f1 and f2 against t (Fig. 5 / 8).
std::optional<std::string> rod_forces(const RunFigureData& d) {
  return two_curves(d, {"forces in the viscoelastic rods", "rod force f_1, f_2", "N", d.f1, d.f2, "f_1 (rod 1)", "f_2 (rod 2)", false});
}

// The gap with its minimum and the contact line.
std::optional<std::string> gap_figure(const RunFigureData& d) {
  const auto& run = d.run;
  const bool si = d.si;
  const auto& t = d.t;
  const auto& gap = d.gap;
  const auto& xrange = d.xrange;
  const auto& tlabel = d.tlabel;
  double lo = 0.0, hi = 0.0;
  for (double g : gap)
    if (std::isfinite(g)) hi = std::max(hi, g), lo = std::min(lo, g);
  std::ostringstream s;
  s << kGnuplotPreamble;
  gnuplot_datablock(s, "d", {t, gap});
  s << title_line(run.scene, "gap between the blocks (pounding margin)") << xrange << tlabel
    << "set ylabel 'gap ξ" << unit(si, "m") << "'\n"
    << "set yrange [" << gnuplot_number(lo - 0.08 * (hi - lo)) << ":" << gnuplot_number(hi + 0.15 * (hi - lo)) << "]\n"
    << "set key " << key_corner(t, {gap, std::vector<double>(t.size(), 0.0)}, 0.0,
                                std::pair{lo - 0.08 * (hi - lo), hi + 0.15 * (hi - lo)}) << "\n";
  std::string extra;
  if (run.min_gap && run.t_min_gap) {
    char label[160];
    std::snprintf(label, sizeof label, "min ξ = %.4g at t = %.4g%s", *run.min_gap, *run.t_min_gap, si ? " s" : "");
    s << "$m << EOD\n" << gnuplot_number(*run.t_min_gap) << " " << gnuplot_number(*run.min_gap) << "\nEOD\n";
    extra += ", $m using 1:2 with points pt 7 ps 1.6 lc rgb '#d0451b' title " + gnuplot_quote(label);
  }
  if (run.t_first_contact)
    s << "set arrow from " << gnuplot_number(*run.t_first_contact) << ", graph 0 to " << gnuplot_number(*run.t_first_contact)
      << ", graph 1 nohead lc rgb '#b00000' dt 2 lw 1.5\n"
      << "set label 'first contact' at " << gnuplot_number(*run.t_first_contact) << ", graph 0.95 offset 0.5,0 tc rgb '#b00000'\n";
  s << "plot $d using 1:2 with lines lt 1 title 'ξ = ξ_0 + x_2 − x_1', 0 with lines lc rgb '#b00000' lw 1.5 "
       "title 'contact (ξ = 0)'"
    << extra << "\n";
  return s.str();
}

// Pounding with a contact law (impacts.csv): the gap and the contact force on one t axis,
// each impact marked (a band from its start to its end, and its peak force).
std::optional<std::string> contact(const RunFigureData& d) {
  const auto& dir = d.dir;
  const auto& run = d.run;
  const bool si = d.si;
  const auto& t = d.t;
  const auto& gap = d.gap;
  const auto& xrange = d.xrange;
  const auto& tlabel = d.tlabel;
  const CsvTable& ts = run.series;
  const fs::path impacts_file = dir / "impacts.csv";
  if (!fs::exists(impacts_file)) return std::nullopt;
  const CsvTable im = read_csv_table(impacts_file);
  const std::string context = "the impacts of `adjoin run` with a contact law";
  const std::vector<double> start = im.numbers("t_start", context), duration = im.numbers("duration", context),
                            peak = im.numbers("force_max", context), t_peak = im.numbers("t_force_max", context);
  const bool force = ts.has("fc");
  std::vector<double> fc = force ? ts.numbers("fc") : std::vector<double>(t.size(), 0.0);
  std::ostringstream s;
  s << kGnuplotPreamble;
  gnuplot_datablock(s, "d", {t, gap, fc});
  if (!start.empty()) gnuplot_datablock(s, "p", {t_peak, peak, start});
  s << "set multiplot layout 2,1 title "
    << gnuplot_quote(run.scene + ": pounding, " + std::to_string(start.size()) +
                     (start.size() == 1 ? " impact" : " impacts"))
    << " noenhanced font ',12' margins 0.11,0.97,0.09,0.91 spacing 0,0.025\n"
    << xrange;
  // The impacts as light bands behind both panels (a Newton impact, of no duration, as a line).
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (!std::isfinite(start[i])) continue;
    const double width = std::isfinite(duration[i]) ? duration[i] : 0.0;
    if (width > 0.0)
      s << "set object " << 10000 + i << " rect from " << gnuplot_number(start[i]) << ", graph 0 to " << gnuplot_number(start[i] + width)
        << ", graph 1 behind fillcolor rgb '#f4d6cc' fillstyle solid 1.0 noborder\n";
    else
      s << "set arrow " << 10000 + i << " from " << gnuplot_number(start[i]) << ", graph 0 to " << gnuplot_number(start[i])
        << ", graph 1 nohead lc rgb '#e08a6e' lw 1\n";
  }
  s << "set format x ''\nunset xlabel\nset key " << key_corner(t, {gap, std::vector<double>(t.size(), 0.0)}) << "\n"
    << "set ylabel 'gap ξ" << unit(si, "m") << "'\n"
    << "plot $d using 1:2 with lines lt 1 title 'ξ = ξ_0 + x_2 − x_1', 0 with lines lc rgb '#b00000' lw 1.5 "
       "title 'contact (ξ = 0)'";
  if (!start.empty())
    s << ", $p using 3:(0) with points pt 9 ps 1.2 lc rgb '#d0451b' title 'first touch'";
  s << "\nset key " << key_corner(t, {fc}) << "\nset format x '%g'\n" << tlabel
    << "set ylabel 'contact force f_c" << unit(si, "N") << "'\n"
    << "plot $d using 1:3 with lines lt 2 title " << gnuplot_quote(force ? "contact force f_c" : "contact force (not in timeseries.csv)");
  if (!start.empty()) s << ", $p using 1:2 with points pt 7 ps 1.2 lc rgb '#d0451b' title 'peak of each impact'";
  s << "\nunset multiplot\n";
  return s.str();
}

// Cumulative energy shares, when an energy history is there.
std::optional<std::string> energy(const RunFigureData& d) {
  const bool si = d.si;
  const RunData& run = d.run;
  const fs::path energy_file = d.dir / "energy.csv";
  if (!fs::exists(energy_file)) return std::nullopt;
  const CsvTable e = read_csv_table(energy_file);
  const std::vector<double> te = e.numbers("t", "time of the energy history");
  std::vector<std::vector<double>> columns{te};
  std::vector<std::string> names;
  std::vector<double> sum(te.size(), 0.0);
  const std::vector<std::pair<const char*, const char*>> parts{
      {"kinetic", "kinetic"}, {"rod1", "rod 1"}, {"rod2", "rod 2"}, {"friction", "friction (damper)"},
      {"contact", "contact (pounding)"}};
  // Final shares of the input energy, for the key.
  double input_final = kNaN;
  if (e.has("input"))
    for (double v : e.numbers("input"))
      if (std::isfinite(v)) input_final = v;
  for (const auto& [column, label] : parts) {
    if (!e.has(column)) continue;
    const std::vector<double> v = e.numbers(column);
    double last = kNaN;
    for (std::size_t i = 0; i < sum.size(); ++i) {
      sum[i] += std::isfinite(v[i]) ? v[i] : 0.0;
      if (std::isfinite(v[i])) last = v[i];
    }
    columns.push_back(sum);
    std::string name = label;
    if (input_final > 0.0 && std::isfinite(last)) {
      char share[48];
      std::snprintf(share, sizeof share, " (%.0f %% at the end)", 100.0 * last / input_final);
      name += share;
    }
    names.push_back(name);
  }
  if (names.empty() && !e.has("input"))
    throw InputError(energy_file.string() + ": no energy columns (expected t and some of input, kinetic, rod1, "
                                            "rod2, friction, residual); the columns are: " + join(e.columns, ", "));
  std::ostringstream s;
  s << kGnuplotPreamble;
  const bool input = e.has("input");
  if (input) columns.push_back(e.numbers("input"));
  gnuplot_datablock(s, "e", columns);
  s << title_line(run.scene, "energy balance (cumulative shares)")
    << "set xlabel 'time t" << unit(si, "s") << "'\n"
    << "set ylabel '" << (si ? "energy [J]" : "energy per unit m_1 (dimensionless)") << "'\n"
    << "set key top left\nset style fill solid 0.75 noborder\n";
  // Headroom above the curves for the key.
  double top = 0.0;
  for (std::size_t c = 1; c < columns.size(); ++c)
    for (double v : columns[c])
      if (std::isfinite(v)) top = std::max(top, v);
  if (top > 0.0) s << "set yrange [*:" << gnuplot_number(1.4 * top) << "]\n";
  s << "plot ";
  for (std::size_t k = 0; k < names.size(); ++k)
    s << (k ? ", " : "") << "$e using 1:" << (k == 0 ? std::string("(0)") : std::to_string(k + 1)) << ":"
      << k + 2 << " with filledcurves lt " << k + 1 << " title " << gnuplot_quote(names[k]);
  if (input)
    s << (names.empty() ? "" : ", ") << "$e using 1:" << names.size() + 2
      << " with lines lc rgb 'black' lw 2 title 'input'";
  s << "\n";
  return s.str();
}

struct RunFigure {
  const char* name;  // the image's name: prefix + name + extension
  std::optional<std::string> (*script)(const RunFigureData&);
};
constexpr RunFigure kRunFigures[] = {
    {"displacements", displacements}, {"excitation", excitation}, {"rod-forces", rod_forces},
    {"gap", gap_figure},              {"contact", contact},       {"energy", energy},
};

}  // namespace

RunPlots plot_run(const fs::path& dir, const std::string& prefix, const PlotStyle& style) {
  if (fs::is_directory(dir) && is_building_run(dir)) return plot_building_run(dir, prefix, style);
  const RunFigureData data = figure_data(dir, style);
  const std::string ext = plot_extension(style.format);
  RunPlots result;
  FigureSet figures;  // all inputs read and every figure drawn before any file is written
  for (const RunFigure& figure : kRunFigures)
    if (const auto script = figure.script(data)) figures.draw(*script, fs::path(prefix + figure.name + ext), style);
  const fs::path energy_file = dir / "energy.csv";
  if (!fs::exists(energy_file)) result.notes.push_back("no energy figure: " + energy_file.string() + " does not exist");
  result.images = figures.commit();
  return result;
}

}  // namespace adjoin
