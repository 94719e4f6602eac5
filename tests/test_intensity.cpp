// Intensity measures against closed forms on signals whose integrals are known.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "adjoin/errors.hpp"
#include "adjoin/post/intensity.hpp"

using namespace adjoin;
using std::numbers::pi;

namespace {

constexpr double g = 9.80665;

Record make(double dt, std::size_t n, const auto& f) {
  Record r;
  r.source = "synthetic";
  r.dt = dt;
  r.accel.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.accel[i] = f(static_cast<double>(i) * dt);
  return r;
}

}  // namespace

TEST_CASE("sine over whole cycles: Arias, CAV, PGA, D5-95, Fourier amplitude, predominant period", "[intensity]") {
  const double A = 3.0, f = 2.0, T = 10.0;  // 20 cycles
  SECTION("Arias intensity pi A^2 T / (4 g) (trapezoid is exact for sin^2 over whole cycles)") {
    const Record r = make(0.005, 2001, [&](double t) { return A * std::sin(2.0 * pi * f * t); });
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
    const Record r = make(0.001, 10001, [&](double t) { return A * std::sin(2.0 * pi * f * t); });
    CHECK(cumulative_absolute_velocity(r) == Approx(2.0 * A * T / pi).epsilon(2e-5));
  }
  SECTION("Fourier amplitude A T / 2 at f, predominant period 1/f") {
    const Record r = make(0.01, 1000, [&](double t) { return A * std::sin(2.0 * pi * f * t); });  // n dt = T
    const FourierSpectrum s = fourier_amplitude_spectrum(r);
    REQUIRE(s.frequency.size() == 501);
    CHECK(s.frequency[1] == Approx(0.1));
    CHECK(s.frequency.back() == Approx(50.0));
    CHECK(s.amplitude[20] == Approx(A * T / 2.0).epsilon(1e-12));
    CHECK(s.amplitude[19] < 1e-10);
    CHECK(s.amplitude[0] < 1e-10);
    CHECK(predominant_period(r) == Approx(1.0 / f).epsilon(1e-12));
    // A 0.7 Hz sine on top of a weaker 5 Hz one: the period of the stronger.
    const Record two = make(0.01, 1000, [](double t) { return std::sin(2.0 * pi * 0.7 * t) + 0.5 * std::sin(2.0 * pi * 5.0 * t); });
    CHECK(predominant_period(two) == Approx(1.0 / 0.7).epsilon(1e-12));
  }
}

TEST_CASE("PGV and PGD of a cosine: A/(2 pi f) and 2 A/(2 pi f)^2", "[intensity]") {
  const double A = 2.0, f = 1.0, w = 2.0 * pi * f;
  const Record r = make(0.001, 5001, [&](double t) { return A * std::cos(w * t); });
  const IntensityMeasures m = intensity_measures(r);
  CHECK(m.pgv == Approx(A / w).epsilon(1e-5));
  CHECK(m.pgd == Approx(2.0 * A / (w * w)).epsilon(1e-5));
  // The velocity history itself: v = A sin(w t) / w.
  const auto v = cumulative_trapezoid(r.accel, r.dt);
  for (std::size_t i = 0; i < v.size(); i += 613) CHECK(v[i] == Approx(A * std::sin(w * i * 0.001) / w).margin(1e-6));
}

TEST_CASE("constant amplitude: D5-95 = 0.9 duration exactly; triangle wave CAV exactly", "[intensity]") {
  const Record c = make(0.02, 501, [](double) { return -1.5; });  // 10 s
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
  Record tr = make(0.01, 1001, tri);
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
  const Record zero = make(0.01, 100, [](double) { return 0.0; });
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
