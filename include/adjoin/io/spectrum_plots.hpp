#pragma once
// Figures of spectra (io/plots.hpp lists them): response spectra and Fourier amplitude.
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/io/plot_style.hpp"
#include "adjoin/post/intensity.hpp"
#include "adjoin/post/spectrum.hpp"

namespace adjoin {

// PSA and SD against period (log axis), one curve per damping; title after "Elastic response
// spectra: ". From memory, or from the CSV of `adjoin spectrum` (title: the file's name).
// `references` (e.g. a code spectrum) are drawn dashed on the PSA panel.
struct ReferenceCurve {
  std::string label;
  std::vector<double> period, psa;  // s, g
};
void plot_spectrum(const ResponseSpectrum& spectrum, const std::filesystem::path& image, const PlotStyle& style,
                   const std::string& title, const std::vector<ReferenceCurve>& references = {});
void plot_spectrum_csv(const std::filesystem::path& csv, const std::filesystem::path& image, const PlotStyle& style);
// Fourier amplitude [m/s] against frequency [Hz] on log-log axes: the raw spectrum and, if
// given, a smoothed one drawn over it; title after "Fourier amplitude spectrum: ".
void plot_fourier(const FourierSpectrum& raw, const FourierSpectrum* smoothed, const std::filesystem::path& image,
                  const PlotStyle& style, const std::string& title);

}  // namespace adjoin
