#pragma once
// Text for gnuplot scripts. Drawing itself (a script to a PNG or SVG file, through a temporary
// file renamed into place) is render_gnuplot in io/plots.hpp.
#include <string>

namespace adjoin {

// Quotes a string for a gnuplot script ('it''s').
std::string gnuplot_quote(const std::string& text);

}  // namespace adjoin
