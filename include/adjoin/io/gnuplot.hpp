#pragma once
// Drawing with gnuplot: the caller writes the data files and a script body that plots them;
// this runs gnuplot on it and moves the finished image into place (PNG or SVG by extension).
#include <filesystem>
#include <string>

namespace adjoin {

// "set terminal ..." for the image's extension (.png or .svg); InputError otherwise.
std::string gnuplot_terminal(const std::filesystem::path& image, int width = 900, int height = 600);
// Quotes a string for a gnuplot script.
std::string gnuplot_quote(const std::string& text);
// Runs `script` (which must not set terminal/output) to make `image`. Throws InputError if
// gnuplot is not installed or fails (its stderr is in the message).
void run_gnuplot(const std::string& script, const std::filesystem::path& image);

}  // namespace adjoin
