// adjoin synth [--spectrum kt|cp] [--omega-g W] [--zeta-g Z] [--omega-f W] [--zeta-f Z]
//              [--s0 S0 | --pga G] [--envelope jht|sh|none] [--t1 S] [--t2 S] [--decay C]
//              [--eps E] [--eta H] [--tn S] [--duration S] [--dt S] [--seed N]
//              [--match ec8:T[:AG[:TYPE]]|FILE] [--damping Z] [--band T0:T1] [--band-points N] [--tolerance R]
//              [--max-iterations N] [--attempts N] --out FILE
//
// Synthesizes filtered white noise (ground/synthesis.hpp), optionally matched to a target
// response spectrum (post/spectrum_matching.hpp), and writes it as two columns "t a" (t in s,
// a in g) after a '#' header that says how it was made, including the complete command (every
// option spelled out) that reproduces it bit for bit (the header avoids the word NPTS, which
// would make the automatic reader take the file for AT2). Read it back with
// `read_record(FILE, {two_column, g})` or `adjoin record info FILE --units g`. Prints the PGA and,
// when matching, the iterations and misfit. A match that does not reach the tolerance is a
// numerical failure (exit 3) and writes nothing.
#include <cctype>
#include <cmath>
#include <iostream>
#include <cstdint>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/number_text.hpp"
#include "adjoin/io/record_writer.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/ground/synthesis.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/intensity.hpp"
#include "command.hpp"

namespace adjoin::cli {
namespace {

struct SynthArgs {
  std::string spectrum = "cp", envelope = "jht";
  double omega_g = 15.6, zeta_g = 0.6, omega_f = 1.5, zeta_f = 0.6;
  std::optional<double> s0, pga, t1, t2, decay, eps, eta, tn;
  double duration = 20.0, dt = 0.005;
  std::uint64_t seed = 1;
  std::string seed_text;  // as given: parsed strictly (CLI11 would wrap -1 and saturate 2^64)
  std::string match, band = "0.1:3";
  std::size_t band_points = 100;
  double tolerance = 0.10;
  std::optional<double> damping;
  int max_iterations = 100;
  int attempts = 5;
  std::string out;
};

// Quotes a word for a POSIX shell when it needs it.
std::string shell_word(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.,:/=+@%") ==
                        std::string::npos)
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

void parse_band(const std::string& text, MatchOptions* m) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || !parse_finite(std::string_view(text).substr(0, colon), &m->period_min) ||
      !parse_finite(std::string_view(text).substr(colon + 1), &m->period_max))
    throw InputError("--band " + text_excerpt(text) + ": expected T0:T1, two periods in s (e.g. 0.1:3)");
}

int synth_command(SynthArgs& a) {
  SynthesisOptions o;
  if (!parse_spectrum_model(a.spectrum, &o.spectrum))
    throw InputError("--spectrum " + text_excerpt(a.spectrum) + ": expected kt (Kanai-Tajimi) or cp (Clough-Penzien)");
  o.omega_g = a.omega_g;
  o.zeta_g = a.zeta_g;
  o.omega_f = a.omega_f;
  o.zeta_f = a.zeta_f;
  o.s0 = a.s0;
  o.target_pga = a.pga;
  if (!parse_envelope_kind(a.envelope, &o.envelope.kind))
    throw InputError("--envelope " + text_excerpt(a.envelope) + ": expected jht (Jennings-Housner-Tsai), sh (Saragoni-Hart) or none");
  const bool jht = o.envelope.kind == EnvelopeKind::jennings_housner_tsai;
  const bool sh = o.envelope.kind == EnvelopeKind::saragoni_hart;
  if (!jht && (a.t1 || a.t2 || a.decay)) throw InputError("--t1/--t2/--decay: only with --envelope jht");
  if (!sh && (a.eps || a.eta || a.tn)) throw InputError("--eps/--eta/--tn: only with --envelope sh");
  o.envelope.t1 = a.t1;
  o.envelope.t2 = a.t2;
  o.envelope.decay = a.decay;
  o.envelope.eps = a.eps;
  o.envelope.eta = a.eta;
  o.envelope.t_n = a.tn;
  o.duration = a.duration;
  o.dt = a.dt;
  if (!a.seed_text.empty()) {
    const std::string& t = a.seed_text;
    std::size_t v = 0;
    static_assert(sizeof v == sizeof a.seed, "a seed is a 64-bit count");
    if (!parse_count(t, &v))
      throw InputError("--seed " + text_excerpt(t) + ": expected a whole number from 0 to 18446744073709551615");
    a.seed = v;
  }
  o.seed = a.seed;

  const bool matching = !a.match.empty();
  if (matching && a.pga) throw InputError("--pga: not with --match (the target spectrum sets the level)");
  if (matching && a.s0) throw InputError("--s0: not with --match (the target spectrum sets the level)");
  if (!matching && a.damping) throw InputError("--damping: only with --match (the damping of the matched spectrum)");
  if (!matching && !a.s0 && !a.pga) throw InputError("--s0 / --pga: give the intensity, S0 [m^2/s^3] or a target PGA [g]");
  if (matching) o.s0 = 1.0;  // checked below; ignored by the matching

  // Option names in messages: the library names scene keys, map them to options.
  std::string error;
  if (!o.IsValid(&error)) {
    static const std::vector<std::pair<std::string, std::string>> names = {
        {"ground.omega_g", "--omega-g"}, {"ground.zeta_g", "--zeta-g"},   {"ground.omega_f", "--omega-f"},
        {"ground.zeta_f", "--zeta-f"},   {"ground.s0", "--s0"},           {"ground.target_pga", "--pga"},
        {"ground.duration", "--duration"}, {"ground.dt", "--dt"},         {"ground.t1", "--t1"},
        {"ground.t2", "--t2"},           {"ground.decay", "--decay"},     {"ground.eps", "--eps"},
        {"ground.eta", "--eta"},         {"ground.t_n", "--tn"}};
    for (const auto& [key, option] : names)
      for (std::size_t at = error.find(key); at != std::string::npos; at = error.find(key, at + option.size()))
        if (at + key.size() == error.size() ||
            (!std::isalnum(static_cast<unsigned char>(error[at + key.size()])) && error[at + key.size()] != '_'))
          error.replace(at, key.size(), option);
    throw InputError(error);
  }

  MatchOptions m;
  if (matching) {
    try {
      m.target = parse_target_spectrum(a.match);
    } catch (const InputError& e) {
      throw InputError(std::string("--match: ") + e.what());
    }
    parse_band(a.band, &m);
    m.band_points = a.band_points;
    m.tolerance = a.tolerance;
    m.max_iterations = a.max_iterations;
    m.attempts = a.attempts;
    if (a.damping) m.damping = *a.damping;
    if (!m.IsValid(&error)) {
      if (error.rfind("match.period", 0) == 0) error = "--band " + a.band + ": " + error;
      else if (error.rfind("match.band_points", 0) == 0) error.replace(0, 17, "--band-points");
      else if (error.rfind("match.tolerance", 0) == 0) error.replace(0, 15, "--tolerance");
      else if (error.rfind("match.max_iterations", 0) == 0) error.replace(0, 20, "--max-iterations");
      else if (error.rfind("match.attempts", 0) == 0) error.replace(0, 14, "--attempts");
      else if (error.rfind("match.damping", 0) == 0) error.replace(0, 13, "--damping");
      throw InputError(error);
    }
    const double lasts = static_cast<double>(synthesis_samples(o.duration, o.dt) - 1) * o.dt;
    if (!(lasts >= m.period_max))
      throw InputError("--duration " + shortest_text(o.duration) + ": shorter than the band's longest period (--band " + a.band +
                       "): spectrum matching needs a record at least that long");
  }

  // The complete command, every option spelled out.
  std::ostringstream command;
  command << "adjoin synth --spectrum " << (o.spectrum == SpectrumModel::kanai_tajimi ? "kt" : "cp") << " --omega-g "
          << shortest_text(o.omega_g) << " --zeta-g " << shortest_text(o.zeta_g);
  if (o.spectrum == SpectrumModel::clough_penzien) command << " --omega-f " << shortest_text(o.omega_f) << " --zeta-f " << shortest_text(o.zeta_f);
  if (a.s0) command << " --s0 " << shortest_text(*a.s0);
  if (a.pga) command << " --pga " << shortest_text(*a.pga);
  command << " --envelope " << (jht ? "jht" : sh ? "sh" : "none");
  if (a.t1) command << " --t1 " << shortest_text(*a.t1);
  if (a.t2) command << " --t2 " << shortest_text(*a.t2);
  if (a.decay) command << " --decay " << shortest_text(*a.decay);
  if (a.eps) command << " --eps " << shortest_text(*a.eps);
  if (a.eta) command << " --eta " << shortest_text(*a.eta);
  if (a.tn) command << " --tn " << shortest_text(*a.tn);
  command << " --duration " << shortest_text(o.duration) << " --dt " << shortest_text(o.dt) << " --seed " << o.seed;
  if (matching)
    command << " --match " << shell_word(a.match) << " --band " << shortest_text(m.period_min) << ":" << shortest_text(m.period_max)
            << " --band-points " << m.band_points << " --tolerance " << shortest_text(m.tolerance) << " --max-iterations "
            << m.max_iterations << " --attempts " << m.attempts << " --damping " << shortest_text(m.damping);
  command << " --out " << shell_word(a.out);

  MatchReport report;
  const Record record = matching ? synthesize_matched(o, m, &report) : synthesize(o);
  if (matching && !report.converged)
    throw NumericalError("spectrum matching reached max |PSA/target - 1| = " + shortest_text(std::round(report.max_misfit * 1e4) / 1e4) +
                             " at best, above --tolerance " + shortest_text(m.tolerance) + " after " +
                             std::to_string(m.max_iterations) + " iterations and " + std::to_string(m.attempts) +
                             " phase draws: raise --max-iterations or --attempts, narrow --band or change --seed",
                         0.0);
  const IntensityMeasures im = intensity_measures(record);

  std::vector<std::string> header = {
      "adjoin " ADJOIN_VERSION " synthetic ground acceleration",
      "command: " + command.str(),
      record.description,
      std::to_string(record.accel.size()) + " samples, dt " + shortest_text(record.dt) + " s, PGA " + shortest_text(im.pga) + " g at t = " +
          shortest_text(std::round(im.t_pga * 1e9) / 1e9) + " s",
  };
  if (matching) {
    std::ostringstream s;
    s << "match: " << m.target.name << ", damping " << shortest_text(100.0 * m.damping) << " %, " << m.band_points << " log-spaced periods " << shortest_text(m.period_min) << "-"
      << shortest_text(m.period_max) << " s, " << report.iterations << " iterations, max |PSA/target - 1| = " << shortest_text(report.max_misfit)
      << ", mean = " << shortest_text(report.mean_misfit);
    if (report.attempt > 0) s << "; phases of attempt " << report.attempt << " (seed " << report.phase_seed << ")";
    header.push_back(s.str());
  }
  header.push_back("columns: t [s], a [g]");
  write_record_g(record, a.out, header);

  std::cout << "wrote " << a.out << ": " << record.accel.size() << " samples, dt = " << shortest_text(record.dt) << " s\n";
  std::cout << "PGA = " << shortest_text(std::round(im.pga * 1e6) / 1e6) << " g at t = " << shortest_text(std::round(im.t_pga * 1e9) / 1e9) << " s\n";
  if (matching)
    std::cout << "match: " << m.target.name << ", damping " << shortest_text(100.0 * m.damping) << " %, " << shortest_text(m.period_min) << "-" << shortest_text(m.period_max) << " s: "
              << report.iterations << " iterations, max misfit " << shortest_text(std::round(report.max_misfit * 1e5) / 1e3)
              << " %, mean misfit " << shortest_text(std::round(report.mean_misfit * 1e5) / 1e3) << " %"
              << (report.attempt > 0 ? " (phase draw " + std::to_string(report.attempt) + ")" : std::string()) << "\n";
  std::cout.flush();
  return 0;
}

const Registration registration(45, "synth", "Synthetic ground motion: filtered white noise, optionally spectrum-matched",
                                [](CLI::App* synth) -> Runner {
  auto a = std::make_shared<SynthArgs>();
  synth->add_option("--spectrum", a->spectrum, "kt (Kanai-Tajimi) or cp (Clough-Penzien, default)");
  synth->add_option("--omega-g", a->omega_g, "Ground filter frequency [rad/s] (default 15.6)");
  synth->add_option("--zeta-g", a->zeta_g, "Ground filter damping ratio (default 0.6)");
  synth->add_option("--omega-f", a->omega_f, "Clough-Penzien high-pass frequency [rad/s] (default 1.5)");
  synth->add_option("--zeta-f", a->zeta_f, "Clough-Penzien high-pass damping ratio (default 0.6)");
  synth->add_option("--s0", a->s0, "Two-sided bedrock white-noise density S0 [m^2/s^3]");
  synth->add_option("--pga", a->pga, "Target PGA [g] (instead of --s0)");
  synth->add_option("--envelope", a->envelope, "jht (Jennings-Housner-Tsai, default), sh (Saragoni-Hart) or none");
  synth->add_option("--t1", a->t1, "JHT: end of the rise [s] (default 0.1 duration)");
  synth->add_option("--t2", a->t2, "JHT: end of the plateau [s] (default 0.5 duration)");
  synth->add_option("--decay", a->decay, "JHT: decay rate after t2 [1/s] (default: 0.05 at the end)");
  synth->add_option("--eps", a->eps, "SH: time of the peak as a fraction of tn (default 0.2)");
  synth->add_option("--eta", a->eta, "SH: envelope value at tn (default 0.05)");
  synth->add_option("--tn", a->tn, "SH: time tn [s] (default the duration)");
  synth->add_option("--duration", a->duration, "Duration [s] (default 20)");
  synth->add_option("--dt", a->dt, "Time step [s] (default 0.005)");
  synth->add_option("--seed", a->seed_text, "Random seed, an unsigned 64-bit integer (default 1)");
  synth->add_option("--match", a->match, "Match a target spectrum: ec8:T[:AG[:TYPE]] (EC8, ground T = A..E, ag in g "
                                          "(default 0.25), spectrum type 1 (default) or 2) or a two-column file of "
                                          "period [s], PSA [g]");
  synth->add_option("--damping", a->damping, "Damping ratio of the matched spectrum (default 0.05; EC8 targets get "
                                             "the code's correction eta)");
  synth->add_option("--band", a->band, "Matching period band T0:T1 [s] (default 0.1:3)");
  synth->add_option("--band-points", a->band_points, "Log-spaced periods checked in the band (default 100)");
  synth->add_option("--tolerance", a->tolerance, "Matching tolerance on PSA/target - 1 (default 0.1)");
  synth->add_option("--max-iterations", a->max_iterations, "Matching iterations at most (default 100)");
  synth->add_option("--attempts", a->attempts, "Phase draws tried if a match falls short (default 5)");
  synth->add_option("--out", a->out, "Output file: two columns t [s], a [g] after a '#' header")->required();
  return [a, synth]() -> int {
    if (synth->parsed()) return synth_command(*a);
    return 0;
  };
});

}  // namespace
}  // namespace adjoin::cli
