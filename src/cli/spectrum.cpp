// adjoin spectrum RECORD [--units g|m/s2|cm/s2|mm/s2] [--format KIND] [--dt S]
//                        [--damping 0.05[,0.02...]] [--periods LIST | --range T0:T1:N[:log|lin]]
//                        [--peaks exact|samples] [--target ec8:T[:AG[:TYPE]]|FILE]
//                        [--free-vibration] [--threads N] [--out FILE] [--plot FILE.png|.svg]
// adjoin spectrum H1 H2 --rotd 50,100 [--components] [reading, period, damping options]
// adjoin spectrum RECORD --ductility 1,2,4,6 [--hysteresis epp|bilinear] [--hardening 0.05]
// adjoin spectrum RECORD --strength-reduction 2,4 | --yield-coefficient 0.1,0.2 [--hysteresis ...]
//
// Elastic response spectra of a recorded accelerogram (SPEC §3): CSV with header
// `period,damping,sd,sv,sa,psv,psa` (s, ratio, m, m/s, g, m/s, g), one row per damping and
// period, to FILE (temporary file and rename) or stdout. --plot draws PSA and SD against
// period with gnuplot. Without gnuplot on PATH the CSV is still written and the command
// fails (exit 2) with a message saying so. --target compares PSA with a target spectrum
// (ratios on stderr, the target dashed on the plot).
//
// Two records (the horizontal components of one station, same dt; the shorter is padded with
// zeros, with a warning): orientation-independent spectra (post/rotd.hpp), CSV
// `period,damping,rotd00,rotd50,rotd100,angle00,angle100,gmroti50` (PSA in g, angles in
// degrees from the first component towards the second), then `rotdNN` for any other
// percentile of --rotd, then `psa_h1,psa_h2` with --components; the GMRotI50 angle on stderr.
// --ductility: constant-ductility spectra (post/inelastic.hpp), CSV
// `period,damping,ductility,cy,uy,R,ductility_reached`. --strength-reduction R or
// --yield-coefficient cy: the constant-strength inverse, CSV `period,damping,R,cy,uy,ductility`.
// --suite (or a folder among the records): a suite of records, spectrum_suite.cpp.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/spectrum_plots.hpp"
#include "adjoin/post/inelastic.hpp"
#include "adjoin/post/rotd.hpp"
#include "adjoin/post/spectrum.hpp"
#include "command.hpp"
#include "reading_options.hpp"
#include "spectrum_suite.hpp"

namespace adjoin::cli {

void write_spectrum_csv(std::ostream& out, const ResponseSpectrum& spectrum) {
  out << "period,damping,sd,sv,sa,psv,psa\n";
  char line[256];
  for (const SpectralValues& v : spectrum.values) {
    std::snprintf(line, sizeof line, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", v.period, v.damping, v.sd,
                  v.sv, v.sa, v.psv, v.psa);
    out << line;
  }
}

namespace {

namespace fs = std::filesystem;

struct SpectrumArgs : ReadingArgs {
  std::vector<std::string> records;
  std::string rotd;  // percentiles; empty: not asked
  bool components = false;
  std::string ductility, strength_reduction, yield_coefficient;
  std::string hysteresis;
  std::string hardening;  // empty: not given
  std::string damping = "0.05";
  std::string periods;
  std::string range;
  std::string peaks = "exact";
  bool free_vibration = false;
  unsigned threads = 0;
  std::string out;
  std::string plot;
  std::string target;
  bool suite = false;
  std::string t1, band, scaling;  // empty: not given
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

std::string trim(const std::string& s) { return std::string(trim_blanks(s)); }

bool parse_number(const std::string& token, double* value) { return parse_finite(trim(token), value); }

std::vector<double> parse_list(const std::string& option, const std::string& text, const std::string& expected) {
  std::vector<double> values;
  for (const std::string& token : split(text, ',')) {
    double v = 0.0;
    if (!parse_number(token, &v))
      throw InputError(option + " " + text_excerpt(text) + ": " + escaped_excerpt(trim(token)) + " is not a number (expected " + expected + ")");
    values.push_back(v);
  }
  if (values.empty()) throw InputError(option + ": empty list (expected " + expected + ")");
  // A value listed twice would be computed and written twice.
  for (auto v = values.begin(); v != values.end(); ++v)
    if (std::find(values.begin(), v, *v) != v)
      throw InputError(option + " " + text_excerpt(text) + ": " + (std::ostringstream() << *v).str() +
                       " is listed twice; list each value once");
  return values;
}

std::vector<double> parse_range(const std::string& text) {
  const std::string expected = "T0:T1:N[:log|lin], e.g. 0.02:5:100:log, with 0 <= T0 < T1 (T0 > 0 for log) and N >= 2";
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() != 3 && parts.size() != 4) throw InputError("--range " + text_excerpt(text) + ": expected " + expected);
  double first = 0.0, last = 0.0, count = 0.0;
  if (!parse_number(parts[0], &first) || !parse_number(parts[1], &last) || !parse_number(parts[2], &count))
    throw InputError("--range " + text_excerpt(text) + ": not numbers (expected " + expected + ")");
  PeriodSpacing spacing = PeriodSpacing::log;
  if (parts.size() == 4) {
    const std::string s = trim(parts[3]);
    if (!parse_enum(s, &spacing))
      throw InputError("--range " + text_excerpt(text) + ": unknown spacing " + escaped_excerpt(s) + " (expected " +
                       join_names(names<PeriodSpacing>(), "", ", ", " or ") + ")");
  }
  if (!(first >= 0.0 && first < last) || count < 2.0 || count != std::floor(count) || count > 1e6 ||
      (spacing == PeriodSpacing::log && first <= 0.0))
    throw InputError("--range " + text_excerpt(text) + ": expected " + expected);
  return period_range(first, last, static_cast<std::size_t>(count), spacing);
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

int rotd_command(const SpectrumArgs& args, const SpectrumOptions& elastic, const PlotStyle& style);
int inelastic_command(const SpectrumArgs& args, const SpectrumOptions& elastic, const PlotStyle& style);
int suite_spectra(const SpectrumArgs& args, const SpectrumOptions& elastic, PlotStyle style,
                  std::optional<TargetSpectrum> target);

int spectrum_command(const SpectrumArgs& args) {
  const RecordFormat format = format_from(args);

  SpectrumOptions options;
  options.dampings = parse_list("--damping", args.damping, "damping ratios in [0, 1) separated by commas, e.g. 0.05,0.02");
  for (double z : options.dampings)
    if (!(z >= 0.0 && z < 1.0))
      throw InputError("--damping " + text_excerpt(args.damping) + ": damping ratios must be in [0, 1) (0.05 is 5 %)");
  if (!args.periods.empty()) {
    options.periods = parse_list("--periods", args.periods, "periods in s, >= 0, separated by commas");
    for (double t : options.periods)
      if (!(t >= 0.0)) throw InputError("--periods " + text_excerpt(args.periods) + ": periods must be >= 0 s");
  } else if (!args.range.empty()) {
    options.periods = parse_range(args.range);
  }
  if (args.peaks == "samples") {
    // The recursion is exact at any step, so one step per sample gives the response at the
    // samples exactly; only the peaks between samples are not looked for.
    options.refine_peaks = false;
    options.max_substeps = 1;
  } else if (args.peaks != "exact") {
    throw InputError("--peaks " + text_excerpt(args.peaks) + ": expected exact or samples");
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

  const bool inelastic = !args.ductility.empty() || !args.strength_reduction.empty() || !args.yield_coefficient.empty();
  bool folder = false;
  for (const std::string& r : args.records) {
    std::error_code ec;
    folder = folder || fs::is_directory(r, ec);
  }
  if (args.suite || folder) {
    if (!args.rotd.empty() || args.components) throw InputError("--rotd/--components: for a pair of components, not a --suite");
    if (inelastic) throw InputError("--ductility/--strength-reduction/--yield-coefficient: not available for a --suite");
    return suite_spectra(args, options, style, std::move(target));
  }
  if (!args.t1.empty() || !args.band.empty() || !args.scaling.empty())
    throw InputError(std::string(!args.t1.empty() ? "--t1" : !args.band.empty() ? "--band" : "--scaling") +
                     ": scales a suite of records (give --suite)");
  if (args.records.size() > 2)
    throw InputError(std::to_string(args.records.size()) +
                     " records: give --suite for a suite (one record gives its spectrum, two with --rotd a pair)");
  if (args.records.size() == 2 || !args.rotd.empty()) {
    if (inelastic) throw InputError("--ductility/--strength-reduction/--yield-coefficient: give one record (two are for --rotd)");
    if (target) throw InputError("--target " + text_excerpt(args.target) + ": compares one record's elastic spectrum (not --rotd)");
    if (options.free_vibration) throw InputError("--free-vibration: not available with --rotd");
    return rotd_command(args, options, style);
  }
  if (inelastic) {
    if (target) throw InputError("--target " + text_excerpt(args.target) + ": compares the elastic spectrum (not inelastic spectra)");
    if (options.free_vibration) throw InputError("--free-vibration: not available for inelastic spectra");
    if (args.peaks != "exact") throw InputError("--peaks " + text_excerpt(args.peaks) + ": inelastic spectra always locate peaks exactly");
    return inelastic_command(args, options, style);
  }
  if (!args.hysteresis.empty() || !args.hardening.empty())
    throw InputError(std::string(args.hysteresis.empty() ? "--hardening" : "--hysteresis") +
                     ": for inelastic spectra (give --ductility, --strength-reduction or --yield-coefficient)");
  if (args.components) throw InputError("--components: for --rotd (two records)");

  const std::string& record_file = args.records.at(0);
  const Record record = read_record(record_file, format);
  const ResponseSpectrum spectrum = response_spectrum(record, options);

  if (!args.out.empty()) {
    AtomicFile file(args.out);
    write_spectrum_csv(file.stream(), spectrum);
    file.commit();
  } else {
    write_spectrum_csv(std::cout, spectrum);
    std::cout.flush();
  }

  std::vector<ReferenceCurve> references;
  if (target) references = compare_with_target(spectrum, *target);

  if (!args.plot.empty()) {
    bool any_positive = false;
    for (double t : spectrum.periods) any_positive = any_positive || t > 0.0;
    if (!any_positive) throw InputError("--plot " + text_excerpt(args.plot) + ": needs at least one period > 0 s");
    return draw_figure(
        [&] { plot_spectrum(spectrum, args.plot, style, fs::path(record_file).filename().string(), references); },
        args.out.empty() ? "the spectrum was printed" : "the spectrum was written to " + args.out);
  }
  return 0;
}


// --out FILE (temporary file and rename) or stdout.
void emit(const std::string& out, const std::string& text) {
  if (!out.empty()) {
    AtomicFile file(out);
    file.stream() << text;
    file.commit();
  } else {
    std::cout << text;
    std::cout.flush();
    if (!std::cout) throw InputError("cannot write to standard output");
  }
}

std::string row(const std::vector<double>& values) {
  std::string line;
  char cell[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(cell, sizeof cell, "%s%.10g", i ? "," : "", values[i]);
    line += cell;
  }
  return line + "\n";
}

// Curves y(period) on a log period axis, one per label.
struct Curve {
  std::string label;
  std::vector<double> period, value;
};
void plot_curves(const std::string& image, const PlotStyle& style, const std::string& title, const std::string& ylabel,
                 const std::vector<Curve>& curves) {
  std::ostringstream s;
  std::string plots;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    s << "$c" << c << " << EOD\n";
    for (std::size_t i = 0; i < curves[c].period.size(); ++i)
      if (curves[c].period[i] > 0.0) s << curves[c].period[i] << " " << curves[c].value[i] << "\n";
    s << "EOD\n";
    plots += (c ? ", " : "") + std::string("$c") + std::to_string(c) + " using 1:2 with lines linewidth 2 title " +
             gnuplot_quote(curves[c].label);
  }
  s << "set title " << gnuplot_quote(title) << " noenhanced\nset logscale x\nset format x '%g'\n"
    << "set grid xtics mxtics ytics lc rgb '#d0d0d0'\nset xlabel 'period T [s]'\nset ylabel "
    << gnuplot_quote(ylabel) << "\nset key top right noenhanced\nplot " << plots << "\n";
  render_gnuplot(s.str(), image, style);
}

// The two components: the same dt (relative 1e-9), the shorter padded with zeros (warning).
std::pair<Record, Record> read_pair(const SpectrumArgs& args) {
  const RecordFormat format = format_from(args);
  Record a = read_record(args.records.at(0), format), b = read_record(args.records.at(1), format);
  if (!(std::abs(a.dt - b.dt) <= 1e-9 * std::max(a.dt, b.dt))) {
    std::ostringstream out;
    out << args.records[0] << " (dt = " << a.dt << " s) and " << args.records[1] << " (dt = " << b.dt
        << " s): the two components must have the same time step (resample one with `adjoin record process "
           "--resample`)";
    throw InputError(out.str());
  }
  if (a.accel.size() != b.accel.size()) {
    const bool first_shorter = a.accel.size() < b.accel.size();
    std::cerr << "warning: " << args.records[first_shorter ? 0 : 1] << " has "
              << (first_shorter ? a : b).accel.size() << " samples, " << args.records[first_shorter ? 1 : 0]
              << " has " << (first_shorter ? b : a).accel.size() << ": the shorter is padded with zeros at its end\n";
    const std::size_t n = std::max(a.accel.size(), b.accel.size());
    a.accel.resize(n, 0.0);
    b.accel.resize(n, 0.0);
  }
  return {std::move(a), std::move(b)};
}

int rotd_command(const SpectrumArgs& args, const SpectrumOptions& elastic, const PlotStyle& style) {
  if (args.records.size() != 2)
    throw InputError("--rotd: needs two records (the two horizontal components of one station), got one");
  RotDOptions options;
  options.periods = elastic.periods;
  options.dampings = elastic.dampings;
  options.points_per_period = elastic.points_per_period;
  options.max_substeps = elastic.max_substeps;
  options.refine_peaks = elastic.refine_peaks;
  options.threads = elastic.threads;
  const std::string expected = "percentiles from 0 to 100 separated by commas, e.g. 50,100";
  if (!args.rotd.empty())
    for (double p : parse_list("--rotd", args.rotd, expected)) {
      if (!(p >= 0.0 && p <= 100.0)) throw InputError("--rotd " + text_excerpt(args.rotd) + ": expected " + expected);
      if (p != 0.0 && p != 50.0 && p != 100.0 &&
          std::find(options.percentiles.begin(), options.percentiles.end(), p) == options.percentiles.end())
        options.percentiles.push_back(p);
    }
  std::string error;
  if (!options.IsValid(&error)) throw InputError("--rotd: " + error);
  const auto [h1, h2] = read_pair(args);
  const RotDSpectrum s = rotd_spectrum(h1, h2, options);

  std::string text = "period,damping,rotd00,rotd50,rotd100,angle00,angle100,gmroti50";
  char name[48];
  for (double p : options.percentiles) {
    std::snprintf(name, sizeof name, ",rotd%02g", p);
    text += name;
  }
  if (args.components) text += ",psa_h1,psa_h2";
  text += "\n";
  for (const RotDValues& v : s.values) {
    std::vector<double> cells{v.period, v.damping, v.rotd00, v.rotd50, v.rotd100, v.angle00, v.angle100, v.gmroti50};
    cells.insert(cells.end(), v.extra.begin(), v.extra.end());
    if (args.components) cells.insert(cells.end(), {v.psa1, v.psa2});
    text += row(cells);
  }
  emit(args.out, text);
  for (std::size_t d = 0; d < s.dampings.size(); ++d)
    std::fprintf(stderr, "GMRotI50, damping %g %%: angle %g degrees from %s\n", 100.0 * s.dampings[d],
                 s.gmroti50_angle[d], args.records[0].c_str());

  if (args.plot.empty()) return 0;
  std::vector<Curve> curves;
  for (std::size_t d = 0; d < s.dampings.size(); ++d) {
    char suffix[32] = "";
    if (s.dampings.size() > 1) std::snprintf(suffix, sizeof suffix, " (%g %%)", 100.0 * s.dampings[d]);
    Curve c00{std::string("RotD00") + suffix, {}, {}}, c50{std::string("RotD50") + suffix, {}, {}},
        c100{std::string("RotD100") + suffix, {}, {}}, gm{std::string("GMRotI50") + suffix, {}, {}};
    for (std::size_t i = 0; i < s.periods.size(); ++i) {
      const RotDValues& v = s.at(d, i);
      for (Curve* c : {&c00, &c50, &c100, &gm}) c->period.push_back(v.period);
      c00.value.push_back(v.rotd00);
      c50.value.push_back(v.rotd50);
      c100.value.push_back(v.rotd100);
      gm.value.push_back(v.gmroti50);
    }
    curves.insert(curves.end(), {c00, c50, c100, gm});
  }
  return draw_figure(
      [&] {
        plot_curves(args.plot, style,
                    "RotD spectra: " + fs::path(args.records[0]).filename().string() + " + " +
                        fs::path(args.records[1]).filename().string(),
                    "PSA [g]", curves);
      },
      args.out.empty() ? "the spectrum was printed" : "the spectrum was written to " + args.out);
}

int inelastic_command(const SpectrumArgs& args, const SpectrumOptions& elastic, const PlotStyle& style) {
  const int given = !args.ductility.empty() + !args.strength_reduction.empty() + !args.yield_coefficient.empty();
  if (given > 1) throw InputError("--ductility, --strength-reduction, --yield-coefficient: give one of them");
  InelasticOptions options;
  for (double t : elastic.periods)
    if (t == 0.0) throw InputError("--periods: inelastic spectra need periods > 0 s (0 is the rigid oscillator)");
  options.periods = elastic.periods;
  options.dampings = elastic.dampings;
  options.threads = elastic.threads;
  if (!args.hysteresis.empty() && !parse_enum(args.hysteresis, &options.hysteresis))
    throw InputError("--hysteresis " + text_excerpt(args.hysteresis) + ": expected " + join_names(names<Hysteresis>(), "", ", ", " or "));
  if (options.hysteresis == Hysteresis::elastic_perfectly_plastic) {
    if (!args.hardening.empty())
      throw InputError("--hardening " + text_excerpt(args.hardening) + ": for --hysteresis bilinear (epp has no hardening)");
  } else {
    options.hardening = 0.05;
    if (!args.hardening.empty()) {
      double alpha = 0.0;
      if (!parse_number(args.hardening, &alpha) || !(alpha >= 0.0 && alpha < 1.0))
        throw InputError("--hardening " + text_excerpt(args.hardening) + ": expected the post-yield stiffness ratio in [0, 1), e.g. 0.05");
      options.hardening = alpha;
    }
  }
  std::vector<double> strengths;
  StrengthMeasure measure = StrengthMeasure::reduction_factor;
  if (!args.ductility.empty()) {
    const std::string expected = "target ductilities from 1 to 100 separated by commas, e.g. 1,2,4,6";
    options.ductilities = parse_list("--ductility", args.ductility, expected);
    for (double mu : options.ductilities)
      if (!(mu >= 1.0 && mu <= 100.0)) throw InputError("--ductility " + text_excerpt(args.ductility) + ": expected " + expected);
  } else {
    const bool r = !args.strength_reduction.empty();
    const std::string option = r ? "--strength-reduction" : "--yield-coefficient";
    const std::string& text = r ? args.strength_reduction : args.yield_coefficient;
    const std::string expected = r ? "strength reduction factors R = fe/fy > 0, e.g. 2,4"
                                   : "yield strength coefficients cy = fy/(m g) > 0, e.g. 0.1,0.2";
    strengths = parse_list(option, text, expected);
    for (double x : strengths)
      if (!(x > 0.0 && x <= 1e6)) throw InputError(option + " " + text_excerpt(text) + ": expected " + expected + " (at most 1e6)");
    measure = r ? StrengthMeasure::reduction_factor : StrengthMeasure::yield_coefficient;
  }
  std::string error;
  if (!options.IsValid(&error)) throw InputError("--periods/--range/--damping/--hardening: " + error);

  const std::string& file = args.records.at(0);
  const Record record = read_record(file, format_from(args));
  const bool ductility = !args.ductility.empty();
  const InelasticSpectrum s = ductility ? constant_ductility_spectrum(record.dt, record.accel, options)
                                        : constant_strength_spectrum(record.dt, record.accel, strengths, measure, options);
  std::string text = ductility ? "period,damping,ductility,cy,uy,R,ductility_reached\n" : "period,damping,R,cy,uy,ductility\n";
  for (const InelasticValues& v : s.values)
    text += ductility ? row({v.period, v.damping, v.ductility, v.cy, v.uy, v.R, v.ductility_reached})
                      : row({v.period, v.damping, v.R, v.cy, v.uy, v.ductility});
  emit(args.out, text);

  if (args.plot.empty()) return 0;
  std::vector<Curve> curves;
  const std::size_t per = ductility ? s.ductilities.size() : strengths.size();
  for (std::size_t d = 0; d < s.dampings.size(); ++d)
    for (std::size_t k = 0; k < per; ++k) {
      char label[96];
      const double key = ductility ? s.ductilities[k] : strengths[k];
      const char* name = ductility ? "mu" : (measure == StrengthMeasure::reduction_factor ? "R" : "cy");
      if (s.dampings.size() > 1)
        std::snprintf(label, sizeof label, "%s = %g (%g %%)", name, key, 100.0 * s.dampings[d]);
      else
        std::snprintf(label, sizeof label, "%s = %g", name, key);
      Curve c{label, {}, {}};
      for (std::size_t i = 0; i < s.periods.size(); ++i) {
        const InelasticValues& v = s.values[(d * s.periods.size() + i) * per + k];
        c.period.push_back(v.period);
        c.value.push_back(ductility ? v.cy : v.ductility);
      }
      curves.push_back(std::move(c));
    }
  return draw_figure(
      [&] {
        plot_curves(args.plot, style,
                    std::string(ductility ? "Constant-ductility spectra: " : "Constant-strength spectra: ") +
                        fs::path(file).filename().string(),
                    ductility ? "yield strength coefficient cy = fy/(m g)" : "ductility demand", curves);
      },
      args.out.empty() ? "the spectrum was printed" : "the spectrum was written to " + args.out);
}

// The suite's own options; the rest was checked by spectrum_command.
int suite_spectra(const SpectrumArgs& args, const SpectrumOptions& elastic, PlotStyle style,
                  std::optional<TargetSpectrum> target) {
  SuiteRequest request;
  request.inputs = args.records;
  request.format = format_from(args);
  request.options = elastic;
  request.out = args.out;
  request.plot = args.plot;  // checked up front (plot_target)
  style.height = 600;         // one panel, PSA
  request.style = style;
  if (!args.t1.empty() && !args.band.empty())
    throw InputError("--t1 " + text_excerpt(args.t1) + " and --band " + text_excerpt(args.band) +
                     ": give one (--t1 T scales over 0.2 T ... 2 T; --band TA,TB over TA ... TB)");
  if (!args.t1.empty() || !args.band.empty()) {
    SuiteScalingOptions scaling;
    const std::string option = !args.t1.empty() ? "--t1 " + text_excerpt(args.t1) : "--band " + text_excerpt(args.band);
    if (!args.t1.empty() && (!parse_number(args.t1, &scaling.t1) || !(scaling.t1 > 0.0 && scaling.t1 <= 1e4)))
      throw InputError(option + ": expected the fundamental period T1 in s, 0 < T1 <= 1e4");
    if (!args.band.empty()) {
      const auto ends = split(args.band, ',');
      if (ends.size() != 2 || !parse_number(ends[0], &scaling.band_from) || !parse_number(ends[1], &scaling.band_to) ||
          !(scaling.band_from > 0.0 && scaling.band_from < scaling.band_to && scaling.band_to <= 1e4))
        throw InputError(option + ": expected two periods TA,TB in s, 0 < TA < TB <= 1e4 (e.g. 0.1,4: 0.2 of the "
                                  "shorter and 2 of the longer fundamental period of two buildings)");
    }
    if (!target) throw InputError(option + ": scales the suite to a target: give --target too");
    if (!args.scaling.empty() && !parse_enum(args.scaling, &scaling.rule))
      throw InputError("--scaling " + text_excerpt(args.scaling) + ": expected " + join_names(names<SuiteScaling>(), "", ", ", " or "));
    request.scaling = scaling;
  } else if (!args.scaling.empty()) {
    throw InputError("--scaling " + text_excerpt(args.scaling) +
                     ": chooses how --t1 or --band scales the suite (give --t1 or --band, and --target)");
  }
  request.target = std::move(target);
  return suite_command(request);
}

const Registration registration(20, "spectrum", "Elastic response spectra of a record: CSV period,damping,sd,sv,sa,psv,psa (s, -, m, m/s, g, m/s, g)",
                                [](CLI::App* sub) -> Runner {
  auto args = std::make_shared<SpectrumArgs>();
  sub->add_option("records", args->records,
                  "Accelerogram (PEER AT2, SMC, ..., column text); two for --rotd (the horizontal components); "
                  "several, or folders of them, with --suite")
      ->required()
      ->expected(-1);
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
  sub->add_option("--out", args->out, "CSV file (default: stdout); with --suite the folder for the suite's files");
  sub->add_option("--plot", args->plot, "Also draw PSA and SD against period with gnuplot (.png or .svg)");
  sub->add_option("--target", args->target,
                  "Compare PSA with a target spectrum: ec8:T[:AG[:TYPE]] or a two-column file period [s], PSA [g] "
                  "(ratios on stderr; dashed on the plot)");
  sub->add_option("--rotd", args->rotd,
                  "Two records: orientation-independent spectra RotD00/50/100 with their angles and GMRotI50, and "
                  "these percentiles too (e.g. 50,100 or 84)");
  sub->add_flag("--components", args->components, "With --rotd: also the two components' own PSA (psa_h1,psa_h2)");
  sub->add_option("--ductility", args->ductility,
                  "Constant-ductility spectra for these target ductilities (e.g. 1,1.5,2,3,4,6): "
                  "period,damping,ductility,cy,uy,R,ductility_reached");
  sub->add_option("--strength-reduction", args->strength_reduction,
                  "Constant-strength spectra: the ductility demand at these R = fe/fy (e.g. 2,4)");
  sub->add_option("--yield-coefficient", args->yield_coefficient,
                  "Constant-strength spectra: the ductility demand at these cy = fy/(m g) (e.g. 0.1,0.2)");
  sub->add_option("--hysteresis", args->hysteresis,
                  "Inelastic spectra: epp (elastic-perfectly-plastic, default) or bilinear");
  sub->add_option("--hardening", args->hardening,
                  "Bilinear: post-yield stiffness ratio in [0, 1) (default 0.05)");
  sub->add_flag("--suite", args->suite,
                "A suite: the records (files, or folders of them) with their mean, median and +-1 sigma in log, "
                "written to --out DIR (a folder among the records implies it)");
  sub->add_option("--t1", args->t1,
                  "Suite: scale it to --target so that its mean is >= 90 % of the target over 0.2 T1 ... 2 T1 [s]");
  sub->add_option("--band", args->band,
                  "Suite: scale it to --target so that its mean is >= 90 % of the target over the band TA,TB [s] "
                  "(two buildings: 0.2 of the shorter, 2 of the longer fundamental period); instead of --t1");
  sub->add_option("--scaling", args->scaling,
                  "Suite with --t1 or --band: fit (default: each record fitted to the target, then one common multiplier) "
                  "or uniform (one factor for all)");
  return [args]() { return spectrum_command(*args); };
});

}  // namespace
}  // namespace adjoin::cli
