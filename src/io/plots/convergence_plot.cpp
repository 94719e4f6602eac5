// The work-precision figure of a convergence study (io/table_plots.hpp): error against wall
// time, one curve per scheme and history engine.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/table_plots.hpp"
#include "figure_text.hpp"

namespace adjoin {
using figure::join;

namespace fs = std::filesystem;

void plot_convergence_csv(const fs::path& csv, const fs::path& image, const PlotStyle& style,
                          const std::string& title) {
  const CsvTable table = read_csv_table(csv, "the convergence.csv of `adjoin converge`");
  const std::string context = "convergence CSV: scheme,history,h,steps,wall_seconds,error,...";
  const std::size_t cs = table.column("scheme", context), ch = table.column("history", context);
  const std::vector<double> wall = table.numbers("wall_seconds", context), error = table.numbers("error", context);
  std::vector<std::pair<std::string, std::string>> series;
  for (const auto& row : table.rows) {
    const std::pair<std::string, std::string> key{row[cs], row[ch]};
    if (std::find(series.begin(), series.end(), key) == series.end()) series.push_back(key);
  }
  std::ostringstream s;
  s << kGnuplotPreamble;
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
    gnuplot_datablock(s, name, cols);
    plots.push_back("$" + name + " using 1:2 with linespoints lt " + std::to_string(plots.size() + 1) +
                    " ps 1.2 title " + gnuplot_quote(key.first + " / " + key.second) + " noenhanced");
  }
  if (plots.empty())
    throw InputError(csv.string() + ": no rows with wall_seconds > 0 and error > 0 to plot on log axes");
  {
    double w_lo = INFINITY, w_hi = 0.0;
    for (double w : wall)
      if (w > 0.0) { w_lo = std::min(w_lo, w); w_hi = std::max(w_hi, w); }
    s << gnuplot_log_tics("x", w_lo, w_hi);
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

}  // namespace adjoin
