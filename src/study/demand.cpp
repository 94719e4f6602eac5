#include "adjoin/core/parse_number.hpp"
#include "adjoin/study/demand.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <gsl/gsl_fit.h>
#include <map>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/study/sweep.hpp"

namespace adjoin {
namespace {


}  // namespace

DemandFit fit_demand_model(std::span<const double> im, std::span<const double> demand) {
  if (im.size() != demand.size())
    throw InputError("demand model: " + std::to_string(im.size()) + " IM values but " + std::to_string(demand.size()) + " demands");
  const std::size_t n = im.size();
  if (n < 3) throw InputError("demand model: " + std::to_string(n) + " motions; a fit with a dispersion needs at least 3");
  std::vector<double> x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(im[i]) && im[i] > 0.0))
      throw InputError("demand model: IM value " + std::to_string(i) + " is " + std::to_string(im[i]) + "; expected a positive number");
    if (!(std::isfinite(demand[i]) && demand[i] > 0.0))
      throw InputError("demand model: demand " + std::to_string(i) + " is " + std::to_string(demand[i]) + "; expected a positive number");
    x[i] = std::log(im[i]);
    y[i] = std::log(demand[i]);
  }
  if (std::all_of(x.begin(), x.end(), [&](double v) { return v == x[0]; }))
    throw InputError("demand model: every motion has the same IM; the slope b needs at least two distinct IM values");
  DemandFit fit;
  fit.n = n;
  double sumsq = 0.0;
  gsl_fit_linear(x.data(), 1, y.data(), 1, n, &fit.a, &fit.b, &fit.cov_aa, &fit.cov_ab, &fit.cov_bb, &sumsq);
  fit.beta = std::sqrt(sumsq / static_cast<double>(n - 2));
  double mean = 0.0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(n);
  double total = 0.0;
  for (double v : y) total += (v - mean) * (v - mean);
  fit.r2 = total > 0.0 ? 1.0 - sumsq / total : 1.0;
  return fit;
}

std::size_t SweepCsvTable::column(const std::string& name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it != header.end()) return static_cast<std::size_t>(it - header.begin());
  std::string list;
  for (const auto& h : header) list += (list.empty() ? "" : ", ") + h;
  throw InputError(file.string() + ":1: no column \"" + name + "\"; the columns are: " + list);
}

SweepCsvTable read_sweep_csv(const std::filesystem::path& file) {
  // A folder or a FIFO is not opened (a FIFO would block the program).
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (std::filesystem::is_directory(status))
    throw InputError(file.string() + ": is a folder; expected a sweep's table (DIR/sweep.csv)");
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(file.string() + ": is not a regular file (a FIFO, device or socket); expected a sweep's table (sweep.csv)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open the table");
  SweepCsvTable table;
  table.file = file;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> cells;
    if (!split_csv_line(line, &cells))
      throw InputError(file.string() + ":" + std::to_string(number) + ": broken quoting (expected CSV cells)");
    if (table.header.empty()) {
      table.header = std::move(cells);
      continue;
    }
    if (cells.size() != table.header.size())
      throw InputError(file.string() + ":" + std::to_string(number) + ": " + std::to_string(cells.size()) +
                       " cells; the header has " + std::to_string(table.header.size()));
    table.rows.push_back(std::move(cells));
  }
  if (table.header.empty()) throw InputError(file.string() + ": empty file (expected a header line and rows)");
  return table;
}

std::vector<std::string> sweep_axis_columns(const SweepCsvTable& table) {
  const std::size_t first = table.column("index"), last = table.column("motion");
  if (last < first) throw InputError(table.file.string() + ":1: \"motion\" comes before \"index\"; not a sweep table");
  return std::vector<std::string>(table.header.begin() + static_cast<std::ptrdiff_t>(first + 1),
                                  table.header.begin() + static_cast<std::ptrdiff_t>(last));
}

std::string demand_im_column(const SweepCsvTable& table, const std::string& im) {
  std::string column;
  if (im == "pga") {
    column = "pga_g";
  } else if (im.rfind("sa:", 0) == 0 && im.size() > 3) {
    column = "sa_" + im.substr(3);
    if (std::find(table.header.begin(), table.header.end(), column) == table.header.end()) {
      // Accept "sa:1.0" for the column sa_1: compare the periods as numbers.
      double wanted = 0.0;
      if (parse_finite(im.substr(3), &wanted))
        for (const auto& h : table.header) {
          double t = 0.0;
          if (h.rfind("sa_", 0) == 0 && parse_finite(h.substr(3), &t) && t == wanted) column = h;
        }
    }
  } else {
    throw InputError("--im " + im + ": expected pga or sa:T (T a period of the sweep's [output] im_periods, e.g. sa:1)");
  }
  if (std::find(table.header.begin(), table.header.end(), column) == table.header.end()) {
    std::string have;
    for (const auto& h : table.header)
      if (h.rfind("sa_", 0) == 0) have += (have.empty() ? "" : ", ") + h;
    throw InputError(table.file.string() + ":1: no column " + column + " for --im " + im +
                     (have.empty() ? std::string("; this sweep has no Sa columns: add [output] im_periods = [T] to the sweep file")
                                   : "; Sa columns present: " + have));
  }
  return column;
}

std::vector<DemandGroupFit> fit_sweep_demand(const SweepCsvTable& table, const std::string& response, const std::string& im,
                                             bool pooled) {
  const std::size_t response_column = table.column(response);
  const std::size_t im_column = table.column(demand_im_column(table, im));
  const std::vector<std::string> axes = pooled ? std::vector<std::string>{} : sweep_axis_columns(table);
  std::vector<std::size_t> axis_columns;
  for (const auto& a : axes) axis_columns.push_back(table.column(a));
  const auto error_it = std::find(table.header.begin(), table.header.end(), "error");
  const std::size_t error_column = error_it == table.header.end() ? table.header.size()
                                                                  : static_cast<std::size_t>(error_it - table.header.begin());

  // Groups in order of first appearance (the sweep's order).
  std::vector<std::vector<std::string>> keys;
  std::map<std::vector<std::string>, std::pair<std::vector<double>, std::vector<double>>> data;
  std::map<std::vector<std::string>, std::size_t> skipped;
  for (const auto& row : table.rows) {
    std::vector<std::string> key;
    for (std::size_t c : axis_columns) key.push_back(row[c]);
    if (!data.count(key)) keys.push_back(key);
    auto& [x, y] = data[key];
    double im_value = 0.0, d = 0.0;
    const bool failed = error_column < row.size() && !row[error_column].empty();
    if (failed || !parse_finite(row[im_column], &im_value) || !parse_finite(row[response_column], &d) ||
        !(im_value > 0.0) || !(d > 0.0) || !std::isfinite(im_value) || !std::isfinite(d)) {
      ++skipped[key];
      continue;
    }
    x.push_back(im_value);
    y.push_back(d);
  }
  std::vector<DemandGroupFit> fits;
  for (const auto& key : keys) {
    DemandGroupFit g;
    g.group = key;
    g.skipped = skipped[key];
    const auto& [x, y] = data[key];
    g.usable = x.size();
    try {
      g.fit = fit_demand_model(x, y);
    } catch (const InputError& e) {
      // One design point that cannot be fitted does not stop the others.
      g.problem = e.what();
      g.fit = DemandFit{};
      g.fit.n = x.size();
    }
    fits.push_back(std::move(g));
  }
  if (fits.empty()) throw InputError(table.file.string() + ": no rows (expected a sweep's table with one row per run)");
  if (std::none_of(fits.begin(), fits.end(), [](const DemandGroupFit& g) { return g.problem.empty(); })) {
    const auto& g = fits.front();
    std::string label;
    for (std::size_t k = 0; k < g.group.size(); ++k) label += (k ? ", " : "") + axes[k] + "=" + g.group[k];
    throw InputError(table.file.string() + ": " + (label.empty() ? std::string("all rows") : label) + ": " + g.problem +
                     (fits.size() > 1 ? " (and no other design point can be fitted either)" : ""));
  }
  return fits;
}

}  // namespace adjoin
