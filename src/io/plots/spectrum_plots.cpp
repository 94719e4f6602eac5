// Figures of spectra (io/spectrum_plots.hpp): elastic response spectra from memory or from
// the CSV of `adjoin spectrum`, and Fourier amplitude spectra.
#include "adjoin/io/spectrum_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"

namespace adjoin {
namespace fs = std::filesystem;

namespace {

struct SpectrumCurve {
  std::string label;
  std::vector<double> period, psa, sd;  // periods > 0, increasing
};

// Numbers in legends rounded for reading: 4 significant digits, no binary noise (0.05, not
// 0.05000000000000000277).
std::string legend_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string damping_label(double zeta) { return "damping " + legend_number(zeta * 100.0) + " %"; }

void draw_spectra(const std::vector<SpectrumCurve>& curves, const std::string& title, const fs::path& image,
                  const PlotStyle& style, const std::vector<ReferenceCurve>& references = {}) {
  std::ostringstream s;
  s << kGnuplotPreamble;
  for (std::size_t d = 0; d < curves.size(); ++d)
    gnuplot_datablock(s, "s" + std::to_string(d), {curves[d].period, curves[d].psa, curves[d].sd});
  for (std::size_t r = 0; r < references.size(); ++r)
    gnuplot_datablock(s, "r" + std::to_string(r), {references[r].period, references[r].psa});
  double t_lo = INFINITY, t_hi = 0.0;
  for (const auto& c : curves)
    for (double t : c.period) {
      t_lo = std::min(t_lo, t);
      t_hi = std::max(t_hi, t);
    }
  s << gnuplot_log_tics("x", t_lo, t_hi);
  s << "set multiplot layout 2,1 title " << gnuplot_quote("Elastic response spectra: " + title)
    << " noenhanced font ',12' margins 0.1,0.72,0.09,0.92 spacing 0,0.03\n"
    << "set logscale x\nset format x ''\nset key outside right top vertical\nset mxtics 10\n"
    << "set grid xtics mxtics ytics lc rgb '#d0d0d0', lc rgb '#ececec'\n";
  auto panel = [&](int column) {
    s << "plot ";
    for (std::size_t d = 0; d < curves.size(); ++d)
      s << (d ? ", " : "") << "$s" << d << " using 1:" << column << " with lines lt " << d + 1 << " title "
        << gnuplot_quote(curves[d].label);
    if (column == 2)
      for (std::size_t r = 0; r < references.size(); ++r)
        s << ", $r" << r << " using 1:2 with lines lt " << r + 1 << " dt 2 lw 1.5 title "
          << gnuplot_quote(references[r].label) << " noenhanced";
    s << "\n";
  };
  s << "set ylabel 'PSA [g]'\n";
  panel(2);
  s << "set format x '%g'\nset xlabel 'period T [s]'\nset ylabel 'SD [m]'\n";
  panel(3);
  s << "unset multiplot\n";
  render_gnuplot(s.str(), image, style);
}

// One curve per signal and damping from rows (signal, period, damping, psa, sd) in any order
// (a run's spectra.csv has a signal column: ground, block1, block2); periods > 0 only.
std::vector<SpectrumCurve> spectrum_curves(const std::vector<double>& period, const std::vector<double>& damping,
                                           const std::vector<double>& psa, const std::vector<double>& sd,
                                           const std::vector<std::string>& signal = {}) {
  std::vector<std::pair<std::string, double>> groups;
  for (std::size_t i = 0; i < damping.size(); ++i) {
    const std::pair<std::string, double> g{signal.empty() ? std::string() : signal[i], damping[i]};
    if (std::isfinite(g.second) && std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
  }
  std::vector<SpectrumCurve> curves;
  for (const auto& [sig, z] : groups) {
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t i = 0; i < period.size(); ++i)
      if (damping[i] == z && period[i] > 0.0 && (signal.empty() || signal[i] == sig)) order.push_back({period[i], i});
    if (order.empty()) continue;
    std::sort(order.begin(), order.end());
    SpectrumCurve curve{(sig.empty() ? "" : sig + ", ") + damping_label(z), {}, {}, {}};
    for (const auto& [p, i] : order) {
      curve.period.push_back(p);
      curve.psa.push_back(psa[i]);
      curve.sd.push_back(sd[i]);
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace

void plot_spectrum(const ResponseSpectrum& spectrum, const fs::path& image, const PlotStyle& style,
                   const std::string& title, const std::vector<ReferenceCurve>& references) {
  std::vector<double> period, damping, psa, sd;
  for (const SpectralValues& v : spectrum.values) {
    period.push_back(v.period);
    damping.push_back(v.damping);
    psa.push_back(v.psa);
    sd.push_back(v.sd);
  }
  const std::vector<SpectrumCurve> curves = spectrum_curves(period, damping, psa, sd);
  if (curves.empty()) throw InputError(image.string() + ": no period > 0 s to plot");
  draw_spectra(curves, title, image, style, references);
}

void plot_spectrum_csv(const fs::path& csv, const fs::path& image, const PlotStyle& style) {
  const CsvTable table = read_csv_table(csv, "the CSV of `adjoin spectrum`: period,damping,sd,sv,sa,psv,psa");
  const std::string context = "spectrum CSV";
  std::vector<std::string> signal;
  if (table.has("signal")) {
    const std::size_t c = table.column("signal", context);
    for (const auto& row : table.rows) signal.push_back(row[c]);
  }
  const std::vector<SpectrumCurve> curves =
      spectrum_curves(table.numbers("period", context), table.numbers("damping", context),
                      table.numbers("psa", context), table.numbers("sd", context), signal);
  if (curves.empty()) throw InputError(csv.string() + ": no rows with period > 0 s to plot");
  draw_spectra(curves, csv.filename().string(), image, style);
}

// ---- Fourier amplitude

void plot_fourier(const FourierSpectrum& raw, const FourierSpectrum* smoothed, const fs::path& image,
                  const PlotStyle& style, const std::string& title) {
  // Log axes: only f > 0 and A > 0 can be drawn.
  auto positive = [](const FourierSpectrum& spectrum) {
    std::vector<std::vector<double>> cols(2);
    for (std::size_t k = 0; k < spectrum.frequency.size(); ++k)
      if (spectrum.frequency[k] > 0.0 && spectrum.amplitude[k] > 0.0) {
        cols[0].push_back(spectrum.frequency[k]);
        cols[1].push_back(spectrum.amplitude[k]);
      }
    return cols;
  };
  const std::vector<std::vector<double>> r = positive(raw);
  if (r[0].empty()) throw InputError(image.string() + ": the spectrum has no amplitude > 0 at a frequency > 0 to plot");
  std::ostringstream s;
  s << kGnuplotPreamble;
  gnuplot_datablock(s, "raw", r);
  std::string plots = "$raw using 1:2 with lines lc rgb '" + std::string(smoothed ? "#b0b0b0" : "#1f5fa8") +
                      "' title 'Fourier amplitude'";
  if (smoothed) {
    gnuplot_datablock(s, "smooth", positive(*smoothed));
    plots += ", $smooth using 1:2 with lines lt 1 linewidth 2 title 'Konno-Ohmachi smoothed'";
  }
  s << "set title " << gnuplot_quote("Fourier amplitude spectrum: " + title) << " noenhanced font ',12'\n"
    << "set logscale xy\nset format x '%g'\nset format y '10^{%L}'\nset mxtics 10\n"
    << "set grid xtics mxtics ytics lc rgb '#d0d0d0', lc rgb '#ececec'\n"
    << "set xlabel 'frequency f [Hz]'\nset ylabel 'Fourier amplitude [m/s]'\nset key bottom left\n"
    << "plot " << plots << "\n";
  render_gnuplot(s.str(), image, style);
}

}  // namespace adjoin
