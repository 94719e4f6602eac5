// An accelerogram through the library: read it, its intensity measures, its 5 % response
// spectrum with exact peaks, and its Konno-Ohmachi smoothed Fourier amplitudes.
//
//     record_spectra [FILE [UNITS]]      (default: the project's synthetic EC8 record, in g)
#include <adjoin/ground/record_file.hpp>
#include <adjoin/core/units.hpp>
#include <adjoin/post/intensity.hpp>
#include <adjoin/post/spectrum.hpp>
#include <cstdio>
#include <exception>
#include <vector>

int main(int argc, char** argv) try {
  adjoin::RecordFormat format;  // AT2 headers say their units; text files need them
  adjoin::AccelUnit unit = adjoin::AccelUnit::g;
  if (argc > 2 && !adjoin::parse_accel_unit(argv[2], &unit)) {
    std::fprintf(stderr, "error: units %s: expected g, m/s2, cm/s2 or mm/s2\n", argv[2]);
    return 2;
  }
  if (argc <= 1 || argc > 2) format.units = unit;
  const adjoin::Record record =
      adjoin::read_record(argc > 1 ? argv[1] : "records/synthetic/cp-ec8b-seed1.txt", format);

  const adjoin::IntensityMeasures im = adjoin::intensity_measures(record);
  std::printf("%s: %zu samples, dt %g s, PGA %.4f g, Arias %.4f m/s, D5-95 %.2f s\n", record.source.c_str(),
              im.npts, im.dt, im.pga, im.arias, im.d5_95);

  // Response spectrum: 5 % and 2 % damping at a few periods, all cores.
  adjoin::SpectrumOptions options;
  options.periods = {0.1, 0.2, 0.5, 1.0, 2.0};
  options.dampings = {0.05, 0.02};
  const adjoin::ResponseSpectrum spectrum = adjoin::response_spectrum(record, options);
  std::printf("%8s %10s %10s %10s\n", "T [s]", "PSA 5% [g]", "PSA 2% [g]", "SD 5% [m]");
  for (std::size_t i = 0; i < options.periods.size(); ++i)
    std::printf("%8.2f %10.4f %10.4f %10.5f\n", options.periods[i], spectrum.at(0, i).psa, spectrum.at(1, i).psa,
                spectrum.at(0, i).sd);

  // Fourier amplitudes, smoothed with the usual bandwidth b = 40.
  const adjoin::FourierSpectrum fas = adjoin::fourier_amplitude_spectrum(record);
  const std::vector<double> frequencies{0.5, 1.0, 2.0, 5.0, 10.0};
  const std::vector<double> smoothed = adjoin::konno_ohmachi(fas, frequencies, 40.0);
  std::printf("%8s %14s\n", "f [Hz]", "FAS KO40 [m/s]");
  for (std::size_t k = 0; k < frequencies.size(); ++k) std::printf("%8.2f %14.5f\n", frequencies[k], smoothed[k]);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 2;
}
