// adjoin plot run DIR [DIR...] [--channels NAME[,NAME...]] [--window T0:T1] [--out PREFIX] [--format png|svg]
//                  [--size WxH]          (several DIRs: their channels overlaid, PREFIXoverlay.png)
// adjoin plot spectrum CSV [--out FILE] [--format png|svg] [--size WxH]
// adjoin plot converge CSV [--out FILE] [--format png|svg] [--size WxH]
// adjoin plot sweep CSV --x COLUMN --y COLUMN[,COLUMN...] [--group COLUMN] [--logx] [--logy]
//                       [--title TEXT] [--out FILE] [--format png|svg] [--size WxH]
// adjoin plot record FILE [reading options: --units, --format (of the record), --dt, --channel ...]
//                    [--out FILE.png|.svg] [--size WxH]
//
// Figures with gnuplot from adjoin's own outputs (see adjoin/io/plots.hpp): the seed paper's
// figures for a run folder, response spectra, work-precision and sweep curves. Prints the
// files it wrote.
#include <filesystem>
#include <iostream>
#include <memory>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/io/plots.hpp"
#include "adjoin/io/record_plot.hpp"
#include "command.hpp"
#include "reading_options.hpp"

namespace adjoin::cli {
namespace {

namespace fs = std::filesystem;

struct PlotArgs {
  std::string input, out, format, size = "900x600", window;
  std::vector<std::string> dirs;  // plot run: one run folder, or several to overlay
  std::string x, group, title;
  std::vector<std::string> y, channels;
  bool log_x = false, log_y = false;
};

PlotStyle style_of(const PlotArgs& a) {
  PlotStyle style;
  parse_plot_size(a.size, &style);
  if (!a.window.empty()) parse_time_window(a.window, &style);
  if (!a.format.empty()) {
    plot_extension(a.format);
    style.format = a.format;
  }
  return style;
}

// The default image beside the CSV: <stem>.png, or <stem>-plot.png if that is the CSV itself.
fs::path beside(const fs::path& csv, const std::string& suffix) {
  fs::path p = csv;
  p.replace_filename(csv.stem().string() + suffix);
  return p;
}

// The channels overlaid by default: those of the first run's kind that every run has
// (two-block: x1, x2, gap; buildings: the roofs' displacements and the first link's force).
std::vector<std::string> default_overlay_channels(const std::vector<fs::path>& dirs) {
  std::vector<std::string> wanted{"x1", "x2", "gap"};
  if (is_building_run(dirs.front())) {
    wanted = {"link1.force"};
    const CsvTable ts = read_csv_table(dirs.front() / "timeseries.csv");
    for (const char* b : {"B", "A"}) {
      int top = 0;
      while (ts.has(std::string(b) + ".x" + std::to_string(top + 1))) ++top;
      if (top > 0) wanted.insert(wanted.begin(), std::string(b) + ".x" + std::to_string(top));
    }
  }
  std::vector<std::string> common;
  for (const auto& name : wanted) {
    bool everywhere = true;
    for (const auto& dir : dirs) {
      const fs::path csv = dir / "timeseries.csv";
      if (!fs::exists(csv))
        throw InputError(csv.string() + ": not found (overlays draw time histories: output.timeseries = true writes it)");
      everywhere = everywhere && read_csv_table(csv).has(name);
    }
    if (everywhere) common.push_back(name);
  }
  if (common.empty())
    throw InputError("plot run: the runs share none of " + wanted.front() +
                     "...; name the channels to overlay with --channels");
  return common;
}

int plot_run_command(const PlotArgs& a) {
  const PlotStyle style = style_of(a);
  std::string prefix = a.out;
  const bool overlay = a.dirs.size() > 1;
  if (prefix.empty()) prefix = overlay ? std::string() : (fs::path(a.dirs.front()) / "").string();
  else if (fs::is_directory(prefix) && prefix.back() != '/') prefix += '/';
  if (overlay || !a.channels.empty()) {
    // One figure: the chosen channels (overlays: of every run) after the prefix.
    std::vector<fs::path> dirs(a.dirs.begin(), a.dirs.end());
    for (const auto& dir : dirs)
      if (!fs::is_directory(dir)) throw InputError(dir.string() + ": not a folder (expected the output folder of `adjoin run`)");
    const std::vector<std::string> channels = a.channels.empty() ? default_overlay_channels(dirs) : a.channels;
    const fs::path image = prefix + (overlay ? "overlay" : "channels") + plot_extension(style.format);
    plot_runs_channels(dirs, channels, image, style);
    std::cout << "wrote " << image.string() << "\n";
    return 0;
  }
  const RunPlots plots = plot_run(a.dirs.front(), prefix, style);
  for (const auto& image : plots.images) std::cout << "wrote " << image.string() << "\n";
  for (const auto& note : plots.notes) std::cout << note << "\n";
  return 0;
}

int plot_spectrum_command(const PlotArgs& a) {
  PlotStyle style = style_of(a);
  const fs::path image = plot_target(a.out, beside(a.input, ".png"), a.format, &style);
  plot_spectrum_csv(a.input, image, style);
  std::cout << "wrote " << image.string() << "\n";
  return 0;
}

int plot_converge_command(const PlotArgs& a) {
  PlotStyle style = style_of(a);
  const fs::path image = plot_target(a.out, beside(a.input, "-work-precision.png"), a.format, &style);
  plot_convergence_csv(a.input, image, style);
  std::cout << "wrote " << image.string() << "\n";
  return 0;
}

int plot_sweep_command(const PlotArgs& a) {
  PlotStyle style = style_of(a);
  const fs::path image = plot_target(a.out, beside(a.input, ".png"), a.format, &style);
  SweepPlotOptions options;
  options.x = a.x;
  options.y = a.y;
  options.group = a.group;
  options.log_x = a.log_x;
  options.log_y = a.log_y;
  options.title = a.title;
  const std::vector<std::string> notes = plot_sweep_csv(a.input, options, image, style);
  for (const auto& note : notes) std::cerr << note << "\n";
  std::cout << "wrote " << image.string() << "\n";
  return 0;
}

// The record's figure: acceleration, velocity, displacement, Husid plot with D5-95. The image
// format follows --out's extension (--format here is the record's, as in `record info`).
int plot_record_command(const PlotArgs& a, const ReadingArgs& reading) {
  PlotStyle style;
  parse_plot_size(a.size, &style);
  const fs::path image = plot_target(a.out, beside(a.input, "-record.png"), "", &style);
  const Record record = read_record(a.input, format_from(reading));
  plot_record(record, image, style, fs::path(a.input).filename().string());
  std::cout << "wrote " << image.string() << "\n";
  return 0;
}

void common_options(CLI::App* sub, PlotArgs* a, const std::string& out_help) {
  sub->add_option("--out", a->out, out_help);
  sub->add_option("--format", a->format, "Image format: png or svg (default png, or the --out extension)");
  sub->add_option("--size", a->size, "Image size WIDTHxHEIGHT in pixels (default 900x600)");
}

const Registration registration(60, "plot", "Figures (PNG or SVG, with gnuplot) of runs, spectra, convergence studies and sweeps",
                                [](CLI::App* plot) -> Runner {
  auto args = std::make_shared<PlotArgs>();
  auto reading = std::make_shared<ReadingArgs>();
  plot->require_subcommand(1);

  auto* run = plot->add_subcommand(
      "run", "The paper's figures for a run folder: displacements, excitation/damper force/relative velocity, "
             "rod forces, gap, energy (if DIR/energy.csv exists)");
  run->add_option("dir", args->dirs,
                  "Output folder(s) of `adjoin run` (summary.json, timeseries.csv); several: their channels overlaid "
                  "in one figure, a curve per run (PREFIXoverlay.png, default in the current folder)")
      ->required();
  run->add_option("--channels", args->channels,
                  "Draw only these columns of DIR/timeseries.csv against time, one panel each (e.g. "
                  "A.x5,B.a3_abs,link1.force, or x1,q,gap): PREFIXchannels.png")
      ->delimiter(',');
  run->add_option("--window", args->window, "Only the time window T0:T1 in seconds of the histories, e.g. 5:15");
  common_options(run, args.get(), "Prefix of the image files (default DIR/; e.g. figs/strong- gives figs/strong-gap.png)");

  auto* spectrum = plot->add_subcommand("spectrum", "PSA and SD against period, one curve per damping");
  spectrum->add_option("csv", args->input, "CSV of `adjoin spectrum` (period,damping,sd,sv,sa,psv,psa)")->required();
  common_options(spectrum, args.get(), "Image file, .png or .svg (default: the CSV's name with .png)");

  auto* converge = plot->add_subcommand("converge", "Work-precision: error against wall time per scheme/history, log-log");
  converge->add_option("csv", args->input, "convergence.csv of `adjoin converge`")->required();
  common_options(converge, args.get(), "Image file, .png or .svg (default <csv name>-work-precision.png beside it)");

  auto* sweep = plot->add_subcommand("sweep", "Column against column(s) of any CSV with a header, e.g. of `adjoin sweep`");
  sweep->add_option("csv", args->input, "CSV file with a header line")->required();
  sweep->add_option("--x", args->x, "Column on the horizontal axis")->required();
  sweep->add_option("--y", args->y, "Column(s) on the vertical axis, comma separated: one panel each")
      ->required()
      ->delimiter(',');
  sweep->add_option("--group", args->group, "One curve per distinct value of this column");
  sweep->add_flag("--logx", args->log_x, "Logarithmic x axis");
  sweep->add_flag("--logy", args->log_y, "Logarithmic y axis");
  sweep->add_option("--title", args->title, "Title (default: Sweep: <file name>)");
  common_options(sweep, args.get(), "Image file, .png or .svg (default: the CSV's name with .png)");

  auto* record = plot->add_subcommand(
      "record", "An accelerogram: acceleration, velocity, displacement and the Husid plot with D5-95 marked");
  record->add_option("file", args->input, "Accelerogram (any format `record info` reads)")->required();
  add_reading_options(record, reading.get());
  record->add_option("--out", args->out, "Image file, .png or .svg (default <file name>-record.png beside it)");
  record->add_option("--size", args->size, "Image size WIDTHxHEIGHT in pixels (default 900x600)");

  return [args, reading, run, spectrum, converge, sweep, record]() {
    if (run->parsed()) return plot_run_command(*args);
    if (spectrum->parsed()) return plot_spectrum_command(*args);
    if (converge->parsed()) return plot_converge_command(*args);
    if (sweep->parsed()) return plot_sweep_command(*args);
    if (record->parsed()) return plot_record_command(*args, *reading);
    throw InputError("plot: expected one of run, spectrum, converge, sweep, record");
  };
});

}  // namespace
}  // namespace adjoin::cli
