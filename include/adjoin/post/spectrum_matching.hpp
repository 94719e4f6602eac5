#pragma once
// Spectrum-compatible ground motion: a record's Fourier amplitudes are scaled iteratively until
// its 5 % pseudo-spectral acceleration (PSA, post/spectrum.hpp) matches a target spectrum
// within a tolerance at every period of a band.
//
//     MatchOptions m;
//     m.target = TargetSpectrum::ec8('B', 0.25);            // or load_target_spectrum(file)
//     MatchReport report;
//     Record r = synthesize_matched(synthesis_options, m, &report);
//
// Targets
//  - EC8 horizontal elastic spectra (EN 1998-1:2004 §3.2.2.2), importance factor 1, ag in g,
//    type 1 (Table 3.2, high seismicity) or type 2 (Table 3.3, Ms <= 5.5), damping
//    correction eta = sqrt(10 / (5 + xi[%])) >= 0.55 (eq. 3.6; 1 at 5 %):
//        0 <= T <= TB:  Se = ag S (1 + T/TB (2.5 eta - 1))
//        TB <= T <= TC: Se = 2.5 ag S eta
//        TC <= T <= TD: Se = 2.5 ag S eta TC / T
//        TD <= T:       Se = 2.5 ag S eta TC TD / T^2   (the code stops at 4 s; continued here)
//    type 1:  ground  S     TB [s]  TC [s]  TD [s]      type 2:  S     TB [s]  TC [s]  TD [s]
//             A       1.0   0.15    0.4     2.0                  1.0   0.05    0.25    1.2
//             B       1.2   0.15    0.5     2.0                  1.35  0.05    0.25    1.2
//             C       1.15  0.20    0.6     2.0                  1.5   0.10    0.25    1.2
//             D       1.35  0.20    0.8     2.0                  1.8   0.10    0.30    1.2
//             E       1.4   0.15    0.5     2.0                  1.6   0.05    0.25    1.2
//    The damping is the matching's (MatchOptions::damping): an EC8 target is the code's
//    spectrum at that damping.
//  - A table of (period [s], PSA [g]) rows, periods strictly increasing, PSA > 0 (a first row
//    at T = 0 may hold the PGA), interpolated linearly in period, taken to be at the
//    matching's damping; text with one row per line,
//    blank/tab/','/';' separated, '#' or '%' comment lines (e.g. records/real/targets/
//    ASCE7.txt).
//
// Algorithm (Fourier-amplitude scaling). The seed (n samples) is zero-padded to an FFT length
// M >= 2n (a 2^a 3^b 5^c 7^d number) and transformed once: Y0. Iteration j keeps a cumulative
// real gain G_j(f) > 0 and forms a_j = the first n samples of IFFT(G_j Y0) (phases are kept;
// what spreads into the padding is dropped). The PSA of a_j (damping 5 %, SpectrumOptions
// defaults) is computed at `band_points` log-spaced periods of [period_min, period_max] and at
// the extension periods period_min / 2^(k/4) and period_max 2^(k/4), k = 1..4 (one octave each
// side, where the target has them); the ratios r = target / PSA (clamped to [0.1, 10]) are
// split into an overall level c (their geometric mean over the band) and local ratios r / c;
// these are interpolated linearly in log-frequency, held at the edge value up to the last
// extension point and blended to 1 by a half-cosine in log-frequency over the next octave, and
// G_{j+1} = G_j * c * (local ratio): frequencies far outside the band follow the level only. The misfit at a band period is PSA / target - 1; the iteration stops
// when max |misfit| <= tolerance or after max_iterations corrections, and returns the iterate
// with the smallest max |misfit| (converged = false if that is still above the tolerance).
//
// The seed's envelope is kept (approximately: the gain is smooth, and the padding absorbs the
// spread) rather than re-applied to every iterate: re-applying the envelope after the scaling
// (SIMQKE on a stationary seed) stalled at 11-24 % max misfit on 4 of 5 seeds for EC8 B,
// 0.1-3 s, 25 s, while scaling the enveloped motion itself reached 10 % on 9 of 10.
// What is left is the limit of amplitude-only scaling: at long periods, a 25 s motion has few
// Fourier components per oscillator bandwidth, and PSA can stay jagged by a few per cent
// between neighbouring periods whatever the amplitudes; synthesize_matched then draws new phases.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"
#include "adjoin/ground/synthesis.hpp"

namespace adjoin {

struct Ec8Parameters {
  double S = 0.0, TB = 0.0, TC = 0.0, TD = 0.0;  // -, s, s, s
};
// Table 3.2 (type 1) or 3.3 (type 2) of EN 1998-1 for ground type 'A'..'E' (case-insensitive);
// InputError for another ground type or a spectrum type other than 1 or 2.
Ec8Parameters ec8_parameters(char ground_type, int spectrum_type = 1);
// eta = max(sqrt(10 / (5 + 100 damping)), 0.55); InputError unless 0 <= damping < 1.
double ec8_damping_correction(double damping);
// Se(T) [g] for ag [g] at the given damping ratio.
double ec8_psa(double period, char ground_type, double ag, int spectrum_type = 1, double damping = 0.05);

struct TargetSpectrum {
  enum class Kind { ec8, table };
  Kind kind = Kind::ec8;
  char ground_type = 'B';  // ec8
  double ag = 0.25;        // g, ec8
  int ec8_type = 1;        // ec8: 1 or 2
  std::vector<double> periods, psa;  // table: s, g
  std::string name;                  // "EC8 type 1, ground B, ag = 0.25 g" or the file

  static TargetSpectrum ec8(char ground_type, double ag, int spectrum_type = 1);
  // InputError (naming `name`) unless periods strictly increase, all finite, T >= 0, PSA > 0.
  static TargetSpectrum table(std::vector<double> periods, std::vector<double> psa, std::string name);

  // PSA [g] at a period [s] and damping ratio (EC8: eta(damping); a table is at the damping it
  // is given for, which the caller knows). A table must cover the period (InputError otherwise).
  double psa_at(double period, double damping = 0.05) const;
  // Periods covered [s]: [0, inf) for EC8, [first, last] for a table.
  double min_period() const;
  double max_period() const;
};

// Reads a two-column target table; InputError "FILE:LINE: ..." on any defect.
TargetSpectrum load_target_spectrum(const std::filesystem::path& path);
// "ec8:B" (type 1, ag 0.25 g), "ec8:B:0.3" (ag 0.3 g), "ec8:B:0.3:2" (type 2), or else a path
// to a table file.
TargetSpectrum parse_target_spectrum(const std::string& text);

struct MatchOptions {
  TargetSpectrum target;
  double period_min = 0.1;       // s, band [period_min, period_max]
  double period_max = 3.0;       // s
  std::size_t band_points = 100; // log-spaced check periods in the band (>= 2)
  double damping = 0.05;
  double tolerance = 0.10;       // max |PSA / target - 1| over the band
  int max_iterations = 100;      // frequency-domain corrections (>= 0)
  int attempts = 5;              // synthesize_matched: phase draws tried (>= 1)

  // Checks values; the message names the field (match.period_min, ...) and what is expected.
  // Requires 0 < period_min < period_max, the band inside the target's periods, band_points
  // >= 2, 0 <= damping < 1, tolerance > 0, max_iterations >= 0, attempts >= 1.
  bool IsValid(std::string* error) const;
};

struct MatchReport {
  int iterations = 0;          // corrections applied to reach the returned record
  bool converged = false;      // max_misfit <= tolerance
  double max_misfit = 0.0;     // max |PSA / target - 1| over the band periods
  double mean_misfit = 0.0;    // mean |PSA / target - 1|
  std::vector<double> max_misfit_history;  // per iterate (0 = the seed as given)
  std::vector<double> periods, psa, target;  // the band periods [s] and PSA values [g]
  int attempt = 0;                 // synthesize_matched: which phase draw was kept (0 = seed)
  std::uint64_t phase_seed = 0;    // synthesize_matched: attempt_seed(seed, attempt)
};

// Matches `seed_motion` (accelerations in m/s^2; its level does not matter) to the target.
// InputError on invalid options or an empty / non-finite seed. `report` may be null.
Record match_spectrum(Record seed_motion, const MatchOptions& options, MatchReport* report);

// Synthesizes `synthesis` (with its envelope; s0 and target_pga are ignored, the target sets the
// level) and matches it. If the match does not reach the tolerance, the synthesis is repeated
// with other phases, seed attempt_seed(synthesis.seed, k) for k = 1 .. attempts - 1, and the
// best match is returned (report->attempt, report->phase_seed say which).
Record synthesize_matched(const SynthesisOptions& synthesis, const MatchOptions& options, MatchReport* report);

// attempt 0: the seed itself; attempt k > 0: splitmix64(seed + k * 0x9E3779B97F4A7C15).
std::uint64_t attempt_seed(std::uint64_t seed, int attempt);

}  // namespace adjoin
