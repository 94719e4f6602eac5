#pragma once
// Text for gnuplot scripts, and gnuplot itself run on a script.
//
// Every piece of text that reaches a script (titles, labels, key entries: scene names from a
// summary.json, file names, column names, --title) goes through gnuplot_quote: a script is
// code, and gnuplot runs shell commands (`system`, backquotes), so text taken from data must
// never end a string or a line. Data reach scripts only as numbers (gnuplot_number, in
// datablocks). Paths never reach a script: gnuplot writes the image to its standard output.
#include <sstream>
#include <string>
#include <vector>

namespace adjoin {

// Text as a single-quoted gnuplot string ('it''s'). In single quotes gnuplot expands nothing
// (no backslash escapes, no backquote commands, no @macros); only a quote ('') and the end
// of the line matter, so control characters (a newline would end the line, and the next
// line would run as a command) are written visibly instead: \n, \t, \r, \xNN.
std::string gnuplot_quote(const std::string& text);
// The same, broken at spaces into lines of about `width` characters: a gnuplot string
// expression ('line 1'."\n".'line 2') for long titles.
std::string gnuplot_quote_wrapped(const std::string& text, std::size_t width);
// A number as gnuplot reads it (%.10g; NaN for a non-finite value, where gnuplot breaks a line).
std::string gnuplot_number(double v);
// "set format <axis> ..." for tick labels that read as numbers: 0.5, 20, 1.5e7 (gnuplot's
// default writes 1x10^7 in enhanced text, which overlaps on short axes); from the values'
// size (and 1e7-style powers of ten on a log axis).
std::string gnuplot_tick_format(const char* axis, const std::vector<double>& values, bool log = false);
// "set <axis>tics STEP" for about four labelled ticks over the values' range (divided by
// `scale`), 1, 2 or 5 times a power of ten: stacked panels are short, and gnuplot's own
// choice crowds their labels.
std::string gnuplot_tick_step(const char* axis, const std::vector<double>& values, double scale = 1.0);
// "set <axis>tics (...)": labelled ticks on a log axis that spans less than two decades,
// where gnuplot labels only the powers of ten (none, or one): 1, 2, 5 times powers of ten
// inside [lo, hi] (finer under one decade). Empty otherwise (gnuplot's own ticks serve).
std::string gnuplot_log_tics(const char* axis, double lo, double hi);
// A datablock $name of whitespace-separated rows, one column a vector.
void gnuplot_datablock(std::ostringstream& script, const std::string& name, const std::vector<std::vector<double>>& columns);
// The common look of adjoin's figures: light grid, readable fonts, one palette of 12 distinct
// colours, each linetype with its own point type (see kGnuplotPalette).
extern const char* const kGnuplotPreamble;

// Runs gnuplot on `script` (which sets the terminal and no output: the image goes to
// gnuplot's standard output) without a shell, and returns the image's bytes. The image is
// checked to be complete (a PNG ends with its IEND chunk, an SVG with </svg>): gnuplot
// exits 0 after a failed write. InputError naming `what` if gnuplot is missing, fails or
// writes an incomplete image.
std::string run_gnuplot(const std::string& script, const std::string& format, const std::string& what);

}  // namespace adjoin
