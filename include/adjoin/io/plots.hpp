#pragma once
// Figures from adjoin's own outputs, drawn with gnuplot (PNG through pngcairo, or SVG); one
// header per family, all read through one table reader (io/csv_table.hpp):
//
//  - plot_run (io/run_plots.hpp): the seed paper's figures for one run folder
//    (timeseries.csv + summary.json):
//      displacements   x1 and x2 against t                         (paper Fig. 3 / 6)
//      excitation      a_g, damper force q, relative velocity v1 - v2, stacked on one t axis,
//                      stick intervals shaded                       (paper Fig. 4 / 7)
//      rod-forces      f1 and f2 against t                          (paper Fig. 5 / 8)
//      gap             the gap ξ with its minimum marked and the contact line ξ = 0
//      contact         only when DIR/impacts.csv exists (a contact law): the gap and the
//                      contact force fc on one t axis, each impact marked (its duration shaded,
//                      its first touch and its peak force as points)
//      energy          cumulative energy shares, only when DIR/energy.csv exists (header
//                      t and any of input,kinetic,rod1,rod2,friction,contact,residual)
//    Axis labels carry the scene's units ("(dimensionless)" or SI units), titles its name.
//    A building run's folder gets its own figures (plot_building_run), and any run's chosen
//    channels one panel each (plot_run_channels).
//  - plot_spectrum_csv (io/spectrum_plots.hpp): PSA and SD against period (log axis), one
//    curve per damping, from the CSV of `adjoin spectrum` (period,damping,sd,sv,sa,psv,psa).
//  - plot_convergence_csv (io/table_plots.hpp): error against wall time (log-log), one curve
//    per scheme/history, from the CSV of `adjoin converge` (scheme,history,h,steps,...).
//  - plot_sweep_csv (io/table_plots.hpp): any column against any column(s) of a CSV with a
//    header, optionally one curve per value of a grouping column (for `adjoin sweep` tables,
//    or any other).
//  - plot_record (io/record_plot.hpp): one accelerogram.
//  - plot_fragility (io/fragility_plot.hpp): fragility curves and observed fractions against IM,
//    one colour per design (`adjoin fragility --plot`).
//
// Bad input (missing file or column, non-numeric cell, unknown format) throws InputError that
// names the file, line or column and what was expected.
#include "adjoin/io/csv_table.hpp"
#include "adjoin/io/plot_style.hpp"
#include "adjoin/io/run_plots.hpp"
#include "adjoin/io/spectrum_plots.hpp"
#include "adjoin/io/table_plots.hpp"
