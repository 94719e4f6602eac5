#include "adjoin/io/plots.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/gnuplot.hpp"

namespace adjoin {
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// Splits one CSV line; false if a quoted field is not closed.
bool split_csv_line(const std::string& line, std::vector<std::string>* fields) {
  fields->clear();
  std::string field;
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        field += c;
      }
    } else if (c == '"' && trim(field).empty()) {
      quoted = was_quoted = true;
      field.clear();
    } else if (c == ',') {
      fields->push_back(was_quoted ? field : trim(field));
      field.clear();
      was_quoted = false;
    } else {
      field += c;
    }
  }
  if (quoted) return false;
  fields->push_back(was_quoted ? field : trim(field));
  return true;
}

bool parse_double(const std::string& text, double* value) {
  const std::string t = trim(text);
  if (t.empty()) return false;
  const char* first = t.data();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, t.data() + t.size(), *value);
  return ec == std::errc() && ptr == t.data() + t.size();
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? separator : "") + items[i];
  return s;
}

// (Shared with the building figures: io/gnuplot.hpp.)
std::string num(double v) { return gnuplot_number(v); }
void datablock(std::ostringstream& script, const std::string& name, const std::vector<std::vector<double>>& columns) {
  gnuplot_datablock(script, name, columns);
}
const char* const kPreamble = kGnuplotPreamble;

// Every CSV read for a figure goes through here so missing files name themselves.
CsvTable must_read(const fs::path& file, const std::string& what) {
  if (!fs::exists(file)) throw InputError(file.string() + ": not found (expected " + what + ")");
  return read_csv_table(file);
}

}  // namespace

// ---------------------------------------------------------------- CSV tables

bool CsvTable::has(const std::string& name) const {
  return std::find(columns.begin(), columns.end(), name) != columns.end();
}

std::size_t CsvTable::column(const std::string& name, const std::string& context) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end())
    throw InputError(file.string() + ": no column '" + name + "'" + (context.empty() ? "" : " (" + context + ")") +
                     "; the columns are: " + join(columns, ", "));
  return static_cast<std::size_t>(it - columns.begin());
}

std::vector<double> CsvTable::numbers(const std::string& name, const std::string& context) const {
  const std::size_t c = column(name, context);
  std::vector<double> values(rows.size(), kNaN);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string cell = trim(rows[i][c]);
    if (cell.empty() || cell == "nan" || cell == "NaN" || cell == "-" || cell == "null") continue;
    if (cell == "true" || cell == "false") {  // flags such as a sweep's `contact` plot as 1 / 0
      values[i] = cell == "true" ? 1.0 : 0.0;
      continue;
    }
    if (!parse_double(cell, &values[i]))
      throw InputError(file.string() + ":" + std::to_string(lines[i]) + ": column '" + name + "' holds '" + cell +
                       "', expected a number");
  }
  return values;
}

CsvTable read_csv_table(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open (expected a CSV file with a header line)");
  CsvTable table;
  table.file = file;
  std::string line;
  std::size_t number = 0;
  std::vector<std::string> fields;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 byte-order mark
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    if (!split_csv_line(line, &fields))
      throw InputError(file.string() + ":" + std::to_string(number) + ": unterminated quoted field");
    if (table.columns.empty()) {
      for (const std::string& f : fields)
        if (f.empty())
          throw InputError(file.string() + ":" + std::to_string(number) +
                           ": empty column name in the header (expected a header line naming every column)");
      table.columns = fields;
      continue;
    }
    if (fields.size() != table.columns.size())
      throw InputError(file.string() + ":" + std::to_string(number) + ": " + std::to_string(fields.size()) +
                       " fields, expected " + std::to_string(table.columns.size()) + " as in the header");
    table.rows.push_back(fields);
    table.lines.push_back(number);
  }
  if (table.columns.empty()) throw InputError(file.string() + ": empty file (expected a CSV file with a header line)");
  return table;
}

// ---------------------------------------------------------------- options

std::string plot_extension(const std::string& format, const std::string& option) {
  if (format == "png") return ".png";
  if (format == "svg") return ".svg";
  throw InputError(option + " " + format + ": unknown format (expected png or svg)");
}

void parse_plot_size(const std::string& text, PlotStyle* style, const std::string& option) {
  const auto x = text.find_first_of("xX");
  double w = 0.0, h = 0.0;
  if (x == std::string::npos || !parse_double(text.substr(0, x), &w) || !parse_double(text.substr(x + 1), &h) ||
      w != std::floor(w) || h != std::floor(h) || w < 100 || h < 100 || w > 10000 || h > 10000)
    throw InputError(option + " " + text + ": expected WIDTHxHEIGHT in pixels, e.g. 900x600 (100 to 10000 each)");
  style->width = static_cast<int>(w);
  style->height = static_cast<int>(h);
}

fs::path plot_target(const std::string& out, const fs::path& fallback, const std::string& explicit_format,
                     PlotStyle* style, const std::string& option) {
  if (!explicit_format.empty()) plot_extension(explicit_format);
  if (out.empty()) {
    if (!explicit_format.empty()) style->format = explicit_format;
    fs::path p = fallback;
    p.replace_extension(plot_extension(style->format));
    return p;
  }
  const std::string ext = fs::path(out).extension().string();
  if (ext != ".png" && ext != ".svg")
    throw InputError(option + " " + out + ": expected a file name ending in .png or .svg");
  const std::string format = ext.substr(1);
  if (!explicit_format.empty() && explicit_format != format)
    throw InputError(option + " " + out + " and --format " + explicit_format + " disagree (expected the same image format)");
  style->format = format;
  // The image's folder is checked now, before the command does its work: a plot that cannot
  // be written is bad input (exit 2), found up front rather than after a long computation.
  fs::path folder = fs::path(out).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw InputError(option + " " + out + ": the folder " + folder.string() + " does not exist (create it first)");
  if (::access(folder.c_str(), W_OK) != 0)
    throw InputError(option + " " + out + ": the folder " + folder.string() + " is not writable");
  if (fs::is_directory(out, ec)) throw InputError(option + " " + out + ": is a folder; expected an image file name");
  return out;
}

void parse_time_window(const std::string& text, PlotStyle* style, const std::string& option) {
  const auto colon = text.find(':');
  double from = 0.0, to = 0.0;
  std::string excerpt = text.substr(0, 40);
  for (char& c : excerpt)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  if (colon == std::string::npos || !parse_double(text.substr(0, colon), &from) ||
      !parse_double(text.substr(colon + 1), &to) || !std::isfinite(from) || !std::isfinite(to))
    throw InputError(option + " '" + excerpt + (text.size() > 40 ? "...'" : "'") +
                     ": expected T0:T1, two times in seconds (e.g. 5:15)");
  if (!(from < to))
    throw InputError(option + " '" + excerpt + "': expected T0 < T1 (a window of some length)");
  style->window = std::pair{from, to};
}

void keep_time_window(CsvTable& series, const PlotStyle& style) {
  if (!style.window) return;
  const auto [from, to] = *style.window;
  const std::vector<double> t = series.numbers("t", "the time of a time history");
  CsvTable kept = series;
  kept.rows.clear();
  kept.lines.clear();
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= from && t[i] <= to) {
      kept.rows.push_back(series.rows[i]);
      kept.lines.push_back(series.lines[i]);
    }
  if (kept.rows.size() < 2) {
    const std::string span = t.empty() ? "no rows" : "t from " + num(t.front()) + " to " + num(t.back());
    throw InputError("--window " + num(from) + ":" + num(to) + ": " + std::to_string(kept.rows.size()) + " row(s) of " +
                     series.file.string() + " in the window (it has " + span + "); expected at least 2");
  }
  series = std::move(kept);
}

// ---------------------------------------------------------------- gnuplot

namespace {

// The terminal line for the image's format at the style's size.
std::string terminal_line(const fs::path& image, const PlotStyle& style, std::string* format) {
  const std::string ext = image.extension().string();
  const std::string size = std::to_string(style.width) + "," + std::to_string(style.height);
  if (ext == ".png") {
    *format = "png";
    return "set terminal pngcairo size " + size + " enhanced font 'sans,11' linewidth 1\n";
  }
  if (ext == ".svg") {
    *format = "svg";
    return "set terminal svg size " + size + " dynamic enhanced font 'sans,11' linewidth 1\n";
  }
  throw InputError(image.string() + ": a plot must be a .png or .svg file");
}

}  // namespace

void FigureSet::draw(const std::string& script, const fs::path& image, const PlotStyle& style) {
  std::string format;
  const std::string terminal = terminal_line(image, style, &format);
  images_.emplace_back(image, run_gnuplot(terminal + script + "\n", format, image.string()));
}

std::vector<fs::path> FigureSet::commit() {
  // Folders that do not exist yet are made now, and removed again if the set fails.
  std::vector<fs::path> made;
  std::vector<std::unique_ptr<AtomicFile>> files;
  try {
    for (const auto& [image, bytes] : images_) {
      const fs::path folder = image.parent_path();
      std::error_code error;
      if (!folder.empty() && !fs::exists(folder, error)) {
        for (fs::path p = folder; !p.empty() && !fs::exists(p, error); p = p.parent_path()) made.push_back(p);
        fs::create_directories(folder, error);
        if (error) throw InputError(folder.string() + ": cannot create the folder: " + error.message());
      }
      files.push_back(std::make_unique<AtomicFile>(image));
      files.back()->stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    for (auto& file : files) file->finish();  // every byte written before anything moves
  } catch (...) {
    files.clear();  // temporaries removed
    std::error_code ignored;
    for (const fs::path& folder : made) fs::remove(folder, ignored);  // innermost first; only if empty
    throw;
  }
  std::vector<fs::path> written;
  for (auto& file : files) {
    file->publish();
    written.push_back(file->target());
  }
  return written;
}

void render_gnuplot(const std::string& script, const fs::path& image, const PlotStyle& style) {
  FigureSet figure;
  figure.draw(script, image, style);
  figure.commit();
}

// ---------------------------------------------------------------- run figures

namespace {

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

}  // namespace

nlohmann::json read_summary_json(const fs::path& file) {
  nlohmann::json j;
  std::ifstream in(file);
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": not valid JSON (" + e.what() + ")");
  }
  return j;
}

namespace {

RunData load_run(const fs::path& dir, const PlotStyle& style) {
  if (!fs::is_directory(dir))
    throw InputError(dir.string() + ": not a folder (expected the output folder of `adjoin run`)");
  RunData run;
  const fs::path summary_file = dir / "summary.json";
  if (!fs::exists(summary_file))
    throw InputError(summary_file.string() + ": not found (expected the summary.json written by `adjoin run`)");
  const nlohmann::json j = read_summary_json(summary_file);
  if (!j.is_object()) throw InputError(summary_file.string() + ": expected a JSON object");
  run.scene = j.value("scene", dir.filename().string());
  const std::string units = j.value("units", "dimensionless");
  if (units != "SI" && units != "dimensionless")
    throw InputError(summary_file.string() + ": \"units\" is '" + units + "', expected \"SI\" or \"dimensionless\"");
  run.si = units == "SI";
  if (j.contains("phases") && j["phases"].is_array())
    for (const auto& p : j["phases"])
      if (p.is_object() && p.contains("t_start") && p.contains("t_end") && p["t_start"].is_number() &&
          p["t_end"].is_number())
        run.phases.push_back({p.value("state", ""), p["t_start"].get<double>(), p["t_end"].get<double>()});
  run.min_gap = json_number(j, "pounding", "min_gap");
  run.t_min_gap = json_number(j, "pounding", "t_min_gap");
  run.t_first_contact = json_number(j, "pounding", "t_first_contact");

  run.series = must_read(dir / "timeseries.csv",
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
      s << "set object " << 100 + n++ << " rect from " << num(p.t0) << ", graph 0 to " << num(p.t1)
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

}  // namespace

RunPlots plot_run(const fs::path& dir, const std::string& prefix, const PlotStyle& style) {
  if (fs::is_directory(dir) && is_building_run(dir)) return plot_building_run(dir, prefix, style);
  const RunData run = load_run(dir, style);
  const std::string ext = plot_extension(style.format);
  const bool si = run.si;
  const CsvTable& ts = run.series;
  const std::vector<double> t = ts.numbers("t"), x1 = ts.numbers("x1"), x2 = ts.numbers("x2"),
                            v1 = ts.numbers("v1"), v2 = ts.numbers("v2"), f1 = ts.numbers("f1"),
                            f2 = ts.numbers("f2"), q = ts.numbers("q"), ag = ts.numbers("ag"),
                            gap = ts.numbers("gap");
  std::vector<double> dv(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) dv[i] = v1[i] - v2[i];
  const double t_first = t.front(), t_last = t.back();
  // The t axis spans the run exactly; the data get a little headroom above and below.
  const std::string xrange =
      "set xrange [" + num(t_first) + ":" + num(t_last) + "]\nset offsets 0, 0, graph 0.06, graph 0.06\n";
  const std::string tlabel = "set xlabel 'time t" + unit(si, "s") + "'\n";
  const std::string bands = stick_bands(run.phases);
  const bool stick = has_stick(run.phases);

  RunPlots result;
  FigureSet figures;  // all inputs read and every figure drawn before any file is written
  auto target = [&](const std::string& name) { return fs::path(prefix + name + ext); };

  // (1) displacements
  {
    std::ostringstream s;
    s << kPreamble;
    datablock(s, "d", {t, x1, x2});
    s << title_line(run.scene, "block displacements relative to the base") << xrange << tlabel
      << "set ylabel 'displacement x_1, x_2" << unit(si, "m") << "'\n"
      << "set key " << key_corner(t, {x1, x2}) << "\n" << bands
      << "plot $d using 1:2 with lines lt 1 title 'x_1', $d using 1:3 with lines lt 2 dt 2 title 'x_2'"
      << (stick ? std::string(", ") + kStickKey : "") << "\n";
    figures.draw(s.str(), target("displacements"), style);
  }

  // (2) ground acceleration, damper force, relative velocity: three panels on one t axis
  {
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
    s << kPreamble;
    datablock(s, "d", {t, ag, q, dv});
    s << "set multiplot layout 3,1 title " << gnuplot_quote(run.scene + ": excitation, damper force and relative velocity")
      << " noenhanced font ',12' margins 0.11,0.97,0.09,0.91 spacing 0,0.025\n"
      << xrange << bands << "set key " << key_corner(t, {ag}) << "\n"
      << "set format x ''\nunset xlabel\n"
      << "set ylabel 'a_g" << unit(si, "m/s²") << "'\n"
      << "plot $d using 1:2 with lines lt 7 title 'ground acceleration a_g'"
      << (stick ? std::string(", ") + kStickKey : "") << "\n"
      << "set ylabel 'q" << unit(si, "N") << "'\n";
    if (slip && mu > 0.0) {
      s << "set key " << key_corner(t, {q}, 0.0, std::pair{-1.35 * mu, 1.35 * mu}) << "\nset yrange [" << num(-1.35 * mu) << ":" << num(1.35 * mu) << "]\n"
        << "plot $d using 1:3 with lines lt 2 title 'damper force q', " << num(mu)
        << " with lines lc rgb '#888888' dt 3 lw 1.5 title '±μ', " << num(-mu)
        << " with lines lc rgb '#888888' dt 3 lw 1.5 notitle\n"
        << "set autoscale y\n";
    } else {
      s << "set key " << key_corner(t, {q}) << "\nplot $d using 1:3 with lines lt 2 title 'damper force q'\n";
    }
    s << "set key " << key_corner(t, {dv}) << "\nset format x '%g'\n" << tlabel << "set ylabel 'v_1 − v_2" << unit(si, "m/s") << "'\n"
      << "plot $d using 1:4 with lines lt 1 title 'relative velocity v_1 − v_2', 0 with lines lc rgb '#888888' "
         "lw 1 notitle\n"
      << "unset multiplot\n";
    figures.draw(s.str(), target("excitation"), style);
  }

  // (3) rod forces
  {
    std::ostringstream s;
    s << kPreamble;
    datablock(s, "d", {t, f1, f2});
    s << title_line(run.scene, "forces in the viscoelastic rods") << xrange << tlabel
      << "set ylabel 'rod force f_1, f_2" << unit(si, "N") << "'\n"
      << "set key " << key_corner(t, {f1, f2}) << "\n" << bands
      << "plot $d using 1:2 with lines lt 1 title 'f_1 (rod 1)', $d using 1:3 with lines lt 2 title 'f_2 (rod 2)'"
      << (stick ? std::string(", ") + kStickKey : "") << "\n";
    figures.draw(s.str(), target("rod-forces"), style);
  }

  // (4) gap with its minimum and the contact line
  {
    double lo = 0.0, hi = 0.0;
    for (double g : gap)
      if (std::isfinite(g)) hi = std::max(hi, g), lo = std::min(lo, g);
    std::ostringstream s;
    s << kPreamble;
    datablock(s, "d", {t, gap});
    s << title_line(run.scene, "gap between the blocks (pounding margin)") << xrange << tlabel
      << "set ylabel 'gap ξ" << unit(si, "m") << "'\n"
      << "set yrange [" << num(lo - 0.08 * (hi - lo)) << ":" << num(hi + 0.15 * (hi - lo)) << "]\n"
      << "set key " << key_corner(t, {gap, std::vector<double>(t.size(), 0.0)}, 0.0,
                                  std::pair{lo - 0.08 * (hi - lo), hi + 0.15 * (hi - lo)}) << "\n";
    std::string extra;
    if (run.min_gap && run.t_min_gap) {
      char label[160];
      std::snprintf(label, sizeof label, "min ξ = %.4g at t = %.4g%s", *run.min_gap, *run.t_min_gap, si ? " s" : "");
      s << "$m << EOD\n" << num(*run.t_min_gap) << " " << num(*run.min_gap) << "\nEOD\n";
      extra += ", $m using 1:2 with points pt 7 ps 1.6 lc rgb '#d0451b' title " + gnuplot_quote(label);
    }
    if (run.t_first_contact)
      s << "set arrow from " << num(*run.t_first_contact) << ", graph 0 to " << num(*run.t_first_contact)
        << ", graph 1 nohead lc rgb '#b00000' dt 2 lw 1.5\n"
        << "set label 'first contact' at " << num(*run.t_first_contact) << ", graph 0.95 offset 0.5,0 tc rgb '#b00000'\n";
    s << "plot $d using 1:2 with lines lt 1 title 'ξ = ξ_0 + x_2 − x_1', 0 with lines lc rgb '#b00000' lw 1.5 "
         "title 'contact (ξ = 0)'"
      << extra << "\n";
    figures.draw(s.str(), target("gap"), style);
  }

  // (5) pounding with a contact law (impacts.csv): the gap and the contact force on one t
  // axis, each impact marked (a band from its start to its end, and its peak force)
  const fs::path impacts_file = dir / "impacts.csv";
  if (fs::exists(impacts_file)) {
    const CsvTable im = read_csv_table(impacts_file);
    const std::string context = "the impacts of `adjoin run` with a contact law";
    const std::vector<double> start = im.numbers("t_start", context), duration = im.numbers("duration", context),
                              peak = im.numbers("force_max", context), t_peak = im.numbers("t_force_max", context);
    const bool force = ts.has("fc");
    std::vector<double> fc = force ? ts.numbers("fc") : std::vector<double>(t.size(), 0.0);
    std::ostringstream s;
    s << kPreamble;
    datablock(s, "d", {t, gap, fc});
    if (!start.empty()) datablock(s, "p", {t_peak, peak, start});
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
        s << "set object " << 10000 + i << " rect from " << num(start[i]) << ", graph 0 to " << num(start[i] + width)
          << ", graph 1 behind fillcolor rgb '#f4d6cc' fillstyle solid 1.0 noborder\n";
      else
        s << "set arrow " << 10000 + i << " from " << num(start[i]) << ", graph 0 to " << num(start[i])
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
    figures.draw(s.str(), target("contact"), style);
  }

  // (6) energy shares, when an energy history is there
  const fs::path energy_file = dir / "energy.csv";
  if (fs::exists(energy_file)) {
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
    s << kPreamble;
    const bool input = e.has("input");
    if (input) columns.push_back(e.numbers("input"));
    datablock(s, "e", columns);
    s << title_line(run.scene, "energy balance (cumulative shares)")
      << "set xlabel 'time t" << unit(si, "s") << "'\n"
      << "set ylabel '" << (si ? "energy [J]" : "energy per unit m_1 (dimensionless)") << "'\n"
      << "set key top left\nset style fill solid 0.75 noborder\n";
    // Headroom above the curves for the key.
    double top = 0.0;
    for (std::size_t c = 1; c < columns.size(); ++c)
      for (double v : columns[c])
        if (std::isfinite(v)) top = std::max(top, v);
    if (top > 0.0) s << "set yrange [*:" << num(1.4 * top) << "]\n";
    s << "plot ";
    for (std::size_t k = 0; k < names.size(); ++k)
      s << (k ? ", " : "") << "$e using 1:" << (k == 0 ? std::string("(0)") : std::to_string(k + 1)) << ":"
        << k + 2 << " with filledcurves lt " << k + 1 << " title " << gnuplot_quote(names[k]);
    if (input)
      s << (names.empty() ? "" : ", ") << "$e using 1:" << names.size() + 2
        << " with lines lc rgb 'black' lw 2 title 'input'";
    s << "\n";
    figures.draw(s.str(), target("energy"), style);
  } else {
    result.notes.push_back("no energy figure: " + energy_file.string() + " does not exist");
  }
  result.images = figures.commit();
  return result;
}

// ---------------------------------------------------------------- spectra

namespace {

struct SpectrumCurve {
  std::string label;
  std::vector<double> period, psa, sd;  // periods > 0, increasing
};

// Labelled ticks on a log axis that spans less than two decades, where gnuplot labels only
// the powers of ten (none, or one): 1, 2, 5 times powers of ten inside [lo, hi]. Empty
// otherwise (gnuplot's own ticks serve).
std::string log_tics(const char* axis, double lo, double hi) {
  if (!(lo > 0.0 && hi > lo) || hi / lo >= 100.0) return "";
  std::string list;
  for (int e = static_cast<int>(std::floor(std::log10(lo))) - 1; e <= static_cast<int>(std::ceil(std::log10(hi))); ++e)
    for (double m : hi / lo < 10.0 ? std::vector<double>{1, 1.5, 2, 3, 4, 5, 6, 8} : std::vector<double>{1, 2, 5}) {
      const double v = m * std::pow(10.0, e);
      if (v < lo * (1 - 1e-9) || v > hi * (1 + 1e-9)) continue;
      char text[64];
      std::snprintf(text, sizeof text, "%s\"%g\" %.12g", list.empty() ? "" : ", ", v, v);
      list += text;
    }
  return list.empty() ? "" : "set " + std::string(axis) + "tics (" + list + ")\n";
}

// Numbers in legends rounded for reading: 4 significant digits, no binary noise (0.05, not
// 0.05000000000000000277).
std::string legend_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string damping_label(double zeta) { return "damping " + legend_number(zeta * 100.0) + " %"; }

void draw_spectra(const std::vector<SpectrumCurve>& curves, const std::string& title, const fs::path& image,
                  const PlotStyle& style, const std::vector<ReferenceCurve>& references = {}) {
  std::ostringstream s;
  s << kPreamble;
  for (std::size_t d = 0; d < curves.size(); ++d)
    datablock(s, "s" + std::to_string(d), {curves[d].period, curves[d].psa, curves[d].sd});
  for (std::size_t r = 0; r < references.size(); ++r)
    datablock(s, "r" + std::to_string(r), {references[r].period, references[r].psa});
  double t_lo = INFINITY, t_hi = 0.0;
  for (const auto& c : curves)
    for (double t : c.period) {
      t_lo = std::min(t_lo, t);
      t_hi = std::max(t_hi, t);
    }
  s << log_tics("x", t_lo, t_hi);
  s << "set multiplot layout 2,1 title " << gnuplot_quote("Elastic response spectra: " + title)
    << " noenhanced font ',12' margins 0.1,0.72,0.09,0.92 spacing 0,0.03\n"
    << "set logscale x\nset format x ''\nset key outside right top vertical\nset mxtics 10\n"
    << "set grid xtics mxtics ytics lc rgb '#d0d0d0', lc rgb '#ececec'\n";
  auto panel = [&](int column) {
    s << "plot ";
    for (std::size_t d = 0; d < curves.size(); ++d)
      s << (d ? ", " : "") << "$s" << d << " using 1:" << column << " with lines lt " << d + 1 << " title "
        << gnuplot_quote(curves[d].label);
    if (column == 2)
      for (std::size_t r = 0; r < references.size(); ++r)
        s << ", $r" << r << " using 1:2 with lines lt " << r + 1 << " dt 2 lw 1.5 title "
          << gnuplot_quote(references[r].label) << " noenhanced";
    s << "\n";
  };
  s << "set ylabel 'PSA [g]'\n";
  panel(2);
  s << "set format x '%g'\nset xlabel 'period T [s]'\nset ylabel 'SD [m]'\n";
  panel(3);
  s << "unset multiplot\n";
  render_gnuplot(s.str(), image, style);
}

// One curve per signal and damping from rows (signal, period, damping, psa, sd) in any order
// (a run's spectra.csv has a signal column: ground, block1, block2); periods > 0 only.
std::vector<SpectrumCurve> spectrum_curves(const std::vector<double>& period, const std::vector<double>& damping,
                                           const std::vector<double>& psa, const std::vector<double>& sd,
                                           const std::vector<std::string>& signal = {}) {
  std::vector<std::pair<std::string, double>> groups;
  for (std::size_t i = 0; i < damping.size(); ++i) {
    const std::pair<std::string, double> g{signal.empty() ? std::string() : signal[i], damping[i]};
    if (std::isfinite(g.second) && std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
  }
  std::vector<SpectrumCurve> curves;
  for (const auto& [sig, z] : groups) {
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t i = 0; i < period.size(); ++i)
      if (damping[i] == z && period[i] > 0.0 && (signal.empty() || signal[i] == sig)) order.push_back({period[i], i});
    if (order.empty()) continue;
    std::sort(order.begin(), order.end());
    SpectrumCurve curve{(sig.empty() ? "" : sig + ", ") + damping_label(z), {}, {}, {}};
    for (const auto& [p, i] : order) {
      curve.period.push_back(p);
      curve.psa.push_back(psa[i]);
      curve.sd.push_back(sd[i]);
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace

void plot_spectrum(const ResponseSpectrum& spectrum, const fs::path& image, const PlotStyle& style,
                   const std::string& title, const std::vector<ReferenceCurve>& references) {
  std::vector<double> period, damping, psa, sd;
  for (const SpectralValues& v : spectrum.values) {
    period.push_back(v.period);
    damping.push_back(v.damping);
    psa.push_back(v.psa);
    sd.push_back(v.sd);
  }
  const std::vector<SpectrumCurve> curves = spectrum_curves(period, damping, psa, sd);
  if (curves.empty()) throw InputError(image.string() + ": no period > 0 s to plot");
  draw_spectra(curves, title, image, style, references);
}

void plot_spectrum_csv(const fs::path& csv, const fs::path& image, const PlotStyle& style) {
  const CsvTable table = must_read(csv, "the CSV of `adjoin spectrum`: period,damping,sd,sv,sa,psv,psa");
  const std::string context = "spectrum CSV";
  std::vector<std::string> signal;
  if (table.has("signal")) {
    const std::size_t c = table.column("signal", context);
    for (const auto& row : table.rows) signal.push_back(row[c]);
  }
  const std::vector<SpectrumCurve> curves =
      spectrum_curves(table.numbers("period", context), table.numbers("damping", context),
                      table.numbers("psa", context), table.numbers("sd", context), signal);
  if (curves.empty()) throw InputError(csv.string() + ": no rows with period > 0 s to plot");
  draw_spectra(curves, csv.filename().string(), image, style);
}

// ---------------------------------------------------------------- Fourier amplitude

void plot_fourier(const FourierSpectrum& raw, const FourierSpectrum* smoothed, const fs::path& image,
                  const PlotStyle& style, const std::string& title) {
  // Log axes: only f > 0 and A > 0 can be drawn.
  auto positive = [](const FourierSpectrum& spectrum) {
    std::vector<std::vector<double>> cols(2);
    for (std::size_t k = 0; k < spectrum.frequency.size(); ++k)
      if (spectrum.frequency[k] > 0.0 && spectrum.amplitude[k] > 0.0) {
        cols[0].push_back(spectrum.frequency[k]);
        cols[1].push_back(spectrum.amplitude[k]);
      }
    return cols;
  };
  const std::vector<std::vector<double>> r = positive(raw);
  if (r[0].empty()) throw InputError(image.string() + ": the spectrum has no amplitude > 0 at a frequency > 0 to plot");
  std::ostringstream s;
  s << kPreamble;
  datablock(s, "raw", r);
  std::string plots = "$raw using 1:2 with lines lc rgb '" + std::string(smoothed ? "#b0b0b0" : "#1f5fa8") +
                      "' title 'Fourier amplitude'";
  if (smoothed) {
    datablock(s, "smooth", positive(*smoothed));
    plots += ", $smooth using 1:2 with lines lt 1 linewidth 2 title 'Konno-Ohmachi smoothed'";
  }
  s << "set title " << gnuplot_quote("Fourier amplitude spectrum: " + title) << " noenhanced font ',12'\n"
    << "set logscale xy\nset format x '%g'\nset format y '10^{%L}'\nset mxtics 10\n"
    << "set grid xtics mxtics ytics lc rgb '#d0d0d0', lc rgb '#ececec'\n"
    << "set xlabel 'frequency f [Hz]'\nset ylabel 'Fourier amplitude [m/s]'\nset key bottom left\n"
    << "plot " << plots << "\n";
  render_gnuplot(s.str(), image, style);
}

// ---------------------------------------------------------------- convergence

void plot_convergence_csv(const fs::path& csv, const fs::path& image, const PlotStyle& style,
                          const std::string& title) {
  const CsvTable table = must_read(csv, "the convergence.csv of `adjoin converge`");
  const std::string context = "convergence CSV: scheme,history,h,steps,wall_seconds,error,...";
  const std::size_t cs = table.column("scheme", context), ch = table.column("history", context);
  const std::vector<double> wall = table.numbers("wall_seconds", context), error = table.numbers("error", context);
  std::vector<std::pair<std::string, std::string>> series;
  for (const auto& row : table.rows) {
    const std::pair<std::string, std::string> key{row[cs], row[ch]};
    if (std::find(series.begin(), series.end(), key) == series.end()) series.push_back(key);
  }
  std::ostringstream s;
  s << kPreamble;
  std::vector<std::string> plots;
  for (const auto& key : series) {
    std::vector<std::vector<double>> cols(2);
    for (std::size_t i = 0; i < table.rows.size(); ++i)
      if (table.rows[i][cs] == key.first && table.rows[i][ch] == key.second && wall[i] > 0.0 && error[i] > 0.0) {
        cols[0].push_back(wall[i]);
        cols[1].push_back(error[i]);
      }
    if (cols[0].empty()) continue;
    const std::string name = "c" + std::to_string(plots.size());
    datablock(s, name, cols);
    plots.push_back("$" + name + " using 1:2 with linespoints lt " + std::to_string(plots.size() + 1) +
                    " ps 1.2 title " + gnuplot_quote(key.first + " / " + key.second) + " noenhanced");
  }
  if (plots.empty())
    throw InputError(csv.string() + ": no rows with wall_seconds > 0 and error > 0 to plot on log axes");
  {
    double w_lo = INFINITY, w_hi = 0.0;
    for (double w : wall)
      if (w > 0.0) { w_lo = std::min(w_lo, w); w_hi = std::max(w_hi, w); }
    s << log_tics("x", w_lo, w_hi);
  }
  const std::string where = !title.empty() ? title
                            : csv.has_parent_path() && !csv.parent_path().filename().empty()
                                ? csv.parent_path().filename().string()
                                : csv.filename().string();
  // The title wraps rather than runs off the figure (long reference descriptions).
  const std::string wrapped = gnuplot_quote_wrapped("Work-precision: " + where, 70);
  s << "set title " << wrapped << " noenhanced font ',11'\n"
    << "set logscale xy\nset format y '10^{%L}'\nset format x '%g'\nset mxtics 10\n"
    << "set xlabel 'wall time of the run [s]'\nset ylabel 'error (relative max norm)'\n"
    << "set key outside right top vertical\nplot " << join(plots, ", ") << "\n";
  render_gnuplot(s.str(), image, style);
}

// ---------------------------------------------------------------- sweeps

namespace {

// Short axis labels with units for the columns adjoin's tables have (a sweep's sweep.csv, a
// building sweep's channel columns; docs/reference/outputs.md): the quantity, the element, the unit.
// A column not listed keeps its name.
struct ColumnLabel {
  const char* column;  // X stands for A or B, N for a link's or contact pair's number
  const char* label;
  const char* unit;    // SI unit, "" for ratios and counts
};
constexpr ColumnLabel kColumnLabels[] = {
    {"X.T1", "fundamental period, building X", "s"},
    {"X.roof_max", "peak roof displacement, building X", "m"},
    {"X.drift_max", "peak storey drift, building X", "m"},
    {"X.drift_storey", "storey of the peak drift, building X", ""},
    {"X.accel_max", "peak floor acceleration, building X", "m/s²"},
    {"X.base_shear_max", "peak base shear, building X", "N"},
    {"X.share_inherent", "share of the input energy in inherent damping, building X", ""},
    {"linkN.force_max", "peak force, link N", "N"},
    {"linkN.stroke_max", "peak stroke, link N", "m"},
    {"linkN.switches", "stick/slip changes, link N", ""},
    {"linkN.energy_share", "share of the input energy, link N", ""},
    {"contactN.min_gap", "smallest gap, contact pair N", "m"},
    {"contactN.impacts", "impacts, contact pair N", ""},
    {"contactN.force_max", "peak impact force, contact pair N", "N"},
    {"contactN.penetration_max", "peak penetration, contact pair N", "m"},
    {"contactN.energy_share", "share of the input energy in impacts, contact pair N", ""},
    {"energy_input", "input energy", "J"},
    {"share_residual", "energy balance residual / input", ""},
    {"x1", "peak displacement of block 1", "m"},
    {"x2", "peak displacement of block 2", "m"},
    {"drift", "peak damper stroke |x_1 − x_2|", "m"},
    {"f1", "peak rod force f_1", "N"},
    {"f2", "peak rod force f_2", "N"},
    {"a1_abs", "peak absolute acceleration of block 1", "m/s²"},
    {"a2_abs", "peak absolute acceleration of block 2", "m/s²"},
    {"min_gap", "smallest gap", "m"},
    {"contact.impacts", "impacts", ""},
    {"contact.force_max", "peak impact force", "N"},
    {"contact.penetration_max", "peak penetration", "m"},
    {"share_rod1", "share of the input energy, rod 1", ""},
    {"share_rod2", "share of the input energy, rod 2", ""},
    {"share_friction", "share of the input energy, friction damper", ""},
    {"pga_g", "peak ground acceleration", "g"},
    {"wall_seconds", "wall time", "s"},
    {"link.N.slip_ratio", "slip force of link N / weight of building B", ""},
    {"link.N.slip_force", "slip force of link N", "N"},
    {"contact.N.gap", "gap of contact pair N", "m"},
    {"model.mu", "friction threshold μ", ""},
};

// `name` against a pattern where X matches A or B and N a number; the matched element.
bool matches(const std::string& pattern, const std::string& name, std::string* element) {
  std::size_t i = 0, j = 0;
  element->clear();
  while (i < pattern.size() && j < name.size()) {
    if (pattern[i] == 'X' && (name[j] == 'A' || name[j] == 'B')) {
      *element = name[j];
      ++i, ++j;
    } else if (pattern[i] == 'N' && std::isdigit(static_cast<unsigned char>(name[j]))) {
      const std::size_t start = j;
      while (j < name.size() && std::isdigit(static_cast<unsigned char>(name[j]))) ++j;
      *element = name.substr(start, j - start);
      ++i;
    } else if (pattern[i] == name[j]) {
      ++i, ++j;
    } else {
      return false;
    }
  }
  return i == pattern.size() && j == name.size();
}

// The axis label of a column: "peak storey drift, building A [m]"; units only in SI tables
// (`si`), "(dimensionless)" otherwise when the quantity has a unit.
std::string column_label(const std::string& column, bool si, std::string* unit_out = nullptr) {
  std::string element;
  for (const ColumnLabel& l : kColumnLabels)
    if (matches(l.column, column, &element)) {
      std::string label = l.label;
      for (const char* placeholder : {"building X", "link N", "pair N"}) {
        const auto at = label.find(placeholder);
        if (at != std::string::npos) label.replace(at + std::strlen(placeholder) - 1, 1, element);
      }
      const std::string unit = l.unit;
      if (unit_out) *unit_out = unit;
      if (unit.empty()) return label;
      if (unit == "g") return label + " [g]";
      return label + (si ? " [" + unit + "]" : " (dimensionless)");
    }
  if (column.rfind("sa_", 0) == 0) return "spectral acceleration at T = " + column.substr(3) + (si ? " s [g]" : " [g]");
  return column;
}

// The x values of a sweep table's column: numbers, or, when a cell is text (`--x damper`:
// none, friction), the position of its value among the distinct values in the order they
// first appear (`categories` then holds those values).
std::vector<double> x_values(const CsvTable& table, const std::string& name, std::vector<std::string>* categories) {
  try {
    return table.numbers(name, "--x");
  } catch (const InputError&) {
    const std::size_t c = table.column(name, "--x");
    std::vector<double> x;
    for (const auto& row : table.rows) {
      auto it = std::find(categories->begin(), categories->end(), row[c]);
      if (it == categories->end()) it = categories->insert(categories->end(), row[c]);
      x.push_back(static_cast<double>(it - categories->begin()));
    }
    return x;
  }
}

}  // namespace

std::vector<std::string> plot_sweep_csv(const fs::path& csv, const SweepPlotOptions& options, const fs::path& image,
                                        const PlotStyle& style) {
  if (options.x.empty()) throw InputError("--x: expected a column name");
  if (options.y.empty()) throw InputError("--y: expected one or more column names separated by commas");
  const CsvTable table = must_read(csv, "a CSV file with a header line");
  std::vector<std::string> categories, notes;
  const std::vector<double> x = x_values(table, options.x, &categories);
  const bool categorical = !categories.empty();
  if (categorical && options.log_x)
    throw InputError("--logx: column '" + options.x + "' holds text ('" + categories.front() +
                     "'), not numbers; a logarithmic axis needs numbers > 0");
  std::vector<std::vector<double>> ys;
  for (const std::string& name : options.y) {
    if (name.empty()) throw InputError("--y: empty column name (expected names separated by commas)");
    ys.push_back(table.numbers(name, "--y"));
  }
  std::vector<std::string> groups{""};
  std::size_t cg = 0;
  if (!options.group.empty()) {
    cg = table.column(options.group, "--group");
    groups.clear();
    for (const auto& row : table.rows)
      if (std::find(groups.begin(), groups.end(), row[cg]) == groups.end()) groups.push_back(row[cg]);
  }
  if (table.rows.empty()) throw InputError(csv.string() + ": no data rows to plot");
  if (groups.size() > 40)
    throw InputError("--group " + options.group + ": " + std::to_string(groups.size()) +
                     " distinct values (expected at most 40 curves; group by a coarser column)");
  // A log axis has no place for zero or negative values: say which rows are left out.
  if (options.log_x) {
    const auto dropped = std::count_if(x.begin(), x.end(), [](double v) { return std::isfinite(v) && v <= 0.0; });
    if (dropped == static_cast<long>(x.size()))
      throw InputError("--logx: every value of column '" + options.x + "' is zero or negative; a logarithmic axis needs values > 0 (leave out --logx)");
    if (dropped > 0)
      notes.push_back("note: --logx: " + std::to_string(dropped) + " row(s) with " + options.x +
                      " <= 0 are not drawn (a logarithmic axis has no zero)");
  }
  if (options.log_y)
    for (std::size_t k = 0; k < ys.size(); ++k) {
      const auto dropped = std::count_if(ys[k].begin(), ys[k].end(), [](double v) { return std::isfinite(v) && v <= 0.0; });
      if (dropped > 0)
        notes.push_back("note: --logy: " + std::to_string(dropped) + " value(s) of " + options.y[k] +
                        " <= 0 are not drawn (a logarithmic axis has no zero)");
    }
  // SI unless the table says otherwise (its `units` column).
  bool si = true;
  if (table.has("units")) {
    const std::size_t cu = table.column("units");
    si = std::none_of(table.rows.begin(), table.rows.end(), [&](const auto& row) { return row[cu] == "dimensionless"; });
  }

  std::ostringstream s;
  s << kPreamble;
  // One datablock per group: x then every y column, sorted by x.
  for (std::size_t g = 0; g < groups.size(); ++g) {
    std::vector<std::size_t> rows;
    for (std::size_t i = 0; i < table.rows.size(); ++i)
      if ((options.group.empty() || table.rows[i][cg] == groups[g]) && std::isfinite(x[i]) &&
          !(options.log_x && x[i] <= 0.0))
        rows.push_back(i);
    std::stable_sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
    std::vector<std::vector<double>> cols(1 + ys.size());
    for (std::size_t i : rows) {
      cols[0].push_back(x[i]);
      for (std::size_t k = 0; k < ys.size(); ++k)
        cols[k + 1].push_back(options.log_y && !(ys[k][i] > 0.0) ? kNaN : ys[k][i]);
    }
    datablock(s, "g" + std::to_string(g), cols);
  }
  for (std::size_t k = 0; k < ys.size(); ++k) {
    const bool any = std::any_of(ys[k].begin(), ys[k].end(), [&](double v) {
      return std::isfinite(v) && !(options.log_y && v <= 0.0);
    });
    if (!any)
      throw InputError(csv.string() + ": column '" + options.y[k] + "' has no " +
                       (options.log_y ? "positive " : "") + "numbers to plot");
  }
  const std::string where = csv.has_parent_path() && !csv.parent_path().filename().empty()
                                ? (csv.parent_path().filename() / csv.filename()).string()
                                : csv.filename().string();
  const std::string title = options.title.empty() ? "Sweep: " + where : options.title;
  const bool panels = ys.size() > 1;
  // The key, when there is one (a curve per group), right of the panels, outside the data.
  const bool key = !options.group.empty();
  const std::string right = key ? "0.74" : "0.97";
  if (panels)
    s << "set multiplot layout " << ys.size() << ",1 title " << gnuplot_quote(title)
      << " noenhanced font ',12' margins 0.12," << right << ",0.09,0.92 spacing 0,0.03\n";
  else
    s << "set title " << gnuplot_quote(title) << " noenhanced font ',12'\n"
      << "set lmargin at screen 0.12\nset rmargin at screen " << right << "\n";
  if (options.log_x) s << "set logscale x\n";
  if (options.log_y) s << "set logscale y\n";
  // Text values: one tick per value, in the order they first appear in the table (labelled
  // on the bottom panel only).
  auto category_tics = [&](bool labelled) {
    std::string tics = "set xtics (";
    for (std::size_t c = 0; c < categories.size(); ++c)
      tics += (c ? ", " : "") + gnuplot_quote(labelled ? categories[c] : "") + " " + std::to_string(c);
    return tics + ") noenhanced\n";
  };
  if (categorical) {
    s << "set xrange [-0.5:" << num(static_cast<double>(categories.size()) - 0.5) << "]\n";
  } else {
    s << gnuplot_tick_format("x", x, options.log_x) << "set autoscale xfix\n";
  }
  // x spans the data plus a little; y gets headroom, but does not go below zero for a
  // quantity that is never negative in the table (peaks, shares, counts).
  const std::string x_offsets = categorical ? "set offsets graph 0, graph 0" : "set offsets graph 0.02, graph 0.02";
  const std::string x_label = gnuplot_quote(column_label(options.x, si)) + " noenhanced";
  for (std::size_t k = 0; k < ys.size(); ++k) {
    const bool first = k == 0, last = k + 1 == ys.size();
    if (key && first) s << "set key outside right top vertical Left reverse noenhanced title " << gnuplot_quote(options.group) << "\n";
    else s << "unset key\n";
    if (panels) s << (last ? "set format x '%g'\nset xlabel " + x_label + "\n" : std::string("set format x ''\nunset xlabel\n"));
    else s << "set xlabel " << x_label << "\n";
    if (panels && last && !categorical) s << gnuplot_tick_format("x", x, options.log_x);
    if (categorical) s << category_tics(last);
    // Stacked panels are short: a long label takes two lines rather than run into the next.
    const std::string y_label = column_label(options.y[k], si);
    s << "set ylabel " << (panels ? gnuplot_quote_wrapped(y_label, 18) + " font ',9'" : gnuplot_quote(y_label))
      << " noenhanced\n" << gnuplot_tick_format("y", ys[k], options.log_y);
    const bool non_negative = std::none_of(ys[k].begin(), ys[k].end(), [](double v) { return v < 0.0; });
    if (non_negative && !options.log_y) s << "set yrange [0:*]\n" << x_offsets << ", graph 0.06, 0\n";
    else s << "set yrange [*:*]\n" << x_offsets << ", graph 0.06, graph 0.06\n";
    s << "plot ";
    for (std::size_t g = 0; g < groups.size(); ++g) {
      // 12 colours, each with its own marker; past 12 groups the dash pattern changes too.
      const std::string label = options.group.empty() ? options.y[k] : groups[g];
      // Text-valued x: points only (lines between categories mean nothing).
      s << (g ? ", " : "") << "$g" << g << " using 1:" << k + 2 << (categorical ? " with points" : " with linespoints")
        << " lt " << g % 12 + 1 << " dt " << g / 12 + 1 << " ps " << (categorical ? "1.4" : "0.9") << " title "
        << gnuplot_quote(label);
    }
    s << "\n";
  }
  if (panels) s << "unset multiplot\n";
  render_gnuplot(s.str(), image, style);
  return notes;
}

}  // namespace adjoin
