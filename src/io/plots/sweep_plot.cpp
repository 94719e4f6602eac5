// Any column of a CSV against any column(s) (io/table_plots.hpp: plot_sweep_csv), with axis
// labels and units for the columns adjoin's tables have (kColumnLabels).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/table_plots.hpp"

namespace adjoin {
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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
    {"X.drift_ratio_max", "peak storey drift ratio, building X", ""},
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
    {"collapse_t", "time of the collapse", "s"},
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

// A table read for the figure: the x values (numbers, or the positions of text values among
// `categories`), the y columns, the groups; notes on what a log axis cannot show.
struct SweepData {
  CsvTable table;
  std::vector<std::string> categories, notes, groups{""};
  std::vector<double> x;
  std::vector<std::vector<double>> ys;
  std::size_t cg = 0;  // the grouping column
  bool categorical = false, si = true;
};

SweepData read_sweep_data(const fs::path& csv, const SweepPlotOptions& options) {
  if (options.x.empty()) throw InputError("--x: expected a column name");
  if (options.y.empty()) throw InputError("--y: expected one or more column names separated by commas");
  SweepData d;
  d.table = read_csv_table(csv, "a CSV file with a header line");
  const CsvTable& table = d.table;
  auto &categories = d.categories, &notes = d.notes, &groups = d.groups;
  auto& x = d.x;
  auto& ys = d.ys;
  auto& cg = d.cg;
  bool &categorical = d.categorical, &si = d.si;
  x = x_values(table, options.x, &categories);
  categorical = !categories.empty();
  if (categorical && options.log_x)
    throw InputError("--logx: column '" + options.x + "' holds text ('" + categories.front() +
                     "'), not numbers; a logarithmic axis needs numbers > 0");
  for (const std::string& name : options.y) {
    if (name.empty()) throw InputError("--y: empty column name (expected names separated by commas)");
    ys.push_back(table.numbers(name, "--y"));
  }
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
  if (table.has("units")) {
    const std::size_t cu = table.column("units");
    si = std::none_of(table.rows.begin(), table.rows.end(), [&](const auto& row) { return row[cu] == "dimensionless"; });
  }
  for (std::size_t k = 0; k < ys.size(); ++k) {
    const bool any = std::any_of(ys[k].begin(), ys[k].end(), [&](double v) {
      return std::isfinite(v) && !(options.log_y && v <= 0.0);
    });
    if (!any)
      throw InputError(csv.string() + ": column '" + options.y[k] + "' has no " +
                       (options.log_y ? "positive " : "") + "numbers to plot");
  }
  return d;
}

// The figure's script: a panel per y column, a curve per group.
std::string sweep_script(const fs::path& csv, const SweepPlotOptions& options, const SweepData& d) {
  const auto& table = d.table;
  const auto& categories = d.categories;
  const auto& groups = d.groups;
  const auto& x = d.x;
  const auto& ys = d.ys;
  const std::size_t cg = d.cg;
  const bool categorical = d.categorical;
  const bool si = d.si;
  std::ostringstream s;
  s << kGnuplotPreamble;
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
    gnuplot_datablock(s, "g" + std::to_string(g), cols);
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
    s << "set xrange [-0.5:" << gnuplot_number(static_cast<double>(categories.size()) - 0.5) << "]\n";
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
  return s.str();
}

}  // namespace

std::string table_column_label(const std::string& column, bool si) { return column_label(column, si); }

std::vector<std::string> plot_sweep_csv(const fs::path& csv, const SweepPlotOptions& options, const fs::path& image,
                                        const PlotStyle& style) {
  const SweepData data = read_sweep_data(csv, options);
  render_gnuplot(sweep_script(csv, options, data), image, style);
  return data.notes;
}

}  // namespace adjoin
