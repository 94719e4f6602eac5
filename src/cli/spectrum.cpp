// adjoin spectrum RECORD [--units g|m/s2|cm/s2|mm/s2] [--format KIND] [--dt S]
//                        [--damping 0.05[,0.02...]] [--periods LIST | --range T0:T1:N[:log|lin]]
//                        [--peaks exact|samples] [--target ec8:T[:AG[:TYPE]]|FILE]
//                        [--free-vibration] [--threads N] [--out FILE] [--plot FILE.png|.svg]
//
// Elastic response spectra of a recorded accelerogram (SPEC §3): CSV with header
// `period,damping,sd,sv,sa,psv,psa` (s, ratio, m, m/s, g, m/s, g), one row per damping and
// period, to FILE (temporary file and rename) or stdout. --plot draws PSA and SD against
// period with gnuplot. Without gnuplot on PATH the CSV is still written and the command
// fails (exit 2) with a message saying so. --target compares PSA with a target spectrum
// (ratios on stderr, the target dashed on the plot).
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/errors.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/ground/spectrum_matching.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/plots.hpp"
#include "adjoin/post/spectrum.hpp"
#include "command.hpp"
#include "reading_options.hpp"

namespace adjoin::cli {
namespace {

namespace fs = std::filesystem;

struct SpectrumArgs : ReadingArgs {
  std::string record;
  std::string damping = "0.05";
  std::string periods;
  std::string range;
  std::string peaks = "exact";
  bool free_vibration = false;
  unsigned threads = 0;
  std::string out;
  std::string plot;
  std::string target;
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

bool parse_number(const std::string& token, double* value) {
  const std::string t = trim(token);
  if (t.empty()) return false;
  const char* first = t.data();
  if (*first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, t.data() + t.size(), *value);
  return ec == std::errc() && ptr == t.data() + t.size() && std::isfinite(*value);
}

std::vector<double> parse_list(const std::string& option, const std::string& text, const std::string& expected) {
  std::vector<double> values;
  for (const std::string& token : split(text, ',')) {
    double v = 0.0;
    if (!parse_number(token, &v))
      throw InputError(option + " " + text + ": '" + trim(token) + "' is not a number (expected " + expected + ")");
    values.push_back(v);
  }
  if (values.empty()) throw InputError(option + ": empty list (expected " + expected + ")");
  return values;
}

std::vector<double> parse_range(const std::string& text) {
  const std::string expected = "T0:T1:N[:log|lin], e.g. 0.02:5:100:log, with 0 <= T0 < T1 (T0 > 0 for log) and N >= 2";
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() != 3 && parts.size() != 4) throw InputError("--range " + text + ": expected " + expected);
  double first = 0.0, last = 0.0, count = 0.0;
  if (!parse_number(parts[0], &first) || !parse_number(parts[1], &last) || !parse_number(parts[2], &count))
    throw InputError("--range " + text + ": not numbers (expected " + expected + ")");
  PeriodSpacing spacing = PeriodSpacing::log;
  if (parts.size() == 4) {
    const std::string s = trim(parts[3]);
    if (s == "log") spacing = PeriodSpacing::log;
    else if (s == "lin" || s == "linear") spacing = PeriodSpacing::linear;
    else throw InputError("--range " + text + ": unknown spacing '" + s + "' (expected log or lin)");
  }
  if (!(first >= 0.0 && first < last) || count < 2.0 || count != std::floor(count) || count > 1e6 ||
      (spacing == PeriodSpacing::log && first <= 0.0))
    throw InputError("--range " + text + ": expected " + expected);
  return period_range(first, last, static_cast<std::size_t>(count), spacing);
}

void write_csv(std::ostream& out, const ResponseSpectrum& spectrum) {
  out << "period,damping,sd,sv,sa,psv,psa\n";
  char line[256];
  for (const SpectralValues& v : spectrum.values) {
    std::snprintf(line, sizeof line, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", v.period, v.damping, v.sd,
                  v.sv, v.sa, v.psv, v.psa);
    out << line;
  }
}

// Prints, for each damping, how the record's PSA compares with the target over the periods
// the target covers (on stderr: stdout may hold the CSV), and returns the target's curves for
// the plot. An EC8 target is the code's spectrum at each damping (eta); a table is the same
// at every damping.
std::vector<ReferenceCurve> compare_with_target(const ResponseSpectrum& spectrum, const TargetSpectrum& target) {
  std::vector<ReferenceCurve> curves;
  for (std::size_t d = 0; d < spectrum.dampings.size(); ++d) {
    const double zeta = spectrum.dampings[d];
    ReferenceCurve curve;
    char label[96];
    std::snprintf(label, sizeof label, "%s (%g %%)", target.name.c_str(), 100.0 * zeta);
    curve.label = label;
    double low = 0.0, high = 0.0, sum = 0.0, t_low = 0.0, t_high = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < spectrum.periods.size(); ++i) {
      const double period = spectrum.periods[i];
      if (!(period > 0.0) || period < target.min_period() || period > target.max_period()) continue;
      const double psa = target.psa_at(period, zeta), ratio = spectrum.at(d, i).psa / psa;
      curve.period.push_back(period);
      curve.psa.push_back(psa);
      if (count == 0 || ratio < low) low = ratio, t_low = period;
      if (count == 0 || ratio > high) high = ratio, t_high = period;
      sum += ratio;
      ++count;
    }
    if (count == 0) {
      std::cerr << "target " << target.name << ": no period of the spectrum is inside the target's\n";
      return {};
    }
    std::fprintf(stderr, "target %s, damping %g %%: PSA/target from %.4g (T = %g s) to %.4g (T = %g s), mean %.4g over %zu periods\n",
                 target.name.c_str(), 100.0 * zeta, low, t_low, high, t_high, sum / static_cast<double>(count), count);
    curves.push_back(std::move(curve));
  }
  return curves;
}

int spectrum_command(const SpectrumArgs& args) {
  const RecordFormat format = format_from(args);

  SpectrumOptions options;
  options.dampings = parse_list("--damping", args.damping, "damping ratios in [0, 1) separated by commas, e.g. 0.05,0.02");
  for (double z : options.dampings)
    if (!(z >= 0.0 && z < 1.0))
      throw InputError("--damping " + args.damping + ": damping ratios must be in [0, 1) (0.05 is 5 %)");
  if (!args.periods.empty()) {
    options.periods = parse_list("--periods", args.periods, "periods in s, >= 0, separated by commas");
    for (double t : options.periods)
      if (!(t >= 0.0)) throw InputError("--periods " + args.periods + ": periods must be >= 0 s");
  } else if (!args.range.empty()) {
    options.periods = parse_range(args.range);
  }
  if (args.peaks == "samples") {
    // The recursion is exact at any step, so one step per sample gives the response at the
    // samples exactly; only the peaks between samples are not looked for.
    options.refine_peaks = false;
    options.max_substeps = 1;
  } else if (args.peaks != "exact") {
    throw InputError("--peaks " + args.peaks + ": expected exact or samples");
  }
  options.free_vibration = args.free_vibration;
  options.threads = args.threads;
  PlotStyle style;  // PSA over SD: a taller figure
  style.height = 900;
  if (!args.plot.empty()) plot_target(args.plot, {}, "", &style, "--plot");
  std::string error;
  if (!options.IsValid(&error)) throw InputError("--periods/--range/--damping: " + error);
  std::optional<TargetSpectrum> target;
  if (!args.target.empty()) {
    try {
      target = parse_target_spectrum(args.target);
    } catch (const InputError& e) {
      throw InputError(std::string("--target: ") + e.what());
    }
  }

  const Record record = read_record(args.record, format);
  const ResponseSpectrum spectrum = response_spectrum(record, options);

  if (!args.out.empty()) {
    AtomicFile file(args.out);
    write_csv(file.stream(), spectrum);
    file.commit();
  } else {
    write_csv(std::cout, spectrum);
    std::cout.flush();
  }

  std::vector<ReferenceCurve> references;
  if (target) references = compare_with_target(spectrum, *target);

  if (!args.plot.empty()) {
    bool any_positive = false;
    for (double t : spectrum.periods) any_positive = any_positive || t > 0.0;
    if (!any_positive) throw InputError("--plot " + args.plot + ": needs at least one period > 0 s");
    return draw_figure(
        [&] { plot_spectrum(spectrum, args.plot, style, fs::path(args.record).filename().string(), references); },
        args.out.empty() ? "the spectrum was printed" : "the spectrum was written to " + args.out);
  }
  return 0;
}

const Registration registration(20, [](CLI::App& app) -> Runner {
  auto args = std::make_shared<SpectrumArgs>();
  auto* sub = app.add_subcommand(
      "spectrum",
      "Elastic response spectra of a record: CSV period,damping,sd,sv,sa,psv,psa (s, -, m, m/s, g, m/s, g)");
  sub->add_option("record", args->record, "Accelerogram (PEER AT2, one/two-column text, CSV)")->required();
  add_reading_options(sub, args.get());
  sub->add_option("--damping", args->damping, "Damping ratios, comma separated (default 0.05)");
  auto* periods = sub->add_option("--periods", args->periods, "Periods [s], comma separated (0: rigid, SA = PGA)");
  auto* range = sub->add_option("--range", args->range,
                                "Periods T0:T1:N[:log|lin] (default 0.01:10:100:log)");
  periods->excludes(range);
  sub->add_option("--peaks", args->peaks,
                  "exact (default): peaks of the exact response between samples too; samples: at the "
                  "record's samples only, as tools that sample the response report them");
  sub->add_flag("--free-vibration", args->free_vibration,
                "Also look for peaks in one period of free vibration after the record");
  sub->add_option("--threads", args->threads, "Worker threads (default 0: all cores)");
  sub->add_option("--out", args->out, "CSV file (default: stdout)");
  sub->add_option("--plot", args->plot, "Also draw PSA and SD against period with gnuplot (.png or .svg)");
  sub->add_option("--target", args->target,
                  "Compare PSA with a target spectrum: ec8:T[:AG[:TYPE]] or a two-column file period [s], PSA [g] "
                  "(ratios on stderr; dashed on the plot)");
  return [args]() { return spectrum_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
