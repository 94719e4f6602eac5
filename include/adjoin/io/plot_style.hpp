#pragma once
// How adjoin's figures are made (io/plots.hpp lists them): the image's format, size and time
// window from the command line, and gnuplot run on a figure's script, one figure or a set
// written all or none.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adjoin/io/csv_table.hpp"

namespace adjoin {

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

}  // namespace adjoin
