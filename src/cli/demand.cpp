// adjoin demand SWEEP_CSV --response drift --im pga|sa:T [--pooled] [--out FILE]
//
// A probabilistic seismic demand model from a sweep over an ensemble of ground motions:
// ln(response) = a + b ln(IM) by least squares, one fit per design point (each combination of
// the sweep's axis values; --pooled: one fit over every row), with the dispersion beta and R^2
// (study/demand.hpp). Prints a table; --out writes it as CSV (temporary file + rename).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/study/demand.hpp"
#include "adjoin/study/sweep.hpp"
#include "command.hpp"

namespace adjoin::cli {
namespace {

struct DemandArgs {
  std::string table, response = "drift", im = "pga", out;
  bool pooled = false;
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

int demand_command(const DemandArgs& args) {
  const SweepCsvTable table = read_sweep_csv(args.table);
  const std::string im_column = demand_im_column(table, args.im);
  const auto fits = fit_sweep_demand(table, args.response, args.im, args.pooled);
  const std::vector<std::string> axes = args.pooled ? std::vector<std::string>{} : sweep_axis_columns(table);

  std::printf("demand model ln(%s) = a + b ln(%s), %s\n", args.response.c_str(), im_column.c_str(), args.table.c_str());
  for (const auto& a : axes) std::printf("%-14s ", a.c_str());
  std::printf("%5s %12s %10s %10s %8s %12s\n", "n", "a", "b", "beta", "R^2", "median@IM=1");
  std::size_t unfitted = 0;
  for (const auto& g : fits) {
    for (const auto& v : g.group) std::printf("%-14s ", v.c_str());
    if (g.problem.empty())
      std::printf("%5zu %12.5g %10.5g %10.5g %8.4f %12.5g", g.fit.n, g.fit.a, g.fit.b, g.fit.beta, g.fit.r2, std::exp(g.fit.a));
    else
      std::printf("%5zu %12s %10s %10s %8s %12s  not fitted", g.usable, "-", "-", "-", "-", "-");
    if (g.skipped) std::printf("  (%zu rows skipped: failed runs, or an IM or response that is not a positive number, which a log fit cannot take)", g.skipped);
    std::printf("\n");
    if (!g.problem.empty()) {
      ++unfitted;
      std::string label;
      for (std::size_t k = 0; k < g.group.size(); ++k) label += (k ? ", " : "") + axes[k] + "=" + g.group[k];
      std::cerr << "warning: " << printable_message(args.table + ": " + label + ": " + g.problem)
                << "; this design point is not fitted (fitted = false in --out), the others are\n";
    }
  }
  if (unfitted) std::printf("%zu of %zu design points not fitted (see the warnings)\n", unfitted, fits.size());
  if (!args.out.empty()) {
    AtomicFile file(args.out);
    std::vector<std::string> header = axes;
    for (const char* c : {"response", "im", "n", "skipped", "a", "b", "beta", "r2", "fitted", "problem"}) header.emplace_back(c);
    file.stream() << csv_line(header) << "\n";
    for (const auto& g : fits) {
      std::vector<std::string> cells = g.group;
      // A design point without a fit: its numbers are empty (never nan), and it says why.
      const bool fitted = g.problem.empty();
      const auto value = [&](double v) { return fitted ? number(v) : std::string(); };
      for (const std::string& c : {args.response, im_column, std::to_string(fitted ? g.fit.n : g.usable), std::to_string(g.skipped),
                                   value(g.fit.a), value(g.fit.b), value(g.fit.beta), value(g.fit.r2),
                                   std::string(fitted ? "true" : "false"), g.problem})
        cells.push_back(c);
      file.stream() << csv_line(cells) << "\n";
    }
    file.commit();
    std::printf("wrote %s\n", args.out.c_str());
  }
  return 0;
}

const Registration registration(52, "demand", "Fit a demand model ln(response) = a + b ln(IM) to a sweep over ground motions",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<DemandArgs>();
  sub->add_option("table", args->table, "The sweep's table (sweep.csv)")->required();
  sub->add_option("--response", args->response, "Response column: drift (default), x1, x2, f1, f2, a1_abs, a2_abs, ...");
  sub->add_option("--im", args->im, "Intensity measure: pga (default) or sa:T (a period of the sweep's im_periods)");
  sub->add_flag("--pooled", args->pooled, "One fit over every row instead of one per design point");
  sub->add_option("--out", args->out, "Write the fits as CSV");
  return [args]() { return demand_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
