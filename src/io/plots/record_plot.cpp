// The figure of one accelerogram: acceleration, velocity, displacement and the Husid plot
// with D5-95 marked (see record_plot.hpp).
#include "adjoin/io/record_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/integration.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/post/intensity.hpp"

namespace adjoin {
namespace {

std::string num(double v, int digits = 10) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  return text;
}

}  // namespace

void plot_record(const Record& record, const std::filesystem::path& image, const PlotStyle& style,
                 const std::string& title) {
  if (record.accel.size() < 2 || !(record.dt > 0.0))
    throw InputError(record.source + ": a record of " + std::to_string(record.accel.size()) +
                     " sample(s) cannot be drawn (expected at least 2)");
  const MotionHistories h = integrate_record(record);
  const std::vector<double> husid = husid_curve(record);
  const SignificantDuration d = significant_duration(record, 0.05, 0.95);
  const bool arias = !husid.empty() && husid.back() > 0.0;

  std::ostringstream s;
  s << "set encoding utf8\nset grid lc rgb '#d0d0d0' lw 1\nset border lw 1.2\n"
    << "set key opaque box lc rgb '#b0b0b0' samplen 2.5 spacing 1.1 top right\n"
    << "set linetype 1 lc rgb '#1f5fa8' lw 1.5\nset linetype 2 lc rgb '#d0451b' lw 1.5\n"
    << "set linetype 3 lc rgb '#2e8b3a' lw 1.5\nset linetype 4 lc rgb '#7b3fa0' lw 2\n";
  s << "$r << EOD\n";
  for (std::size_t i = 0; i < h.accel.size(); ++i)
    s << num(static_cast<double>(i) * h.dt) << " " << num(h.accel[i] / 9.80665) << " " << num(h.velocity[i]) << " "
      << num(h.displacement[i]) << " " << num(husid[i]) << "\n";
  s << "EOD\n";
  const double t_end = static_cast<double>(h.accel.size() - 1) * h.dt;
  s << "set xrange [0:" << num(t_end) << "]\n"
    << "set multiplot layout 4,1 title " << gnuplot_quote("Record: " + title)
    << " noenhanced font ',12' margins 0.11,0.97,0.11,0.92 spacing 0,0.02\n"
    << "set format x ''\nunset xlabel\n";
  if (arias) {
    // The D5-95 band behind every panel (objects persist across multiplot panels).
    s << "set object 1 rect from " << num(d.t_start) << ", graph 0 to " << num(d.t_end)
      << ", graph 1 back fillstyle solid 1.0 noborder fillcolor rgb '#eef2f8'\n";
  }
  s << "set ylabel 'a [g]'\n" << gnuplot_tick_step("y", h.accel, 9.80665) << "plot $r using 1:2 with lines lt 1 title 'acceleration'\n"
    << "set ylabel 'v [m/s]'\n" << gnuplot_tick_step("y", h.velocity) << "plot $r using 1:3 with lines lt 2 title 'velocity (trapezoid, from rest)'\n"
    << "set ylabel 'd [m]'\n" << gnuplot_tick_step("y", h.displacement) << "plot $r using 1:4 with lines lt 3 title 'displacement'\n"
    << "set format x '%g'\nset xlabel 't [s]'\nset ylabel 'Husid H(t)'\nset ytics 0.2\nset yrange [-0.02:1.05]\nset key bottom right\n";
  if (arias) {
    const std::string label = "D_{5-95} = " + num(d.duration, 4) + " s (" + num(d.t_start, 4) + " to " + num(d.t_end, 4) + " s)";
    s << "set arrow 1 from " << num(d.t_start) << ", graph 0 to " << num(d.t_start)
      << ", graph 1 nohead lc rgb '#555555' dt 2 lw 1.5\n"
      << "set arrow 2 from " << num(d.t_end) << ", graph 0 to " << num(d.t_end)
      << ", graph 1 nohead lc rgb '#555555' dt 2 lw 1.5\n"
      << "plot $r using 1:5 with lines lt 4 title 'normalised Arias intensity', 0.05 with lines lc rgb '#888888' dt 3 lw 1 "
         "notitle, 0.95 with lines lc rgb '#888888' dt 3 lw 1 notitle, NaN with boxes fillstyle solid 1.0 noborder "
         "fillcolor rgb '#dde5f1' title "
      << gnuplot_quote(label) << "\n";
  } else {
    s << "plot $r using 1:5 with lines lt 4 title 'normalised Arias intensity (the record is zero: no D_{5-95})'\n";
  }
  s << "unset multiplot\n";
  render_gnuplot(s.str(), image, style);
}

}  // namespace adjoin
