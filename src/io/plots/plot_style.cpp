// The image's format, size and time window from the command line (io/plot_style.hpp).
#include "adjoin/io/plot_style.hpp"

#include <unistd.h>

#include <cmath>

#include "adjoin/core/parse_number.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"

namespace adjoin {
namespace fs = std::filesystem;

namespace {

// A number of an option: blanks around it allowed.
bool parse_double(const std::string& text, double* value) { return parse_number(trim_blanks(text), *value) == NumberStatus::ok; }

}  // namespace

std::string plot_extension(const std::string& format, const std::string& option) {
  if (format == "png") return ".png";
  if (format == "svg") return ".svg";
  throw InputError(option + " " + format + ": unknown format (expected png or svg)");
}

void parse_plot_size(const std::string& text, PlotStyle* style, const std::string& option) {
  const auto x = text.find_first_of("xX");
  double w = 0.0, h = 0.0;
  if (x == std::string::npos || !parse_double(text.substr(0, x), &w) || !parse_double(text.substr(x + 1), &h) ||
      w != std::floor(w) || h != std::floor(h) || w < 100 || h < 100 || w > 10000 || h > 10000)
    throw InputError(option + " " + text + ": expected WIDTHxHEIGHT in pixels, e.g. 900x600 (100 to 10000 each)");
  style->width = static_cast<int>(w);
  style->height = static_cast<int>(h);
}

fs::path plot_target(const std::string& out, const fs::path& fallback, const std::string& explicit_format,
                     PlotStyle* style, const std::string& option) {
  if (!explicit_format.empty()) plot_extension(explicit_format);
  if (out.empty()) {
    if (!explicit_format.empty()) style->format = explicit_format;
    fs::path p = fallback;
    p.replace_extension(plot_extension(style->format));
    return p;
  }
  const std::string ext = fs::path(out).extension().string();
  if (ext != ".png" && ext != ".svg")
    throw InputError(option + " " + out + ": expected a file name ending in .png or .svg");
  const std::string format = ext.substr(1);
  if (!explicit_format.empty() && explicit_format != format)
    throw InputError(option + " " + out + " and --format " + explicit_format + " disagree (expected the same image format)");
  style->format = format;
  // The image's folder is checked now, before the command does its work: a plot that cannot
  // be written is bad input (exit 2), found up front rather than after a long computation.
  fs::path folder = fs::path(out).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw InputError(option + " " + out + ": the folder " + folder.string() + " does not exist (create it first)");
  if (::access(folder.c_str(), W_OK) != 0)
    throw InputError(option + " " + out + ": the folder " + folder.string() + " is not writable");
  if (fs::is_directory(out, ec)) throw InputError(option + " " + out + ": is a folder; expected an image file name");
  return out;
}

void parse_time_window(const std::string& text, PlotStyle* style, const std::string& option) {
  const auto colon = text.find(':');
  double from = 0.0, to = 0.0;
  std::string excerpt = text.substr(0, 40);
  for (char& c : excerpt)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  if (colon == std::string::npos || !parse_double(text.substr(0, colon), &from) ||
      !parse_double(text.substr(colon + 1), &to) || !std::isfinite(from) || !std::isfinite(to))
    throw InputError(option + " '" + excerpt + (text.size() > 40 ? "...'" : "'") +
                     ": expected T0:T1, two times in seconds (e.g. 5:15)");
  if (!(from < to))
    throw InputError(option + " '" + excerpt + "': expected T0 < T1 (a window of some length)");
  style->window = std::pair{from, to};
}

void keep_time_window(CsvTable& series, const PlotStyle& style) {
  if (!style.window) return;
  const auto [from, to] = *style.window;
  const std::vector<double> t = series.numbers("t", "the time of a time history");
  CsvTable kept = series;
  kept.rows.clear();
  kept.lines.clear();
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= from && t[i] <= to) {
      kept.rows.push_back(series.rows[i]);
      kept.lines.push_back(series.lines[i]);
    }
  if (kept.rows.size() < 2) {
    const std::string span = t.empty() ? "no rows" : "t from " + gnuplot_number(t.front()) + " to " + gnuplot_number(t.back());
    throw InputError("--window " + gnuplot_number(from) + ":" + gnuplot_number(to) + ": " + std::to_string(kept.rows.size()) + " row(s) of " +
                     series.file.string() + " in the window (it has " + span + "); expected at least 2");
  }
  series = std::move(kept);
}

}  // namespace adjoin
