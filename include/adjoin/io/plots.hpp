#pragma once
// Figures from adjoin's own outputs, drawn with gnuplot (PNG through pngcairo, or SVG):
//
//  - plot_run: the seed paper's figures for one run folder (timeseries.csv + summary.json):
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
//  - plot_spectrum_csv: PSA and SD against period (log axis), one curve per damping, from the
//    CSV of `adjoin spectrum` (period,damping,sd,sv,sa,psv,psa).
//  - plot_convergence_csv: error against wall time (log-log), one curve per scheme/history,
//    from the CSV of `adjoin converge` (scheme,history,h,steps,wall_seconds,error,...).
//  - plot_sweep_csv: any column against any column(s) of a CSV with a header, optionally one
//    curve per value of a grouping column (for `adjoin sweep` tables, or any other).
//
// Bad input (missing file or column, non-numeric cell, unknown format) throws InputError that
// names the file, line or column and what was expected.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "adjoin/post/intensity.hpp"
#include "adjoin/post/spectrum.hpp"

namespace adjoin {

// A CSV file with a header line: cells kept as text, converted on demand. Quoted fields
// ("a,b", with "" for a quote) are understood; blank lines and lines starting with '#' are
// skipped; every row must have as many fields as the header.
struct CsvTable {
  std::filesystem::path file;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::size_t> lines;  // the file line of each row (1-based)

  bool has(const std::string& name) const;
  // Index of a column; InputError naming the column and listing the available ones otherwise.
  std::size_t column(const std::string& name, const std::string& context = "") const;
  // The column as numbers: an empty cell, nan/NaN, "-" or null is NaN; true/false are 1/0;
  // anything else that is not a number
  // is an InputError naming file:line and the column.
  std::vector<double> numbers(const std::string& name, const std::string& context = "") const;
};

CsvTable read_csv_table(const std::filesystem::path& file);

struct PlotStyle {
  std::string format = "png";  // "png" or "svg"
  int width = 900, height = 600;
  // Time histories drawn only for from <= t <= to (--window T0:T1); none: the whole run.
  std::optional<std::pair<double, double>> window;
};

// Parses --window "T0:T1" (numbers, T0 < T1) into the style; InputError naming `option`.
void parse_time_window(const std::string& text, PlotStyle* style, const std::string& option = "--window");
// Keeps the rows of a time-series table (column t) inside the style's window; InputError if
// fewer than two are left (naming the window and the span the table has).
void keep_time_window(CsvTable& series, const PlotStyle& style);

// Checks "png"/"svg" (InputError naming `option` otherwise) and returns the extension (".png").
std::string plot_extension(const std::string& format, const std::string& option = "--format");
// Parses "WxH" (e.g. 900x600, each 100..10000 pixels) into the style; InputError otherwise.
void parse_plot_size(const std::string& text, PlotStyle* style, const std::string& option = "--size");
// For a single-image command: the image path (`out`, or `fallback` with the format's
// extension); the extension of `out` must be .png or .svg and agree with an explicit format.
// `option` names `out` in messages.
std::filesystem::path plot_target(const std::string& out, const std::filesystem::path& fallback,
                                  const std::string& explicit_format, PlotStyle* style,
                                  const std::string& option = "--out");

// Runs a gnuplot script (which must not set terminal or output) to make `image` at the
// style's size, written through a temporary file renamed into place (after gnuplot finished
// and the image was checked complete). UTF-8 text; enhanced text mode (x_1 is a subscript;
// use `noenhanced` for verbatim labels). Text in the script must come from gnuplot_quote.
void render_gnuplot(const std::string& script, const std::filesystem::path& image, const PlotStyle& style);

// Figures that belong together (the figures of one run folder): each is drawn in memory by
// draw(); commit() writes them all or none (every one to its temporary first, then all
// renamed into place; folders created only then). Destroyed without commit(), nothing is
// written.
class FigureSet {
 public:
  void draw(const std::string& script, const std::filesystem::path& image, const PlotStyle& style);
  std::vector<std::filesystem::path> commit();

 private:
  std::vector<std::pair<std::filesystem::path, std::string>> images_;
};

struct RunPlots {
  std::vector<std::filesystem::path> images;  // in the order listed above
  std::vector<std::string> notes;             // e.g. why the energy figure was skipped
};

// Figures for the run folder `dir`, written to `prefix` + name + extension (e.g. prefix
// "out/paper-strong/" gives out/paper-strong/displacements.png). Parent folders are created.
RunPlots plot_run(const std::filesystem::path& dir, const std::string& prefix, const PlotStyle& style);

// A building run's folder (summary.json with "structure" and floor peaks): `profiles` (peak
// displacement by floor and peak drift by storey, A and B side by side) and, with a
// timeseries.csv, `roofs` (the roofs' displacements and the links' forces against time).
// plot_run hands such folders here.
bool is_building_run(const std::filesystem::path& dir);
RunPlots plot_building_run(const std::filesystem::path& dir, const std::string& prefix, const PlotStyle& style);

// Chosen channels of any run folder (columns of its timeseries.csv: A.x5, link1.force, x1, fd,
// ...) against time, one panel each, stacked with a shared time axis, to `image`. At most 8
// channels; a name that is not a column is an InputError naming `option` and listing the
// columns there are.
void plot_run_channels(const std::filesystem::path& dir, const std::vector<std::string>& channels,
                       const std::filesystem::path& image, const PlotStyle& style,
                       const std::string& option = "--channels");
// The same channels of several run folders in one figure: a panel per channel, a curve per
// run (legend: scene and folder), each run on its own time grid. At most 24 runs.
void plot_runs_channels(const std::vector<std::filesystem::path>& dirs, const std::vector<std::string>& channels,
                        const std::filesystem::path& image, const PlotStyle& style,
                        const std::string& option = "--channels");

// PSA and SD against period (log axis), one curve per damping; title after "Elastic response
// spectra: ". From memory, or from the CSV of `adjoin spectrum` (title: the file's name).
// `references` (e.g. a code spectrum) are drawn dashed on the PSA panel.
struct ReferenceCurve {
  std::string label;
  std::vector<double> period, psa;  // s, g
};
void plot_spectrum(const ResponseSpectrum& spectrum, const std::filesystem::path& image, const PlotStyle& style,
                   const std::string& title, const std::vector<ReferenceCurve>& references = {});
void plot_spectrum_csv(const std::filesystem::path& csv, const std::filesystem::path& image, const PlotStyle& style);
// Fourier amplitude [m/s] against frequency [Hz] on log-log axes: the raw spectrum and, if
// given, a smoothed one drawn over it; title after "Fourier amplitude spectrum: ".
void plot_fourier(const FourierSpectrum& raw, const FourierSpectrum* smoothed, const std::filesystem::path& image,
                  const PlotStyle& style, const std::string& title);
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

}  // namespace adjoin
