// gnuplot run on a figure's script, one figure or a set written all or none
// (io/plot_style.hpp).
#include <memory>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/plot_style.hpp"

namespace adjoin {
namespace fs = std::filesystem;

namespace {

// The terminal line for the image's format at the style's size.
std::string terminal_line(const fs::path& image, const PlotStyle& style, std::string* format) {
  const std::string ext = image.extension().string();
  const std::string size = std::to_string(style.width) + "," + std::to_string(style.height);
  if (ext == ".png") {
    *format = "png";
    return "set terminal pngcairo size " + size + " enhanced font 'sans,11' linewidth 1\n";
  }
  if (ext == ".svg") {
    *format = "svg";
    return "set terminal svg size " + size + " dynamic enhanced font 'sans,11' linewidth 1\n";
  }
  throw InputError(image.string() + ": a plot must be a .png or .svg file");
}

}  // namespace

void FigureSet::draw(const std::string& script, const fs::path& image, const PlotStyle& style) {
  std::string format;
  const std::string terminal = terminal_line(image, style, &format);
  images_.emplace_back(image, run_gnuplot(terminal + script + "\n", format, image.string()));
}

std::vector<fs::path> FigureSet::commit() {
  // Folders that do not exist yet are made now, and removed again if the set fails.
  std::vector<fs::path> made;
  std::vector<std::unique_ptr<AtomicFile>> files;
  try {
    for (const auto& [image, bytes] : images_) {
      const fs::path folder = image.parent_path();
      std::error_code error;
      if (!folder.empty() && !fs::exists(folder, error)) {
        for (fs::path p = folder; !p.empty() && !fs::exists(p, error); p = p.parent_path()) made.push_back(p);
        fs::create_directories(folder, error);
        if (error) throw InputError(folder.string() + ": cannot create the folder: " + error.message());
      }
      files.push_back(std::make_unique<AtomicFile>(image));
      files.back()->stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    for (auto& file : files) file->finish();  // every byte written before anything moves
  } catch (...) {
    files.clear();  // temporaries removed
    std::error_code ignored;
    for (const fs::path& folder : made) fs::remove(folder, ignored);  // innermost first; only if empty
    throw;
  }
  std::vector<fs::path> written;
  for (auto& file : files) {
    file->publish();
    written.push_back(file->target());
  }
  return written;
}

void render_gnuplot(const std::string& script, const fs::path& image, const PlotStyle& style) {
  FigureSet figure;
  figure.draw(script, image, style);
  figure.commit();
}

}  // namespace adjoin
