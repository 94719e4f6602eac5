#pragma once
// Text for gnuplot scripts. Drawing itself (a script to a PNG or SVG file, through a temporary
// file renamed into place) is render_gnuplot in io/plots.hpp.
#include <sstream>
#include <string>
#include <vector>

namespace adjoin {

// Quotes a string for a gnuplot script ('it''s').
std::string gnuplot_quote(const std::string& text);
// A number as gnuplot reads it (%.10g; NaN for a non-finite value, where gnuplot breaks a line).
std::string gnuplot_number(double v);
// A datablock $name of whitespace-separated rows, one column a vector.
void gnuplot_datablock(std::ostringstream& script, const std::string& name, const std::vector<std::vector<double>>& columns);
// The common look of adjoin's figures: light grid, readable fonts, a sober palette.
extern const char* const kGnuplotPreamble;

}  // namespace adjoin
