#include "adjoin/io/gnuplot.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "adjoin/errors.hpp"

namespace adjoin {

std::string gnuplot_terminal(const std::filesystem::path& image, int width, int height) {
  const std::string ext = image.extension().string();
  std::ostringstream s;
  if (ext == ".png") s << "set terminal pngcairo size " << width << "," << height << " noenhanced font 'sans,10'\n";
  else if (ext == ".svg") s << "set terminal svg size " << width << "," << height << " noenhanced dynamic font 'sans,10'\n";
  else throw InputError(image.string() + ": a plot must be a .png or .svg file");
  return s.str();
}

std::string gnuplot_quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

void run_gnuplot(const std::string& script, const std::filesystem::path& image) {
  const std::string tag = ".tmp." + std::to_string(::getpid());
  std::filesystem::path temporary = image;
  temporary += tag + image.extension().string();
  const std::filesystem::path script_file = image.string() + tag + ".gp";
  const std::filesystem::path errors = image.string() + tag + ".err";
  {
    std::ofstream out(script_file);
    out << gnuplot_terminal(image) << "set output " << gnuplot_quote(temporary.string()) << "\n" << script
        << "\nunset output\n";
    if (!out) throw InputError(script_file.string() + ": cannot write the gnuplot script");
  }
  const std::string command = "gnuplot " + gnuplot_quote(script_file.string()) + " 2> " + gnuplot_quote(errors.string());
  const int status = std::system(command.c_str());
  std::ifstream err_in(errors);
  std::stringstream err;
  err << err_in.rdbuf();
  std::error_code ignored;
  std::filesystem::remove(script_file, ignored);
  std::filesystem::remove(errors, ignored);
  if (status != 0 || !std::filesystem::exists(temporary)) {
    std::filesystem::remove(temporary, ignored);
    throw InputError(image.string() + ": gnuplot failed" +
                     (status == 127 * 256 ? std::string(" (is gnuplot installed? scripts/setup.sh installs it)") : ": " + err.str()));
  }
  std::filesystem::rename(temporary, image);
}

}  // namespace adjoin
