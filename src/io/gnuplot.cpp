#include "adjoin/io/gnuplot.hpp"

#include <cmath>
#include <cstdio>

namespace adjoin {

std::string gnuplot_quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

std::string gnuplot_number(double v) {
  if (!std::isfinite(v)) return "NaN";
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

// A gnuplot datablock named $name with whitespace-separated rows; NaN cells are written as
// NaN (gnuplot skips those points and breaks the line there).
void gnuplot_datablock(std::ostringstream& script, const std::string& name, const std::vector<std::vector<double>>& columns) {
  script << "$" << name << " << EOD\n";
  const std::size_t n = columns.empty() ? 0 : columns.front().size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) script << (c ? " " : "") << gnuplot_number(columns[c][i]);
    script << "\n";
  }
  script << "EOD\n";
}

// Common look: light grid, readable fonts, a sober palette.
const char* const kGnuplotPreamble =
    "set encoding utf8\n"
    "set grid lc rgb '#d0d0d0' lw 1\n"
    "set border lw 1.2\n"
    "set key opaque box lc rgb '#b0b0b0' samplen 2.5 spacing 1.1\n"
    "set linetype 1 lc rgb '#1f5fa8' lw 2\n"
    "set linetype 2 lc rgb '#d0451b' lw 2\n"
    "set linetype 3 lc rgb '#2e8b3a' lw 2\n"
    "set linetype 4 lc rgb '#7b3fa0' lw 2\n"
    "set linetype 5 lc rgb '#c08a00' lw 2\n"
    "set linetype 6 lc rgb '#0f9b9b' lw 2\n"
    "set linetype 7 lc rgb '#555555' lw 2\n"
    "set linetype 8 lc rgb '#e377c2' lw 2\n"
    "set linetype 9 lc rgb '#8c564b' lw 2\n"
    "set linetype 10 lc rgb '#17becf' lw 2\n"
    "set linetype 11 lc rgb '#bcbd22' lw 2\n"
    "set linetype 12 lc rgb '#000000' lw 2\n"
    "set linetype cycle 12\n"
    "set linetype cycle 8\n";

}  // namespace adjoin
