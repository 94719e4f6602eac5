// adjoin record info FILE... [--units U] [--dt DT] [--format F] [--time-column C]
//                            [--accel-column C] [--delimiter D] [--json] [--out FILE]
// adjoin record process FILE [reading options] [--window T0:T1] [--baseline N] [--pad B:A]
//                       [--highpass F | --lowpass F | --bandpass F1:F2] [--filter-order N]
//                       [--resample DT] [--scale-pga G] --out FILE
// adjoin record fourier FILE [reading options] [--smooth B] [--frequencies F0:F1:N]
//                       [--out FILE] [--plot FILE.png|.svg]
//
// `fourier` writes the Fourier amplitude spectrum as CSV `frequency,amplitude` (Hz, m/s): at
// the FFT frequencies k / (n dt), or, with --smooth or --frequencies, Konno-Ohmachi smoothed
// (bandwidth B, default 40) at N log-spaced frequencies (default 200 from 0.1 Hz, or the
// lowest FFT frequency above it, to 50 Hz or the Nyquist frequency).
//
// `process` applies what scenes can ask for (ground/processing.hpp, in that order: window,
// baseline, padding, zero-phase Butterworth, resampling, scaling) and writes two columns,
// t [s] and a [g], that the readers take back; then prints the result's intensity measures.
// With --integrate it writes CSV with a header line instead, "t [s],a [g],v [m/s],d [m]":
// velocity and displacement by the trapezoid rule from rest (ground/integration.hpp), after
// the processing asked for (so --baseline N corrects the drift of an offset); the readers take
// the acceleration back from it (the "a [g]" column, found by name).
//
// Reads accelerograms and prints their intensity measures: npts, dt, duration, PGA [g],
// PGV [m/s], PGD [m] (trapezoid integrals, no baseline correction), Arias intensity [m/s],
// CAV [m/s], significant duration D5-95 [s], predominant period [s] (peak of the Fourier
// amplitude spectrum), Housner's spectrum intensity [m] and Von Thun's ASI [g s]. As a table
// (one block per file) or JSON (an object, or an array for several files), to stdout or to
// FILE (temporary file and rename).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/ground/integration.hpp"
#include "adjoin/ground/processing.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/ground/synthesis.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/plots.hpp"
#include "adjoin/io/record_writer.hpp"
#include "adjoin/io/spectrum_plots.hpp"
#include "adjoin/post/intensity.hpp"
#include "adjoin/post/rotd.hpp"
#include "adjoin/post/spectrum.hpp"
#include "command.hpp"
#include "reading_options.hpp"

namespace adjoin::cli {
namespace {

struct RecordArgs : ReadingArgs {
  std::vector<std::string> files;
  bool json = false;
  std::string out;
  // process
  std::string window, pad, bandpass;
  double highpass = 0.0, lowpass = 0.0, resample = 0.0, scale_pga = 0.0;
  int baseline = -1, filter_order = 4;
  bool integrate = false;
  // fourier
  double smooth = 0.0;  // 0: not asked
  std::string frequencies, plot;
};


std::string number(double x, int precision = 6) {
  std::ostringstream s;
  s << std::setprecision(precision) << x;
  return s.str();
}

nlohmann::json to_json(const Record& record, const IntensityMeasures& m, const SpectrumIntensity& si) {
  return nlohmann::json{{"file", record.source},
                        {"description", record.description},
                        {"npts", m.npts},
                        {"dt_s", m.dt},
                        {"duration_s", m.duration},
                        {"pga_g", m.pga},
                        {"pga_m_s2", m.pga_m_s2},
                        {"t_pga_s", m.t_pga},
                        {"pgv_m_s", m.pgv},
                        {"pgd_m", m.pgd},
                        {"arias_m_s", m.arias},
                        {"cav_m_s", m.cav},
                        {"t5_s", m.t5},
                        {"t95_s", m.t95},
                        {"d5_95_s", m.d5_95},
                        {"predominant_period_s", m.predominant_period},
                        {"housner_si_m", si.housner},
                        {"asi_g_s", si.asi}};
}

// The spectrum intensities are printed when given.
std::string table(const Record& record, const IntensityMeasures& m, const SpectrumIntensity* si = nullptr) {
  std::ostringstream s;
  auto row = [&](const std::string& name, const std::string& value, const std::string& unit, const std::string& note = "") {
    s << "  " << std::left << std::setw(20) << name << std::right << std::setw(12) << value << "  " << std::left
      << std::setw(4) << unit << note << "\n";
  };
  s << record.source << "\n";
  if (!record.description.empty()) s << "  " << record.description << "\n";
  row("npts", std::to_string(m.npts), "");
  row("dt", number(m.dt), "s");
  row("duration", number(m.duration), "s");
  row("PGA", number(m.pga, 4), "g", "  at t = " + number(m.t_pga, 6) + " s");
  row("PGV", number(m.pgv, 4), "m/s");
  row("PGD", number(m.pgd, 4), "m", "  (no baseline correction)");
  row("Arias intensity", number(m.arias, 4), "m/s");
  row("CAV", number(m.cav, 4), "m/s");
  row("D5-95", number(m.d5_95, 4), "s", "  from " + number(m.t5, 5) + " to " + number(m.t95, 5) + " s");
  row("predominant period", number(m.predominant_period, 4), "s");
  if (si) {
    row("Housner SI", number(si->housner, 4), "m", "  (PSV 5 %, 0.1-2.5 s)");
    row("ASI", number(si->asi, 4), "g s", " (PSA 5 %, 0.1-0.5 s)");
  }
  return s.str();
}

// "A:B" -> two numbers; InputError naming the option otherwise.
std::pair<double, double> pair_of(const std::string& option, const std::string& text) {
  const auto colon = text.find(':');
  double a = 0.0, b = 0.0;
  if (colon == std::string::npos || !parse_finite(trim_blanks(std::string_view(text).substr(0, colon)), &a) ||
      !parse_finite(trim_blanks(std::string_view(text).substr(colon + 1)), &b))
    throw InputError(option + " " + text_excerpt(text) + ": expected two numbers as A:B");
  return {a, b};
}

// t, a [g], v [m/s], d [m] as CSV with '#' comment lines and a header the delimited reader
// understands (time column "t", acceleration "a" in g).
void write_histories(const Record& record, const std::string& path, const std::vector<std::string>& header) {
  const MotionHistories h = integrate_record(record);
  AtomicFile file(path);
  std::ostream& out = file.stream();
  for (const std::string& line : header) out << "# " << line << "\n";
  out << "# velocity and displacement: trapezoid rule from rest\n";
  out << "t [s],a [g],v [m/s],d [m]\n";
  std::string text;
  text.reserve(h.accel.size() * 80);
  char line[160];
  for (std::size_t i = 0; i < h.accel.size(); ++i) {
    char* p = line;
    char* const end = line + sizeof line;
    for (const double value : {static_cast<double>(i) * h.dt, h.accel[i] / 9.80665, h.velocity[i], h.displacement[i]}) {
      if (p != line) *p++ = ',';
      p = std::to_chars(p, end - 2, value).ptr;
    }
    *p++ = '\n';
    text.append(line, p);
  }
  out << text;
  file.commit();
}

int process_command(const RecordArgs& args, const CLI::App& sub) {
  const RecordFormat format = format_from(args);
  const Record input = read_record(args.files.at(0), format);
  auto given = [&](const char* option) { return sub.count(option) > 0; };
  Processing p;
  std::vector<std::string> header = {"processed by adjoin record process from " + input.source};
  if (!args.window.empty()) {
    const auto [t0, t1] = pair_of("--window", args.window);
    p.window_t0 = t0;
    p.window_t1 = t1;
    header.push_back("window " + number(t0) + " to " + number(t1) + " s");
  }
  if (given("--baseline")) {
    p.baseline_order = args.baseline;
    header.push_back("baseline removed: polynomial of order " + std::to_string(args.baseline));
  }
  if (!args.pad.empty()) {
    const auto [before, after] = pair_of("--pad", args.pad);
    p.pad_before = before;
    p.pad_after = after;
    header.push_back("zero padding " + number(before) + " s before, " + number(after) + " s after");
  }
  const int filters = given("--highpass") + given("--lowpass") + !args.bandpass.empty();
  if (filters > 1) throw InputError("--highpass, --lowpass, --bandpass: give one filter");
  std::string filter_option;
  if (filters == 1) {
    ButterworthFilter f;
    f.order = args.filter_order;
    if (given("--highpass")) { f.type = ButterworthFilter::Type::highpass; f.f_low = args.highpass; filter_option = "--highpass"; }
    if (given("--lowpass")) { f.type = ButterworthFilter::Type::lowpass; f.f_high = args.lowpass; filter_option = "--lowpass"; }
    if (!args.bandpass.empty()) {
      f.type = ButterworthFilter::Type::bandpass;
      std::tie(f.f_low, f.f_high) = pair_of("--bandpass", args.bandpass);
      filter_option = "--bandpass";
    }
    p.filter = f;
    header.push_back("zero-phase Butterworth of order " + std::to_string(f.order) + ", corners " + number(f.f_low) +
                     " / " + number(f.f_high) + " Hz");
  } else if (given("--filter-order")) {
    throw InputError("--filter-order: give a filter too (--highpass, --lowpass or --bandpass)");
  }
  if (given("--resample")) {
    p.dt = args.resample;
    header.push_back("resampled to dt = " + number(args.resample) + " s (windowed sinc)");
  }
  if (given("--scale-pga")) {
    p.target_pga = args.scale_pga * 9.80665;
    header.push_back("scaled to PGA = " + number(args.scale_pga) + " g");
  }
  // One validation with the scenes' (ground/processing.hpp), each problem named by its option.
  if (const auto problem = check_processing(p, input, 0.8 * physical_memory_bytes())) {
    const char* option = "";
    switch (problem->field) {
      case ProcessingField::window_start: case ProcessingField::window_end: option = "--window"; break;
      case ProcessingField::baseline: option = "--baseline"; break;
      case ProcessingField::pad_before: case ProcessingField::pad_after: option = "--pad"; break;
      case ProcessingField::filter_order: option = "--filter-order"; break;
      case ProcessingField::f_low: case ProcessingField::f_high: option = filter_option.c_str(); break;
      case ProcessingField::resample_dt: option = "--resample"; break;
      case ProcessingField::scale_pga: option = "--scale-pga"; break;
    }
    throw InputError(args.files.at(0) + ": " + option + " " + problem->message);
  }
  const Record output = process(input, p);
  if (args.integrate) {
    write_histories(output, args.out, header);
    std::cout << "wrote " << args.out << " (CSV: t [s], a [g], v [m/s], d [m])\n" << table(output, intensity_measures(output));
    return 0;
  }
  write_record_g(output, args.out, header);
  std::cout << "wrote " << args.out << " (two columns: t [s], a [g])\n" << table(output, intensity_measures(output));
  return 0;
}

// "F0:F1:N" -> N log-spaced frequencies [Hz]; InputError naming --frequencies otherwise.
std::vector<double> frequency_points(const std::string& text) {
  const std::string expected = ": expected F0:F1:N with 0 < F0 < F1 [Hz] and N >= 2 points (log-spaced)";
  double f0 = 0.0, f1 = 0.0, n = 0.0;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> f0 >> c1 >> f1 >> c2 >> n) || c1 != ':' || c2 != ':' || !(in >> std::ws).eof() || !(f0 > 0.0) ||
      !(f1 > f0) || !std::isfinite(f1) || n < 2.0 || n > 1e6 || n != std::floor(n))
    throw InputError("--frequencies " + text_excerpt(text) + expected);
  // period_range spaces any positive quantity; here frequencies.
  return period_range(f0, f1, static_cast<std::size_t>(n), PeriodSpacing::log);
}

int fourier_command(const RecordArgs& args) {
  if (args.smooth < 0.0 || !(args.smooth <= 1000.0))
    throw InputError("--smooth " + number(args.smooth) + ": expected the Konno-Ohmachi bandwidth b > 0, at most 1000 (40 is usual)");
  PlotStyle style;
  if (!args.plot.empty()) plot_target(args.plot, {}, "", &style, "--plot");
  const bool smoothing = args.smooth > 0.0 || !args.frequencies.empty();
  std::vector<double> centres;
  if (!args.frequencies.empty()) centres = frequency_points(args.frequencies);

  const Record record = read_record(args.files.at(0), format_from(args));
  const FourierSpectrum raw = fourier_amplitude_spectrum(record);
  FourierSpectrum smoothed;
  if (smoothing) {
    if (centres.empty()) {
      const double df = raw.frequency.size() > 1 ? raw.frequency[1] : 0.0;
      const double low = std::max(0.1, df), high = std::min(50.0, raw.frequency.back());
      if (!(df > 0.0) || !(high > low))
        throw InputError(record.source + ": its Fourier frequencies (" + number(df) + " to " +
                         number(raw.frequency.back()) + " Hz) leave nothing of the default 0.1-50 Hz; give "
                         "--frequencies F0:F1:N");
      centres = period_range(low, high, 200, PeriodSpacing::log);
    }
    smoothed.frequency = centres;
    smoothed.amplitude = konno_ohmachi(raw, centres, args.smooth > 0.0 ? args.smooth : 40.0);
  }
  const FourierSpectrum& shown = smoothing ? smoothed : raw;
  std::ostringstream csv;
  csv << "frequency,amplitude\n";
  char line[64];
  for (std::size_t k = 0; k < shown.frequency.size(); ++k) {
    std::snprintf(line, sizeof line, "%.10g,%.10g\n", shown.frequency[k], shown.amplitude[k]);
    csv << line;
  }
  if (args.out.empty()) {
    std::cout << csv.str();
    std::cout.flush();
    if (!std::cout) throw InputError("cannot write to standard output");
  } else {
    AtomicFile out(args.out);
    out.stream() << csv.str();
    out.commit();
  }
  if (!args.plot.empty())
    return draw_figure(
        [&] {
          plot_fourier(raw, smoothing ? &smoothed : nullptr, args.plot, style,
                       std::filesystem::path(args.files.at(0)).filename().string());
        },
        args.out.empty() ? "the spectrum was printed" : "the spectrum was written to " + args.out);
  return 0;
}

// Two files with the same dt: the horizontal components of one station. PGA [g], PGV [m/s] and
// PGD [m] rotated (post/rotd.hpp: RotD00/50/100 over 0-179 degrees from the first towards the
// second, at the samples; v, d the trapezoid integrals as above); the shorter padded with zeros.
void add_pair(Record a, Record b, std::string* text, nlohmann::json* first) {
  if (!(std::abs(a.dt - b.dt) <= 1e-9 * std::max(a.dt, b.dt))) {
    std::cerr << "note: " << a.source << " and " << b.source << " have different dt: no rotated measures\n";
    return;
  }
  if (a.accel.size() != b.accel.size()) {
    std::cerr << "warning: " << a.source << " and " << b.source << " have " << a.accel.size() << " and "
              << b.accel.size() << " samples: the shorter is padded with zeros for the rotated measures\n";
    const std::size_t n = std::max(a.accel.size(), b.accel.size());
    a.accel.resize(n, 0.0);
    b.accel.resize(n, 0.0);
  }
  const std::vector<double> va = cumulative_trapezoid(a.accel, a.dt), vb = cumulative_trapezoid(b.accel, b.dt);
  const RotatedPeaks pga = rotated_peaks(a.accel, b.accel), pgv = rotated_peaks(va, vb),
                     pgd = rotated_peaks(cumulative_trapezoid(va, a.dt), cumulative_trapezoid(vb, b.dt));
  const double g = 9.80665;
  auto json = [](const RotatedPeaks& p, double scale) {
    return nlohmann::json{{"rotd00", p.rotd00 / scale}, {"rotd50", p.rotd50 / scale}, {"rotd100", p.rotd100 / scale},
                          {"angle00_deg", p.angle00}, {"angle100_deg", p.angle100}};
  };
  if (first) {
    (*first)["pair"] = nlohmann::json{{"with", b.source}, {"pga_g", json(pga, g)}, {"pgv_m_s", json(pgv, 1.0)},
                                      {"pgd_m", json(pgd, 1.0)}};
    return;
  }
  std::ostringstream s;
  s << "\npair " << a.source << " + " << b.source << " (rotated 0-179 deg from the first towards the second)\n";
  auto line = [&](const char* name, const RotatedPeaks& p, double scale, const char* unit) {
    s << "  " << std::left << std::setw(20) << name << std::right << std::setw(10) << number(p.rotd00 / scale, 4)
      << std::setw(10) << number(p.rotd50 / scale, 4) << std::setw(10) << number(p.rotd100 / scale, 4) << "  "
      << std::left << std::setw(4) << unit << "  angles " << number(p.angle00) << " / " << number(p.angle100)
      << " deg\n";
  };
  s << "  " << std::left << std::setw(20) << "RotD" << std::right << std::setw(10) << "00" << std::setw(10) << "50"
    << std::setw(10) << "100" << "\n";
  line("PGA", pga, g, "g");
  line("PGV", pgv, 1.0, "m/s");
  line("PGD", pgd, 1.0, "m");
  *text += s.str();
}

int info_command(const RecordArgs& args) {
  const RecordFormat format = format_from(args);
  std::string text;
  nlohmann::json all = nlohmann::json::array();
  std::vector<Record> pair;
  for (std::size_t i = 0; i < args.files.size(); ++i) {
    const Record record = read_record(args.files[i], format);
    if (args.files.size() == 2) pair.push_back(record);
    const IntensityMeasures m = intensity_measures(record);
    const SpectrumIntensity si = spectrum_intensity(record);
    if (args.json)
      all.push_back(to_json(record, m, si));
    else
      text += (i ? "\n" : "") + table(record, m, &si);
  }
  if (pair.size() == 2) add_pair(pair[0], pair[1], &text, args.json ? &all[0] : nullptr);
  if (args.json) text = (all.size() == 1 ? all[0] : all).dump(2) + "\n";
  if (args.out.empty()) {
    std::cout << text;
    std::cout.flush();
    if (!std::cout) throw InputError("cannot write to standard output");
  } else {
    AtomicFile out(args.out);
    out.stream() << text;
    out.commit();
  }
  return 0;
}

// The options that say how to read a record, shared by the subcommands.
const Registration registration(30, "record", "Recorded accelerograms: information, processing, Fourier spectra",
                                [](CLI::App* record) -> Runner {
  auto args = std::make_shared<RecordArgs>();
  record->require_subcommand(1);
  auto* info = record->add_subcommand(
      "info", "npts, dt, duration, PGA [g], PGV [m/s], PGD [m], Arias [m/s], CAV [m/s], D5-95 [s], predominant "
              "period [s], Housner SI [m], ASI [g s]; for two files with the same dt (a pair of horizontal components) also "
              "PGA, PGV, PGD rotated (RotD00/50/100 and angles)");
  info->add_option("files", args->files, "Accelerogram(s): PEER AT2, one/two-column text, delimited text with a header")
      ->required();
  add_reading_options(info, args.get());
  info->add_flag("--json", args->json, "Print JSON instead of a table");
  info->add_option("--out", args->out, "Write to this file instead of stdout");
  auto* process = record->add_subcommand("process", "Process a record (window, baseline, padding, filter, resampling, "
                                                     "scaling) and write it as two columns t [s], a [g]");
  process->add_option("file", args->files, "Accelerogram to process")->required()->expected(1);
  add_reading_options(process, args.get());
  process->add_option("--window", args->window, "Keep T0:T1 [s]");
  process->add_option("--baseline", args->baseline, "Remove a least-squares polynomial baseline of this order (0 = mean)");
  process->add_option("--pad", args->pad, "Zero padding BEFORE:AFTER [s]");
  process->add_option("--highpass", args->highpass, "Zero-phase Butterworth high-pass corner [Hz]");
  process->add_option("--lowpass", args->lowpass, "Zero-phase Butterworth low-pass corner [Hz]");
  process->add_option("--bandpass", args->bandpass, "Zero-phase Butterworth band-pass corners F1:F2 [Hz]");
  process->add_option("--filter-order", args->filter_order, "Butterworth order per pass (default 4)");
  process->add_option("--resample", args->resample, "New time step [s] (band-limited windowed-sinc interpolation)");
  process->add_option("--scale-pga", args->scale_pga, "Scale to this PGA [g] (last)");
  process->add_option("--out", args->out, "Output file (two columns t [s], a [g])")->required();
  process->add_flag("--integrate", args->integrate,
                    "Also integrate (trapezoid, from rest, after the processing): write CSV t [s],a [g],v [m/s],d [m]");
  auto* fourier = record->add_subcommand(
      "fourier", "Fourier amplitude spectrum: CSV frequency,amplitude (Hz, m/s), raw or Konno-Ohmachi smoothed");
  fourier->add_option("file", args->files, "Accelerogram")->required()->expected(1);
  add_reading_options(fourier, args.get());
  fourier->add_option("--smooth", args->smooth, "Konno-Ohmachi smoothing with this bandwidth b (40 is usual)");
  fourier->add_option("--frequencies", args->frequencies,
                      "Smoothed spectrum at F0:F1:N log-spaced frequencies [Hz] (default 0.1:50:200; implies "
                      "smoothing, b = 40 unless --smooth)");
  fourier->add_option("--out", args->out, "CSV file (default: stdout)");
  fourier->add_option("--plot", args->plot, "Also draw the spectrum with gnuplot (.png or .svg)");
  return [args, info, process, fourier]() -> int {
    if (info->parsed()) return info_command(*args);
    if (process->parsed()) return process_command(*args, *process);
    if (fourier->parsed()) return fourier_command(*args);
    return 0;
  };
});

}  // namespace
}  // namespace adjoin::cli
