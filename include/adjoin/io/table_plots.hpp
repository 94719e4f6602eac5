#pragma once
// Figures of the tables adjoin writes (io/plots.hpp lists them): a convergence study's
// work-precision diagram, and any column against any column(s) of a CSV (a sweep's table).
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/io/plot_style.hpp"

namespace adjoin {

// Error against wall time, one curve per scheme/history; title after "Work-precision: "
// (default: the CSV's folder).
void plot_convergence_csv(const std::filesystem::path& csv, const std::filesystem::path& image, const PlotStyle& style,
                          const std::string& title = "");

struct SweepPlotOptions {
  std::string x;               // column on the horizontal axis
  std::vector<std::string> y;  // one panel per column
  std::string group;           // optional: one curve per distinct value of this column
  bool log_x = false, log_y = false;
  std::string title;           // default: the CSV's file name
};
// Returns notes for the terminal (rows a log axis cannot show). Axis labels name the
// quantity and its unit for the columns adjoin's tables have; a text-valued --x column is a
// categorical axis (one tick per value, in the table's order).
std::vector<std::string> plot_sweep_csv(const std::filesystem::path& csv, const SweepPlotOptions& options,
                                        const std::filesystem::path& image, const PlotStyle& style);

// The axis label of a table's column: "peak storey drift, building A [m]" (units only when
// `si`); a column adjoin does not know keeps its name.
std::string table_column_label(const std::string& column, bool si);

}  // namespace adjoin
