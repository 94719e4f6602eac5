#pragma once
// The figure of one accelerogram, drawn with gnuplot (see io/plots.hpp for the conventions):
// four panels on one time axis,
//   acceleration [g], velocity [m/s], displacement [m]   (trapezoid integrals from rest,
//                                                         ground/integration.hpp)
//   Husid plot: normalised cumulative Arias intensity, with the 5 % and 95 % times marked
//   and the significant duration D5-95 shaded and written in the panel's key.
#include <filesystem>
#include <string>

#include "adjoin/ground/record.hpp"
#include "adjoin/io/plot_style.hpp"

namespace adjoin {

void plot_record(const Record& record, const std::filesystem::path& image, const PlotStyle& style,
                 const std::string& title);

}  // namespace adjoin
