// Intensity measures against closed forms on signals whose integrals are known.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <cmath>
#include <vector>
#include <numbers>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/intensity.hpp"
#include "adjoin/post/spectrum.hpp"
#include "record_helpers.hpp"

using namespace adjoin;
using std::numbers::pi;

namespace {

constexpr double g = 9.80665;

}  // namespace

TEST_CASE("sine over whole cycles: Arias, CAV, PGA, D5-95, Fourier amplitude, predominant period", "[intensity]") {
  const double A = 3.0, f = 2.0, T = 10.0;  // 20 cycles
  SECTION("Arias intensity pi A^2 T / (4 g) (trapezoid is exact for sin^2 over whole cycles)") {
    const Record r = test::sampled_record(0.005, 2001, [&](double t) { return A * std::sin(2.0 * pi * f * t); });
    CHECK(arias_intensity(r) == Approx(pi * A * A * T / (4.0 * g)).epsilon(1e-12));
    const IntensityMeasures m = intensity_measures(r);
    CHECK(m.npts == 2001);
    CHECK(m.dt == 0.005);
    CHECK(m.duration == Approx(T));
    CHECK(m.pga == Approx(A / g).epsilon(1e-12));  // samples hit the crests (t = 0.125 + k/4)
    CHECK(std::abs(std::sin(2.0 * pi * f * m.t_pga)) == Approx(1.0).epsilon(1e-12));
    CHECK(m.arias == Approx(pi * A * A * T / (4.0 * g)).epsilon(1e-12));
    // Husid H(t) = t/T - sin(4 pi f t)/(4 pi f T): at t = 0.05 T = 1 cycle and 0.95 T the sine
    // term vanishes, so D5-95 = 0.9 T up to the linear interpolation between samples.
    CHECK(m.t5 == Approx(0.05 * T).margin(2e-4));
    CHECK(m.t95 == Approx(0.95 * T).margin(2e-4));
    CHECK(m.d5_95 == Approx(0.9 * T).margin(4e-4));
  }
  SECTION("CAV 2 A T / pi (piecewise-linear exact integral converges at O(dt^2))") {
    const Record r = test::sampled_record(0.001, 10001, [&](double t) { return A * std::sin(2.0 * pi * f * t); });
    CHECK(cumulative_absolute_velocity(r) == Approx(2.0 * A * T / pi).epsilon(2e-5));
  }
  SECTION("Fourier amplitude A T / 2 at f, predominant period 1/f") {
    const Record r = test::sampled_record(0.01, 1000, [&](double t) { return A * std::sin(2.0 * pi * f * t); });  // n dt = T
    const FourierSpectrum s = fourier_amplitude_spectrum(r);
    REQUIRE(s.frequency.size() == 501);
    CHECK(s.frequency[1] == Approx(0.1));
    CHECK(s.frequency.back() == Approx(50.0));
    CHECK(s.amplitude[20] == Approx(A * T / 2.0).epsilon(1e-12));
    CHECK(s.amplitude[19] < 1e-10);
    CHECK(s.amplitude[0] < 1e-10);
    CHECK(predominant_period(r) == Approx(1.0 / f).epsilon(1e-12));
    // A 0.7 Hz sine on top of a weaker 5 Hz one: the period of the stronger.
    const Record two = test::sampled_record(0.01, 1000, [](double t) { return std::sin(2.0 * pi * 0.7 * t) + 0.5 * std::sin(2.0 * pi * 5.0 * t); });
    CHECK(predominant_period(two) == Approx(1.0 / 0.7).epsilon(1e-12));
  }
}

TEST_CASE("PGV and PGD of a cosine: A/(2 pi f) and 2 A/(2 pi f)^2", "[intensity]") {
  const double A = 2.0, f = 1.0, w = 2.0 * pi * f;
  const Record r = test::sampled_record(0.001, 5001, [&](double t) { return A * std::cos(w * t); });
  const IntensityMeasures m = intensity_measures(r);
  CHECK(m.pgv == Approx(A / w).epsilon(1e-5));
  CHECK(m.pgd == Approx(2.0 * A / (w * w)).epsilon(1e-5));
  // The velocity history itself: v = A sin(w t) / w.
  const auto v = cumulative_trapezoid(r.accel, r.dt);
  for (std::size_t i = 0; i < v.size(); i += 613) CHECK(v[i] == Approx(A * std::sin(w * i * 0.001) / w).margin(1e-6));
}

TEST_CASE("constant amplitude: D5-95 = 0.9 duration exactly, triangle wave CAV exactly", "[intensity]") {
  const Record c = test::sampled_record(0.02, 501, [](double) { return -1.5; });  // 10 s
  const SignificantDuration d = significant_duration(c);
  CHECK(d.t_start == Approx(0.5).epsilon(1e-12));
  CHECK(d.t_end == Approx(9.5).epsilon(1e-12));
  CHECK(d.duration == Approx(9.0).epsilon(1e-12));
  CHECK(significant_duration(c, 0.25, 0.75).duration == Approx(5.0).epsilon(1e-12));
  CHECK(cumulative_absolute_velocity(c) == Approx(15.0).epsilon(1e-14));
  CHECK(arias_intensity(c) == Approx(pi / (2.0 * g) * 2.25 * 10.0).epsilon(1e-14));
  const IntensityMeasures m = intensity_measures(c);
  CHECK(m.pgv == Approx(15.0).epsilon(1e-12));       // v = a t
  CHECK(m.pgd == Approx(0.5 * 1.5 * 100.0).epsilon(1e-12));  // d = a t^2 / 2 (trapezoid exact on linear v)
  // Triangle wave, amplitude A, period P, zero crossings between samples: splitting a step at
  // its crossing makes CAV exact for the piecewise-linear record (plain trapezoid of |a| is not).
  const double A = 0.8, P = 1.0;
  const auto tri = [&](double t) {
    const double x = std::fmod(t + 0.013, P) / P;  // shifted so zero crossings fall between samples
    return A * (x < 0.5 ? 4.0 * x - 1.0 : 3.0 - 4.0 * x);
  };
  Record tr = test::sampled_record(0.01, 1001, tri);
  // The integral of |piecewise-linear interpolant| by a fine midpoint rule, and A T / 2 up to
  // the apexes that fall between samples.
  double exact = 0.0;
  for (std::size_t i = 1; i < tr.accel.size(); ++i) {
    const double p = tr.accel[i - 1], q = tr.accel[i];
    const double n = 1000.0;  // midpoint-rule reference on a fine sub-grid
    for (int k = 0; k < 1000; ++k) exact += std::abs(p + (q - p) * (k + 0.5) / n) * tr.dt / n;
  }
  CHECK(cumulative_absolute_velocity(tr) == Approx(exact).epsilon(1e-6));
  CHECK(cumulative_absolute_velocity(tr) == Approx(A * 10.0 / 2.0).epsilon(2e-3));
}

TEST_CASE("degenerate records", "[intensity]") {
  const Record zero = test::sampled_record(0.01, 100, [](double) { return 0.0; });
  const IntensityMeasures m = intensity_measures(zero);
  CHECK(m.pga == 0.0);
  CHECK(m.arias == 0.0);
  CHECK(m.d5_95 == 0.0);
  CHECK(m.predominant_period == 0.0);
  Record bad = zero;
  bad.dt = 0.0;
  CHECK_THROWS_AS(intensity_measures(bad), InputError);
  CHECK_THROWS_AS(significant_duration(zero, 0.9, 0.1), InputError);
}

TEST_CASE("Fourier amplitudes satisfy Parseval: sum A^2 df (one-sided) = sum a^2 dt", "[intensity]") {
  // Independent of the FFT's normalisation and of how the one-sided spectrum is folded: the
  // energy of a record equals that of its spectrum, for odd and even lengths.
  for (std::size_t n : {999u, 1000u, 4096u, 6007u}) {
    const Record r = test::sampled_record(0.01, n, [](double t) {
      return std::exp(-0.2 * t) * (std::sin(7.0 * t) + 0.3 * std::cos(41.0 * t * t / (1.0 + t)));
    });
    const FourierSpectrum s = fourier_amplitude_spectrum(r);
    const double df = 1.0 / (static_cast<double>(n) * r.dt);
    double spectral = 0.0;
    for (std::size_t k = 0; k < s.amplitude.size(); ++k) {
      const bool single = k == 0 || (n % 2 == 0 && k == n / 2);  // DC and Nyquist appear once
      spectral += (single ? 1.0 : 2.0) * s.amplitude[k] * s.amplitude[k] * df;
    }
    double temporal = 0.0;
    for (double a : r.accel) temporal += a * a * r.dt;
    INFO("n = " << n);
    CHECK(spectral == Approx(temporal).epsilon(1e-12));
  }
}

TEST_CASE("Konno-Ohmachi smoothing: constants kept, the window's zeros, scale invariance", "[intensity]") {
  const Record r = test::sampled_record(0.01, 3000, [](double t) { return std::sin(3.0 * t) * std::exp(-0.1 * t); });
  FourierSpectrum s = fourier_amplitude_spectrum(r);
  const std::vector<double> centres{0.05, 0.3, 1.0, 7.0, 49.0};

  SECTION("a constant spectrum stays constant (the weights are normalised)") {
    for (double& a : s.amplitude) a = 2.5;
    for (double v : konno_ohmachi(s, centres)) CHECK(v == Approx(2.5).epsilon(1e-13));
  }
  SECTION("a single line: zero where the window has its first zeros, fc = f0 10^(+-pi/b)") {
    for (double& a : s.amplitude) a = 0.0;
    const std::size_t k0 = 400;  // f0 = 400 / 30 Hz
    s.amplitude[k0] = 1.0;
    const double f0 = s.frequency[k0];
    for (double b : {20.0, 40.0, 80.0}) {
      const std::vector<double> zeros{f0 * std::pow(10.0, pi / b), f0 * std::pow(10.0, -pi / b)};
      const std::vector<double> at_zeros = konno_ohmachi(s, zeros, b);
      const std::vector<double> at_line = konno_ohmachi(s, std::vector<double>{f0}, b);
      INFO("b = " << b);
      CHECK(at_zeros[0] < 1e-25 * at_line[0]);
      CHECK(at_zeros[1] < 1e-25 * at_line[0]);
    }
  }
  SECTION("the window's shape: (sin x / x)^4 with x = b log10(f / fc)") {
    // On a grid uniform in log f, centres moved by whole grid steps see the same normalising
    // sum (up to the grid's far ends), so a single line smoothed at fc = f0 10^(m step) is
    // the line's own value times W(b m step). With step = pi / (4 b), m = 2 is halfway to the
    // first zero, W = (2/pi)^4, and m = 4 is the zero itself.
    const double b = 40.0, step = pi / (4.0 * b);
    FourierSpectrum log_grid;
    for (int i = -3000; i <= 3000; ++i) {
      log_grid.frequency.push_back(std::pow(10.0, step * i));
      log_grid.amplitude.push_back(i == 0 ? 1.0 : 0.0);
    }
    const std::vector<double> c{1.0, std::pow(10.0, 2.0 * step), std::pow(10.0, -2.0 * step), std::pow(10.0, 4.0 * step),
                                std::pow(10.0, 6.0 * step)};
    const std::vector<double> v = konno_ohmachi(log_grid, c, b);
    CHECK(v[1] / v[0] == Approx(std::pow(2.0 / pi, 4)).epsilon(1e-6));
    CHECK(v[2] / v[0] == Approx(std::pow(2.0 / pi, 4)).epsilon(1e-6));
    CHECK(v[3] < 1e-25 * v[0]);
    const double x = 1.5 * pi;  // the first side lobe's neighbourhood: (sin x / x)^4
    CHECK(v[4] / v[0] == Approx(std::pow(std::sin(x) / x, 4)).epsilon(1e-6));
  }
  SECTION("a very narrow window returns the raw amplitude at a line's frequency") {
    const std::vector<double> at{s.frequency[90], s.frequency[1000]};
    const std::vector<double> v = konno_ohmachi(s, at, 1e6);
    CHECK(v[0] == Approx(s.amplitude[90]).epsilon(1e-9));
    CHECK(v[1] == Approx(s.amplitude[1000]).epsilon(1e-9));
  }
  SECTION("bad input") {
    CHECK_THROWS_AS(konno_ohmachi(s, centres, 0.0), InputError);
    CHECK_THROWS_AS(konno_ohmachi(s, std::vector<double>{0.0}), InputError);
    CHECK_THROWS_AS(konno_ohmachi(s, std::vector<double>{NAN}), InputError);
    CHECK_THROWS_AS(konno_ohmachi(FourierSpectrum{{0.0}, {1.0}}, centres), InputError);
  }
}

TEST_CASE("spectrum intensities equal an adaptive quadrature of the spectrum (GSL QAG)", "[intensity]") {
  // An independent integration of the same integrand: GSL's adaptive Gauss-Kronrod rule calls
  // the one-oscillator spectrum wherever it wants, so Simpson's fixed 0.005 s grid is checked
  // against a quadrature whose error is controlled.
  const Record record = read_record(std::filesystem::path(ADJOIN_REAL_RECORDS) / "peer" / "RSN1044_DirRot2.AT2");
  struct Integrand {
    const Record* record;
    bool psa;
  };
  auto integrate = [](Integrand& in, double from, double to) {
    gsl_function f;
    f.function = [](double period, void* p) {
      const auto* i = static_cast<Integrand*>(p);
      const SpectralValues v = spectral_values(i->record->dt, i->record->accel, period, 0.05);
      return i->psa ? v.psa : v.psv;
    };
    f.params = &in;
    // The spectrum has kinks (where the peak moves to another cycle), so the rule may stop at
    // "roundoff" before 1e-7; its own error estimate must still be far below the tolerance.
    gsl_error_handler_t* previous = gsl_set_error_handler_off();
    gsl_integration_workspace* w = gsl_integration_workspace_alloc(4000);
    double result = 0.0, error = 0.0;
    const int status = gsl_integration_qag(&f, from, to, 0.0, 1e-7, 4000, GSL_INTEG_GAUSS15, w, &result, &error);
    gsl_integration_workspace_free(w);
    gsl_set_error_handler(previous);
    CHECK((status == GSL_SUCCESS || status == GSL_EROUND));
    CHECK(error <= 1e-6 * std::abs(result));
    return result;
  };
  const SpectrumIntensity si = spectrum_intensity(record);
  Integrand housner{&record, false}, asi{&record, true};
  const double housner_qag = integrate(housner, 0.1, 2.5), asi_qag = integrate(asi, 0.1, 0.5);
  INFO("Housner SI " << si.housner << " m (QAG " << housner_qag << "), ASI " << si.asi << " g s (QAG " << asi_qag << ")");
  CHECK(si.housner == Approx(housner_qag).epsilon(1e-4));
  CHECK(si.asi == Approx(asi_qag).epsilon(1e-4));
}
