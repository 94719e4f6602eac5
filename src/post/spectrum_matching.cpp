// Spectrum-compatible motions by iterative Fourier-amplitude scaling (see spectrum_matching.hpp).
#include "adjoin/post/spectrum_matching.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string_view>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/number_text.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"
#include "../ground/synthesis_detail.hpp"

namespace adjoin {
namespace {

constexpr double kPi = std::numbers::pi;

bool fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

}  // namespace

Ec8Parameters ec8_parameters(char ground_type, int spectrum_type) {
  if (spectrum_type != 1 && spectrum_type != 2)
    throw InputError("EC8 spectrum type " + std::to_string(spectrum_type) + ": expected 1 or 2");
  const bool one = spectrum_type == 1;
  switch (upper(ground_type)) {
    case 'A': return one ? Ec8Parameters{1.0, 0.15, 0.4, 2.0} : Ec8Parameters{1.0, 0.05, 0.25, 1.2};
    case 'B': return one ? Ec8Parameters{1.2, 0.15, 0.5, 2.0} : Ec8Parameters{1.35, 0.05, 0.25, 1.2};
    case 'C': return one ? Ec8Parameters{1.15, 0.20, 0.6, 2.0} : Ec8Parameters{1.5, 0.10, 0.25, 1.2};
    case 'D': return one ? Ec8Parameters{1.35, 0.20, 0.8, 2.0} : Ec8Parameters{1.8, 0.10, 0.30, 1.2};
    case 'E': return one ? Ec8Parameters{1.4, 0.15, 0.5, 2.0} : Ec8Parameters{1.6, 0.05, 0.25, 1.2};
    default: break;
  }
  throw InputError(std::string("EC8 ground type '") + ground_type + "': expected A, B, C, D or E");
}

double ec8_damping_correction(double damping) {
  if (!(damping >= 0.0 && damping < 1.0))
    throw InputError("EC8 damping correction: damping ratio " + shortest_text(damping) + " (expected 0 <= damping < 1)");
  return std::max(std::sqrt(10.0 / (5.0 + 100.0 * damping)), 0.55);
}

double ec8_psa(double period, char ground_type, double ag, int spectrum_type, double damping) {
  const Ec8Parameters p = ec8_parameters(ground_type, spectrum_type);
  const double eta = ec8_damping_correction(damping);
  const double plateau = 2.5 * ag * p.S * eta;
  if (period <= p.TB) return ag * p.S * (1.0 + period / p.TB * (2.5 * eta - 1.0));
  if (period <= p.TC) return plateau;
  if (period <= p.TD) return plateau * p.TC / period;
  return plateau * p.TC * p.TD / (period * period);
}

TargetSpectrum TargetSpectrum::ec8(char ground_type, double ag, int spectrum_type) {
  ec8_parameters(ground_type, spectrum_type);  // checks both
  // (At most 10 g: beyond any code's design acceleration, and what keeps the matching's
  // corrections, 10x at most each, within its iterations.)
  if (!(ag > 0.0 && ag <= 10.0)) throw InputError("EC8 ag = " + shortest_text(ag) + ": expected a design ground acceleration > 0 and at most 10 g");
  TargetSpectrum t;
  t.kind = Kind::ec8;
  t.ground_type = upper(ground_type);
  t.ag = ag;
  t.ec8_type = spectrum_type;
  t.name = "EC8 type " + std::to_string(spectrum_type) + ", ground " + t.ground_type + ", ag = " + shortest_text(ag) + " g";
  return t;
}

TargetSpectrum TargetSpectrum::table(std::vector<double> periods, std::vector<double> psa, std::string name) {
  if (periods.size() != psa.size()) throw InputError(name + ": periods and PSA values differ in number");
  if (periods.size() < 2) throw InputError(name + ": a target table needs at least two rows (period [s], PSA [g])");
  for (std::size_t i = 0; i < periods.size(); ++i) {
    if (!std::isfinite(periods[i]) || periods[i] < 0.0)
      throw InputError(name + ": row " + std::to_string(i + 1) + ": period " + shortest_text(periods[i]) + " (expected >= 0 s)");
    if (!(psa[i] > 0.0 && psa[i] <= 100.0))
      throw InputError(name + ": row " + std::to_string(i + 1) + ": PSA " + shortest_text(psa[i]) + " (expected > 0 and at most 100 g)");
    if (i > 0 && !(periods[i] > periods[i - 1]))
      throw InputError(name + ": row " + std::to_string(i + 1) + ": period " + shortest_text(periods[i]) +
                       " (expected periods to increase strictly)");
  }
  TargetSpectrum t;
  t.kind = Kind::table;
  t.periods = std::move(periods);
  t.psa = std::move(psa);
  t.name = std::move(name);
  return t;
}

double TargetSpectrum::psa_at(double period, double damping) const {
  if (kind == Kind::ec8) return ec8_psa(period, ground_type, ag, ec8_type, damping);
  if (period < periods.front() || period > periods.back())
    throw InputError(name + ": period " + shortest_text(period) + " s is outside the table (" + shortest_text(periods.front()) + " to " +
                     shortest_text(periods.back()) + " s)");
  const auto it = std::upper_bound(periods.begin(), periods.end(), period);
  if (it == periods.end()) return psa.back();
  const std::size_t i = static_cast<std::size_t>(it - periods.begin());
  const double w = (period - periods[i - 1]) / (periods[i] - periods[i - 1]);
  return psa[i - 1] + w * (psa[i] - psa[i - 1]);
}

double TargetSpectrum::min_period() const { return kind == Kind::table ? periods.front() : 0.0; }
double TargetSpectrum::max_period() const {
  return kind == Kind::table ? periods.back() : std::numeric_limits<double>::infinity();
}

TargetSpectrum load_target_spectrum(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot read the target spectrum file");
  std::vector<double> periods, psa;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 && line.size() >= 3 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#' || line[first] == '%') continue;
    const std::string where = path.string() + ":" + std::to_string(number) + ": ";
    std::vector<double> values;
    std::size_t pos = first;
    while (pos < line.size()) {
      pos = line.find_first_not_of(" \t,;", pos);
      if (pos == std::string::npos) break;
      std::size_t end = line.find_first_of(" \t,;", pos);
      if (end == std::string::npos) end = line.size();
      double v = 0.0;
      if (!parse_finite(std::string_view(line).substr(pos, end - pos), &v))
        throw InputError(where + "'" + line.substr(pos, end - pos) + "' is not a number (expected period [s] and PSA [g])");
      values.push_back(v);
      pos = end;
    }
    if (values.size() != 2)
      throw InputError(where + std::to_string(values.size()) + " values (expected two: period [s] and PSA [g])");
    if (values[0] < 0.0) throw InputError(where + "period " + shortest_text(values[0]) + " (expected >= 0 s)");
    if (!(values[1] > 0.0)) throw InputError(where + "PSA " + shortest_text(values[1]) + " (expected > 0 g)");
    if (!periods.empty() && !(values[0] > periods.back()))
      throw InputError(where + "period " + shortest_text(values[0]) + " after " + shortest_text(periods.back()) +
                       " (expected periods to increase strictly)");
    periods.push_back(values[0]);
    psa.push_back(values[1]);
  }
  if (periods.size() < 2)
    throw InputError(path.string() + ": " + std::to_string(periods.size()) +
                     " rows (expected at least two rows of period [s] and PSA [g])");
  return TargetSpectrum::table(std::move(periods), std::move(psa), path.string());
}

TargetSpectrum parse_target_spectrum(const std::string& text) {
  std::string lower = text;
  for (char& c : lower)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  if (lower.rfind("ec8:", 0) == 0) {
    // ec8:T[:AG[:TYPE]]
    std::vector<std::string> parts;
    for (std::size_t start = 4;;) {
      const std::size_t colon = text.find(':', start);
      parts.push_back(text.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
      if (colon == std::string::npos) break;
      start = colon + 1;
    }
    const std::string usage = "expected ec8:T, ec8:T:AG or ec8:T:AG:TYPE with ground type T one of A, B, C, D, E, "
                              "ag in g and spectrum type 1 or 2";
    if (parts.size() > 3 || parts[0].size() != 1) throw InputError("'" + text + "': " + usage);
    double ag = 0.25;
    if (parts.size() >= 2) {
      const std::string& a = parts[1];
      if (!parse_finite(a, &ag))
        throw InputError("'" + text + "': '" + a + "' is not a number (expected ag in g, e.g. ec8:B:0.25)");
    }
    int type = 1;
    if (parts.size() == 3) {
      if (parts[2] != "1" && parts[2] != "2")
        throw InputError("'" + text + "': spectrum type '" + parts[2] + "' (expected 1 or 2, e.g. ec8:B:0.25:2)");
      type = parts[2] == "2" ? 2 : 1;
    }
    try {
      return TargetSpectrum::ec8(parts[0][0], ag, type);
    } catch (const InputError& e) {
      throw InputError("'" + text + "': " + e.what());
    }
  }
  return load_target_spectrum(text);
}

bool MatchOptions::IsValid(std::string* error) const {
  if (!(period_min > 0.0) || !std::isfinite(period_min))
    return fail(error, "match.period_min = " + shortest_text(period_min) + ": expected a period > 0 s");
  if (!(period_max > period_min) || !std::isfinite(period_max))
    return fail(error, "match.period_max = " + shortest_text(period_max) + ": expected a period > match.period_min = " +
                           shortest_text(period_min) + " s");
  if (period_min < target.min_period() || period_max > target.max_period())
    return fail(error, "match.period_min/period_max = " + shortest_text(period_min) + "/" + shortest_text(period_max) +
                           ": expected a band inside the target's periods (" + shortest_text(target.min_period()) + " to " +
                           shortest_text(target.max_period()) + " s of " + target.name + ")");
  if (band_points < 2) return fail(error, "match.band_points = " + std::to_string(band_points) + ": expected >= 2");
  if (!(damping >= 0.0 && damping < 1.0)) return fail(error, "match.damping = " + shortest_text(damping) + ": expected 0 <= damping < 1");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    return fail(error, "match.tolerance = " + shortest_text(tolerance) + ": expected a relative tolerance > 0");
  if (max_iterations < 0) return fail(error, "match.max_iterations = " + std::to_string(max_iterations) + ": expected >= 0");
  if (attempts < 1) return fail(error, "match.attempts = " + std::to_string(attempts) + ": expected >= 1");
  return true;
}

namespace {

// Linear interpolation of ratio(ln f) through (x_i, r_i) (x ascending), held at the ends up to
// the last point, then blended to 1 over one octave by a half cosine.
double gain_factor(double lf, const std::vector<double>& x, const std::vector<double>& r) {
  const double octave = std::log(2.0);
  auto blend = [&](double edge, double distance) {
    const double w = distance / octave;
    if (w >= 1.0) return 1.0;
    const double s = 0.5 * (1.0 - std::cos(kPi * w));
    return edge * (1.0 - s) + s;
  };
  if (lf <= x.front()) return blend(r.front(), x.front() - lf);
  if (lf >= x.back()) return blend(r.back(), lf - x.back());
  const auto it = std::upper_bound(x.begin(), x.end(), lf);
  const std::size_t i = static_cast<std::size_t>(it - x.begin());
  const double w = (lf - x[i - 1]) / (x[i] - x[i - 1]);
  return r[i - 1] + w * (r[i] - r[i - 1]);
}

// The matching loop on a buffer of m samples whose first n are the motion.
// `envelope` (n values, or empty): the shape the motion must keep. The buffer then holds a
// stationary motion; each iteration's gains shape its spectrum, and the envelope is applied
// before the response spectrum is measured, so the matched motion has the envelope exactly
// (SIMQKE's way). Without it, gains change the record as given.
Record match_core(std::vector<double> buffer, std::size_t n, double dt, const MatchOptions& o, MatchReport* report,
                  Record prototype, const std::vector<double>& envelope = {}) {
  // A record shorter than a band period cannot shape that period's response: the corrections
  // would never converge, and each of the up to max_iterations x attempts would still cost a
  // whole spectrum (found by the scene fuzzer: a 0.01 s record took seconds to fail).
  const double duration = static_cast<double>(n - 1) * dt;
  if (!(duration >= o.period_max))
    throw InputError("spectrum matching: the record lasts " + shortest_text(duration) + " s, less than the band's longest period " +
                     "(match.period_max = " + shortest_text(o.period_max) + " s); give a record at least that long or a shorter band");
  const std::size_t m = buffer.size();
  const std::size_t half = m / 2;
  detail::RealArray real = detail::real_array(m);
  detail::ComplexArray y0 = detail::complex_array(half + 1), work = detail::complex_array(half + 1);
  std::copy(buffer.begin(), buffer.end(), real.get());
  detail::forward_real_fft(m, real.get(), y0.get());
  std::vector<double> gain(half + 1, 1.0 / static_cast<double>(m));

  // Periods: the band, and one octave beyond each end in quarter octaves (inside the target).
  const std::vector<double> band = period_range(o.period_min, o.period_max, o.band_points, PeriodSpacing::log);
  std::vector<double> periods;
  for (int k = 4; k >= 1; --k) {
    const double t = o.period_min / std::pow(2.0, k / 4.0);
    if (t >= o.target.min_period() && t > 0.0) periods.push_back(t);
  }
  const std::size_t band_first = periods.size();
  periods.insert(periods.end(), band.begin(), band.end());
  for (int k = 1; k <= 4; ++k) {
    const double t = o.period_max * std::pow(2.0, k / 4.0);
    if (t <= o.target.max_period()) periods.push_back(t);
  }
  std::vector<double> target(periods.size());
  for (std::size_t i = 0; i < periods.size(); ++i) target[i] = o.target.psa_at(periods[i], o.damping);
  // ln f ascending: periods descending.
  std::vector<double> lf(periods.size()), ratio(periods.size());
  for (std::size_t i = 0; i < periods.size(); ++i) lf[periods.size() - 1 - i] = -std::log(periods[i]);

  SpectrumOptions spectrum;
  spectrum.periods = periods;
  spectrum.dampings = {o.damping};

  std::vector<double> accel(n), best;
  MatchReport r;
  double best_max = std::numeric_limits<double>::infinity();
  for (int iteration = 0;; ++iteration) {
    for (std::size_t k = 0; k <= half; ++k) {
      work[k][0] = gain[k] * y0[k][0];
      work[k][1] = gain[k] * y0[k][1];
    }
    detail::inverse_real_fft(m, work.get(), real.get());
    std::copy(real.get(), real.get() + n, accel.begin());
    if (!envelope.empty())
      for (std::size_t i = 0; i < n; ++i) accel[i] *= envelope[i];
    const ResponseSpectrum s = response_spectrum(dt, accel, spectrum);
    double max_misfit = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < band.size(); ++i) {
      const double misfit = std::abs(s.at(0, band_first + i).psa / target[band_first + i] - 1.0);
      if (!std::isfinite(misfit)) throw NumericalError("spectrum matching: non-finite PSA at iteration " + std::to_string(iteration), 0.0);
      max_misfit = std::max(max_misfit, misfit);
      sum += misfit;
    }
    r.max_misfit_history.push_back(max_misfit);
    if (max_misfit < best_max) {
      best_max = max_misfit;
      best = accel;
      r.iterations = iteration;
      r.max_misfit = max_misfit;
      r.mean_misfit = sum / static_cast<double>(band.size());
      r.psa.resize(band.size());
      for (std::size_t i = 0; i < band.size(); ++i) r.psa[i] = s.at(0, band_first + i).psa;
    }
    if (max_misfit <= o.tolerance || iteration >= o.max_iterations) break;
    for (std::size_t i = 0; i < periods.size(); ++i) {
      const double psa = s.at(0, i).psa;
      ratio[periods.size() - 1 - i] = psa > 0.0 ? std::clamp(target[i] / psa, 0.1, 10.0) : 10.0;
    }
    // The overall level c (geometric mean of the band ratios) scales every frequency; the
    // local ratios relative to it shape the band and blend to c outside.
    double log_c = 0.0;
    for (std::size_t i = 0; i < band.size(); ++i) log_c += std::log(ratio[periods.size() - 1 - band_first - i]);
    const double c = std::exp(log_c / static_cast<double>(band.size()));
    for (double& v : ratio) v /= c;
    const double df = 1.0 / (static_cast<double>(m) * dt);
    gain[0] *= c * gain_factor(-std::numeric_limits<double>::infinity(), lf, ratio);
    for (std::size_t k = 1; k <= half; ++k) gain[k] *= c * gain_factor(std::log(static_cast<double>(k) * df), lf, ratio);
  }
  r.converged = r.max_misfit <= o.tolerance;
  r.periods = band;
  r.target.assign(target.begin() + static_cast<std::ptrdiff_t>(band_first),
                  target.begin() + static_cast<std::ptrdiff_t>(band_first + band.size()));
  if (report) *report = r;

  Record out = std::move(prototype);
  out.dt = dt;
  out.accel = std::move(best);
  std::ostringstream d;
  d << "; matched to " << o.target.name << ", damping " << shortest_text(100.0 * o.damping) << " %, over " << shortest_text(o.period_min) << "-" << shortest_text(o.period_max) << " s ("
    << r.iterations << " iterations, max misfit " << shortest_text(std::round(r.max_misfit * 1e4) / 1e4) << ", mean "
    << shortest_text(std::round(r.mean_misfit * 1e4) / 1e4) << ")";
  out.description += d.str();
  return out;
}

void check_options(const MatchOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw InputError(error);
}

}  // namespace

Record match_spectrum(Record seed, const MatchOptions& o, MatchReport* report) {
  check_options(o);
  if (seed.accel.size() < 2) throw InputError(seed.source + ": spectrum matching needs a record of at least two samples");
  if (!(seed.dt > 0.0) || !std::isfinite(seed.dt)) throw InputError(seed.source + ": the record's dt must be positive");
  for (double v : seed.accel)
    if (!std::isfinite(v)) throw InputError(seed.source + ": non-finite acceleration in the seed record");
  const std::size_t n = seed.accel.size();
  std::vector<double> buffer(detail::smooth_fft_length(2 * n), 0.0);
  std::copy(seed.accel.begin(), seed.accel.end(), buffer.begin());
  const double dt = seed.dt;
  seed.accel.clear();
  return match_core(std::move(buffer), n, dt, o, report, std::move(seed));
}

Record synthesize_matched(const SynthesisOptions& synthesis, const MatchOptions& options, MatchReport* report) {
  check_options(options);
  SynthesisOptions s = synthesis;
  s.s0 = 1.0;
  s.target_pga.reset();
  std::string error;
  if (!s.IsValid(&error)) throw InputError(error);
  Record best;
  MatchReport best_report;
  // The matching shapes a stationary motion and applies the envelope each iteration, so the
  // matched motion keeps the envelope's shape (shaping the enveloped motion instead spreads
  // long-period energy over the whole record: a 0.24 g pulse at 0.18 s where an ASCE 7 target's
  // envelope was below 1 %).
  SynthesisOptions stationary = s;
  stationary.envelope = Envelope{};
  stationary.envelope.kind = EnvelopeKind::none;
  const Envelope shape = resolve_envelope(synthesis.envelope, synthesis.duration);
  for (int attempt = 0; attempt < options.attempts; ++attempt) {
    stationary.seed = s.seed = attempt_seed(synthesis.seed, attempt);
    Record seed = synthesize(stationary);
    seed.description = detail::describe(s, false);
    std::vector<double> envelope(seed.accel.size());
    for (std::size_t i = 0; i < envelope.size(); ++i) envelope[i] = envelope_value(shape, static_cast<double>(i) * seed.dt);
    MatchReport r;
    const std::size_t n = seed.accel.size();
    std::vector<double> buffer(detail::smooth_fft_length(2 * n), 0.0);
    std::copy(seed.accel.begin(), seed.accel.end(), buffer.begin());
    const double dt = seed.dt;
    seed.accel.clear();
    Record matched = match_core(std::move(buffer), n, dt, options, &r, std::move(seed), envelope);
    r.attempt = attempt;
    r.phase_seed = s.seed;
    if (attempt == 0 || r.max_misfit < best_report.max_misfit) {
      best = std::move(matched);
      best_report = std::move(r);
    }
    if (best_report.converged) break;
  }
  if (report) *report = best_report;
  return best;
}

std::uint64_t attempt_seed(std::uint64_t seed, int attempt) {
  if (attempt == 0) return seed;
  // splitmix64 of seed + attempt * golden ratio constant.
  std::uint64_t z = seed + static_cast<std::uint64_t>(attempt) * 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace adjoin
