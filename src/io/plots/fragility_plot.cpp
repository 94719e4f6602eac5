// The fragility figure (io/fragility_plot.hpp).
#include "adjoin/io/fragility_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "adjoin/io/gnuplot.hpp"
#include "figure_text.hpp"

namespace adjoin {
using figure::join;

namespace {

// The lognormal curve at 300 points over (0, top].
std::vector<std::vector<double>> curve_points(double theta, double beta, double top) {
  std::vector<std::vector<double>> cols(2);
  for (int i = 1; i <= 300; ++i) {
    const double x = top * i / 300.0;
    cols[0].push_back(x);
    cols[1].push_back(fragility_probability(theta, beta, x));
  }
  return cols;
}

// A value for a key entry: three significant digits.
std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

}  // namespace

void plot_fragility(const std::vector<FragilityCurve>& curves, const std::string& title, std::optional<double> at,
                    const std::filesystem::path& image, const PlotStyle& style) {
  double top = at.value_or(0.0);
  std::size_t largest_n = 1;
  for (const FragilityCurve& c : curves)
    for (const FragilityLevel& l : c.levels) {
      top = std::max(top, l.im);
      largest_n = std::max(largest_n, l.n);
    }
  top *= 1.1;
  std::ostringstream s;
  s << kGnuplotPreamble;
  std::vector<std::string> plots;
  const bool one = curves.size() == 1;
  for (std::size_t d = 0; d < curves.size(); ++d) {
    const FragilityCurve& c = curves[d];
    const std::string lt = " lt " + std::to_string(d + 1);
    const std::string tag = std::to_string(d);
    const std::string name = one ? "" : c.label + ": ";
    // Observed fractions: point size from the run count (area proportional to n).
    std::vector<std::vector<double>> observed(5);
    for (const FragilityLevel& l : c.levels) {
      observed[0].push_back(l.im);
      observed[1].push_back(double(l.events) / double(l.n));
      observed[2].push_back(0.6 + 1.8 * std::sqrt(double(l.n) / double(largest_n)));
      observed[3].push_back(double(l.n));
      observed[4].push_back(double(l.events));
    }
    gnuplot_datablock(s, "o" + tag, observed);
    if (c.fit.fitted) {
      gnuplot_datablock(s, "f" + tag, curve_points(c.fit.theta, c.fit.beta, top));
      plots.push_back("$f" + tag + " using 1:2 with lines" + lt + " title " +
                      gnuplot_quote(name + "maximum likelihood (θ = " + short_number(c.fit.theta) + " g, β = " + short_number(c.fit.beta) + ")") +
                      " noenhanced");
    }
    if (c.first_event && c.first_event->fitted) {
      gnuplot_datablock(s, "e" + tag, curve_points(c.first_event->theta, c.first_event->beta, top));
      plots.push_back("$e" + tag + " using 1:2 with lines dt 2" + lt + " title " +
                      gnuplot_quote(name + "IM at first event (θ = " +
                                    short_number(c.first_event->theta) + " g, β = " + short_number(c.first_event->beta) + ")") +
                      " noenhanced");
    }
    plots.push_back("$o" + tag + " using 1:2:3 with points" + lt + " ps variable title " +
                    gnuplot_quote(name + "observed fraction (size: runs)") + " noenhanced");
    if (one && c.levels.size() <= 25)
      plots.push_back("$o" + tag + " using 1:2:(sprintf('%d/%d', int($5), int($4))) with labels offset 0,1 font ',9' notitle");
  }
  if (at) s << "set arrow from " << gnuplot_number(*at) << ", graph 0 to " << gnuplot_number(*at)
            << ", graph 1 nohead dt 3 lc rgb '#555555'\nset label 'IM = " << short_number(*at)
            << " g' at " << gnuplot_number(*at) << ", graph 0.04 offset 0.5,0 left font ',9' textcolor rgb '#555555'\n";
  s << "set title " << gnuplot_quote_wrapped(title, 70) << " noenhanced font ',11'\n"
    << "set xrange [0:" << gnuplot_number(top) << "]\nset yrange [-0.05:1.1]\nset ytics 0,0.2,1\n"
    << "set xlabel 'intensity measure IM [g]'\nset ylabel 'P(event | IM)'\n"
    << "set key top left noenhanced\nplot " << join(plots, ", ") << "\n";
  render_gnuplot(s.str(), image, style);
}

}  // namespace adjoin
