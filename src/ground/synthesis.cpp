// Synthetic ground motion by filtered white noise (see synthesis.hpp for the conventions).
#include "adjoin/ground/synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <system_error>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/number_text.hpp"
#include "adjoin/core/units.hpp"
#include "synthesis_detail.hpp"

namespace adjoin {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::size_t kMaxSamples = std::size_t{1} << 26;

std::string normalise(std::string name) {
  for (char& c : name) {
    if (c == '_') c = '-';
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return name;
}

bool positive(double x) { return x > 0.0 && std::isfinite(x); }

bool fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

}  // namespace

bool parse_spectrum_model(const std::string& name, SpectrumModel* model) { return parse_enum(normalise(name), model); }

bool parse_envelope_kind(const std::string& name, EnvelopeKind* kind) { return parse_enum(normalise(name), kind); }

Envelope resolve_envelope(const Envelope& envelope, double duration) {
  Envelope e = envelope;
  if (e.kind == EnvelopeKind::jennings_housner_tsai) {
    if (!e.t1) e.t1 = 0.1 * duration;
    if (!e.t2) e.t2 = std::max(*e.t1, 0.5 * duration);
    if (!e.decay) e.decay = duration > *e.t2 ? std::log(20.0) / (duration - *e.t2) : std::log(20.0) / (0.5 * duration);
  } else if (e.kind == EnvelopeKind::saragoni_hart) {
    if (!e.eps) e.eps = 0.2;
    if (!e.eta) e.eta = 0.05;
    if (!e.t_n) e.t_n = duration;
  }
  return e;
}

double envelope_value(const Envelope& e, double t) {
  switch (e.kind) {
    case EnvelopeKind::none: return 1.0;
    case EnvelopeKind::jennings_housner_tsai: {
      const double t1 = e.t1.value_or(0.0), t2 = e.t2.value_or(t1), c = e.decay.value_or(0.0);
      if (t < 0.0) return 0.0;
      if (t < t1) return (t / t1) * (t / t1);
      if (t <= t2) return 1.0;
      return std::exp(-c * (t - t2));
    }
    case EnvelopeKind::saragoni_hart: {
      const double eps = e.eps.value_or(0.2), eta = e.eta.value_or(0.05), tn = e.t_n.value_or(1.0);
      if (t <= 0.0) return 0.0;
      const double b = -eps * std::log(eta) / (1.0 + eps * (std::log(eps) - 1.0));
      const double c = b / eps;
      const double s = t / tn;
      // (e/eps)^b s^b e^{-c s}, in logarithms.
      return std::exp(b * (1.0 - std::log(eps) + std::log(s)) - c * s);
    }
  }
  return 1.0;
}

namespace {

bool envelope_valid(const Envelope& e, const std::string& prefix, std::string* error) {
  auto check = [&](const std::optional<double>& v, const char* key, bool ok, const char* expected) {
    if (v && !ok) return fail(error, prefix + key + " = " + shortest_text(*v) + ": expected " + expected);
    return true;
  };
  if (e.kind == EnvelopeKind::jennings_housner_tsai) {
    if (!check(e.t1, "t1", e.t1 && *e.t1 >= 0.0 && std::isfinite(*e.t1), "a rise time >= 0 s")) return false;
    if (!check(e.t2, "t2", e.t2 && *e.t2 >= 0.0 && std::isfinite(*e.t2), "an end of the plateau >= 0 s")) return false;
    if (e.t1 && e.t2 && *e.t2 < *e.t1)
      return fail(error, prefix + "t2 = " + shortest_text(*e.t2) + ": expected the end of the plateau >= " + prefix +
                             "t1 = " + shortest_text(*e.t1));
    if (!check(e.decay, "decay", e.decay && positive(*e.decay), "a decay rate > 0 [1/s]")) return false;
  } else if (e.kind == EnvelopeKind::saragoni_hart) {
    if (!check(e.eps, "eps", e.eps && *e.eps > 0.0 && *e.eps < 1.0, "a peak-time fraction 0 < eps < 1")) return false;
    if (!check(e.eta, "eta", e.eta && *e.eta > 0.0 && *e.eta < 1.0, "an end level 0 < eta < 1")) return false;
    if (!check(e.t_n, "t_n", e.t_n && positive(*e.t_n), "a time t_n > 0 s")) return false;
  }
  return true;
}

}  // namespace

bool SynthesisOptions::IsValid(std::string* error) const {
  if (!positive(dt)) return fail(error, "ground.dt = " + shortest_text(dt) + ": expected a time step > 0 s");
  if (!positive(duration) || duration < dt)
    return fail(error, "ground.duration = " + shortest_text(duration) + ": expected a duration >= ground.dt = " + shortest_text(dt) + " s");
  if (duration / dt >= static_cast<double>(kMaxSamples))
    return fail(error, "ground.duration = " + shortest_text(duration) + ": more than 2^26 samples at ground.dt = " + shortest_text(dt));
  const double nyquist = kPi / dt;
  if (!positive(omega_g)) return fail(error, "ground.omega_g = " + shortest_text(omega_g) + ": expected a frequency > 0 rad/s");
  if (omega_g >= nyquist)
    return fail(error, "ground.omega_g = " + shortest_text(omega_g) + ": expected a frequency below the Nyquist frequency pi/dt = " +
                           shortest_text(nyquist) + " rad/s (reduce ground.dt)");
  if (!positive(zeta_g)) return fail(error, "ground.zeta_g = " + shortest_text(zeta_g) + ": expected a damping ratio > 0");
  if (spectrum == SpectrumModel::clough_penzien) {
    if (!positive(omega_f)) return fail(error, "ground.omega_f = " + shortest_text(omega_f) + ": expected a frequency > 0 rad/s");
    if (omega_f >= nyquist)
      return fail(error, "ground.omega_f = " + shortest_text(omega_f) + ": expected a frequency below pi/dt = " + shortest_text(nyquist) + " rad/s");
    if (!positive(zeta_f)) return fail(error, "ground.zeta_f = " + shortest_text(zeta_f) + ": expected a damping ratio > 0");
  }
  if (s0 && target_pga)
    return fail(error, "ground.s0 and ground.target_pga: give one intensity, not both");
  if (!s0 && !target_pga)
    return fail(error, "ground.s0 / ground.target_pga: missing intensity (expected S0 [m^2/s^3] or a target PGA [g])");
  // Upper bounds that keep every output finite (the accelerations within 1e6 g, as records).
  if (s0 && !(positive(*s0) && *s0 <= 1e12)) return fail(error, "ground.s0 = " + shortest_text(*s0) + ": expected a spectral density > 0 and at most 1e12 m^2/s^3");
  if (target_pga && !(positive(*target_pga) && *target_pga <= 1e6))
    return fail(error, "ground.target_pga = " + shortest_text(*target_pga) + ": expected a PGA > 0 and at most 1e6 g");
  return envelope_valid(envelope, "ground.", error);
}

double kanai_tajimi_psd(double omega, double omega_g, double zeta_g, double s0) {
  const double w2 = omega * omega, g2 = omega_g * omega_g;
  const double c = 4.0 * zeta_g * zeta_g * g2 * w2;
  return s0 * (g2 * g2 + c) / ((g2 - w2) * (g2 - w2) + c);
}

double clough_penzien_factor(double omega, double omega_f, double zeta_f) {
  const double w2 = omega * omega, f2 = omega_f * omega_f;
  return w2 * w2 / ((f2 - w2) * (f2 - w2) + 4.0 * zeta_f * zeta_f * f2 * w2);
}

double kanai_tajimi_variance(double omega_g, double zeta_g, double s0) {
  return kPi * s0 * omega_g * (1.0 + 4.0 * zeta_g * zeta_g) / (2.0 * zeta_g);
}

double ground_psd(const SynthesisOptions& o, double omega) {
  double s = kanai_tajimi_psd(omega, o.omega_g, o.zeta_g, o.s0.value_or(1.0));
  if (o.spectrum == SpectrumModel::clough_penzien) s *= clough_penzien_factor(omega, o.omega_f, o.zeta_f);
  return s;
}

std::size_t synthesis_samples(double duration, double dt) {
  return static_cast<std::size_t>(std::floor(duration / dt + 1e-9)) + 1;
}

std::size_t synthesis_fft_length(std::size_t n) { return detail::smooth_fft_length(n); }

double discrete_variance(const SynthesisOptions& o) {
  const std::size_t m = synthesis_fft_length(synthesis_samples(o.duration, o.dt));
  const double dw = 2.0 * kPi / (static_cast<double>(m) * o.dt);
  double sum = 0.0;
  for (std::size_t k = 1; k < m / 2; ++k) sum += 2.0 * ground_psd(o, static_cast<double>(k) * dw) * dw;
  return sum;
}

namespace detail {

std::string describe(const SynthesisOptions& o, bool intensity) {
  const Envelope envelope = resolve_envelope(o.envelope, o.duration);
  const std::size_t n = synthesis_samples(o.duration, o.dt);
  std::ostringstream d;
  d << "filtered noise: " << to_string(o.spectrum) << " omega_g=" << shortest_text(o.omega_g) << " rad/s zeta_g=" << shortest_text(o.zeta_g);
  if (o.spectrum == SpectrumModel::clough_penzien) d << " omega_f=" << shortest_text(o.omega_f) << " rad/s zeta_f=" << shortest_text(o.zeta_f);
  if (intensity && o.s0) d << " S0=" << shortest_text(*o.s0) << " m^2/s^3";
  if (intensity && o.target_pga) d << " target PGA=" << shortest_text(*o.target_pga) << " g";
  d << "; envelope " << to_string(envelope.kind);
  if (envelope.kind == EnvelopeKind::jennings_housner_tsai)
    d << " t1=" << shortest_text(*envelope.t1) << " s t2=" << shortest_text(*envelope.t2) << " s decay=" << shortest_text(*envelope.decay) << " 1/s";
  if (envelope.kind == EnvelopeKind::saragoni_hart)
    d << " eps=" << shortest_text(*envelope.eps) << " eta=" << shortest_text(*envelope.eta) << " t_n=" << shortest_text(*envelope.t_n) << " s";
  d << "; duration=" << shortest_text(static_cast<double>(n - 1) * o.dt) << " s dt=" << shortest_text(o.dt) << " s seed=" << o.seed;
  return d.str();
}

// The stationary process on the whole FFT grid (M samples), S0 = s0 (or 1).
std::vector<double> stationary_process(const SynthesisOptions& o) {
  const std::size_t n = synthesis_samples(o.duration, o.dt);
  const std::size_t m = synthesis_fft_length(n);
  const std::size_t half = m / 2;
  const double dw = 2.0 * kPi / (static_cast<double>(m) * o.dt);
  ComplexArray spectrum = complex_array(half + 1);
  RealArray out = real_array(m);
  std::mt19937_64 generator(o.seed);
  constexpr double kTwoTo53 = 1.0 / 9007199254740992.0;
  auto uniform = [&] { return (static_cast<double>(generator() >> 11) + 0.5) * kTwoTo53; };
  spectrum[0][0] = spectrum[0][1] = 0.0;
  for (std::size_t k = 1; k < half; ++k) {
    const double u1 = uniform(), u2 = uniform();
    // c2r gives x_j = Y_0 + 2 Re sum_k Y_k e^{..}: Y_k = sqrt(2 S dw) z / 2.
    const double amplitude = std::sqrt(0.5 * ground_psd(o, static_cast<double>(k) * dw) * dw) *
                             std::sqrt(-2.0 * std::log(u1));
    const double phase = 2.0 * kPi * u2;
    spectrum[k][0] = amplitude * std::cos(phase);
    spectrum[k][1] = amplitude * std::sin(phase);
  }
  spectrum[half][0] = spectrum[half][1] = 0.0;
  inverse_real_fft(m, spectrum.get(), out.get());
  return std::vector<double>(out.get(), out.get() + m);
}

}  // namespace detail

Record synthesize(const SynthesisOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw InputError(error);
  const std::size_t n = synthesis_samples(o.duration, o.dt);
  std::vector<double> x = detail::stationary_process(o);
  x.resize(n);
  const Envelope envelope = resolve_envelope(o.envelope, o.duration);
  if (envelope.kind != EnvelopeKind::none)
    for (std::size_t i = 0; i < n; ++i) x[i] *= envelope_value(envelope, static_cast<double>(i) * o.dt);
  if (o.target_pga) {
    double peak = 0.0;
    for (double v : x) peak = std::max(peak, std::abs(v));
    if (!(peak > 0.0)) throw InputError("ground: the synthesized motion is zero (duration too short for the spectrum?)");
    const double target = *o.target_pga * kStandardGravity;
    const double factor = target / peak;
    for (double& v : x) v *= factor;
    // Make max |a| equal to the target exactly (the product may be off by one rounding).
    for (double& v : x)
      if (std::abs(v) >= target * (1.0 - 1e-15)) v = std::copysign(target, v);
  }
  Record r;
  r.source = "synthetic filtered-noise";
  r.description = detail::describe(o, true);
  r.dt = o.dt;
  r.accel = std::move(x);
  return r;
}

}  // namespace adjoin
