// ground.source = "filtered-noise": a synthetic motion (ground/synthesis.hpp), optionally
// matched to a target spectrum (post/spectrum_matching.hpp).
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "../ground_cache.hpp"
#include "adjoin/core/number_text.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/ground/record_motion.hpp"
#include "adjoin/ground/synthesis.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/post/spectrum_matching.hpp"
#include "registry.hpp"

namespace adjoin::detail {
namespace {

constexpr std::array<KeySpec, 25> kKeys = {{
    {"ground.spectrum", Kind::string},    {"ground.omega_g", Kind::number},
    {"ground.zeta_g", Kind::number},      {"ground.omega_f", Kind::number},
    {"ground.zeta_f", Kind::number},      {"ground.s0", Kind::number},
    {"ground.target_pga", Kind::number},  {"ground.envelope", Kind::string},
    {"ground.t1", Kind::number},          {"ground.t2", Kind::number},
    {"ground.decay", Kind::number},       {"ground.eps", Kind::number},
    {"ground.eta", Kind::number},         {"ground.t_n", Kind::number},
    {"ground.duration", Kind::number},    {"ground.dt", Kind::number},
    {"ground.seed", Kind::integer},
    {"ground.match_ec8", Kind::string},   {"ground.match_ag", Kind::number},
    {"ground.match_table", Kind::string}, {"ground.match_band", Kind::numbers},
    {"ground.match_tolerance", Kind::number}, {"ground.match_ec8_type", Kind::number},
    {"ground.match_damping", Kind::number},
    {"ground.time_scale", Kind::number},
}};

std::span<const KeySpec> filtered_noise_keys() { return kKeys; }

// source = "filtered-noise": white noise shaped by a Kanai-Tajimi or Clough-Penzien spectrum
// and an envelope (ground/synthesis.hpp), optionally matched to a target spectrum. Reproducible
// from ground.seed.
std::shared_ptr<const GroundMotion> read_filtered_noise(const SceneReader& r, const Scales& scales) {
  SynthesisOptions o;
  if (r.has("ground.spectrum")) {
    const std::string name = r.string("ground.spectrum", "");
    if (!parse_spectrum_model(name, &o.spectrum))
      r.fail("ground.spectrum", "ground.spectrum = " + escaped_excerpt(name) + " must be " + join_names(names<SpectrumModel>(), "\"", ", ", " or "));
  }
  o.omega_g = r.number("ground.omega_g", o.omega_g);
  o.zeta_g = r.number("ground.zeta_g", o.zeta_g);
  o.omega_f = r.number("ground.omega_f", o.omega_f);
  o.zeta_f = r.number("ground.zeta_f", o.zeta_f);
  if (r.has("ground.s0")) o.s0 = r.number("ground.s0");
  if (r.has("ground.target_pga")) o.target_pga = r.number("ground.target_pga");
  if (r.has("ground.envelope")) {
    const std::string name = r.string("ground.envelope", "");
    if (!parse_envelope_kind(name, &o.envelope.kind))
      r.fail("ground.envelope", "ground.envelope = " + escaped_excerpt(name) + " must be " + join_names(names<EnvelopeKind>(), "\"", ", ", " or "));
  }
  // Keys of another spectrum or envelope than the one chosen would be ignored.
  if (o.spectrum != SpectrumModel::clough_penzien)
    for (const char* key : {"ground.omega_f", "ground.zeta_f"})
      if (r.has(key)) r.fail(key, std::string(key) + " belongs to ground.spectrum = \"" + to_string(SpectrumModel::clough_penzien) + "\" (its high-pass filter)");
  const auto envelope_keys = [&](EnvelopeKind kind, std::initializer_list<const char*> keys) {
    if (o.envelope.kind == kind) return;
    for (const char* key : keys)
      if (r.has(key)) r.fail(key, std::string(key) + " belongs to ground.envelope = \"" + to_string(kind) + "\"");
  };
  envelope_keys(EnvelopeKind::jennings_housner_tsai, {"ground.t1", "ground.t2", "ground.decay"});
  envelope_keys(EnvelopeKind::saragoni_hart, {"ground.eps", "ground.eta", "ground.t_n"});
  for (auto [key, field] : {std::pair{"ground.t1", &o.envelope.t1}, {"ground.t2", &o.envelope.t2}, {"ground.decay", &o.envelope.decay},
                            {"ground.eps", &o.envelope.eps}, {"ground.eta", &o.envelope.eta}, {"ground.t_n", &o.envelope.t_n}})
    if (r.has(key)) *field = r.number(key);
  o.duration = r.number("ground.duration", o.duration);
  o.dt = r.number("ground.dt", o.dt);
  const std::int64_t seed = r.integer("ground.seed", 1);
  if (seed < 0) r.fail("ground.seed", "ground.seed = " + std::to_string(seed) + " must be zero or positive");
  o.seed = static_cast<std::uint64_t>(seed);
  const bool match = r.has("ground.match_ec8") || r.has("ground.match_table");
  // A matched motion takes its level from the target spectrum: no intensity needed.
  if (match && !o.s0 && !o.target_pga) o.target_pga = 1.0;
  std::string error;
  if (!o.IsValid(&error)) r.fail(error.substr(0, error.find(' ')), error);
  const double time_scale = record_time_scale(r, scales);

  for (const char* key : {"ground.match_ag", "ground.match_band", "ground.match_tolerance", "ground.match_ec8_type",
                          "ground.match_damping"})
    if (r.has(key) && !match) r.fail(key, std::string(key) + " needs ground.match_ec8 or ground.match_table");
  if (!match)
    return cached_ground(ground_key(r, time_scale, ""), [&]() -> std::shared_ptr<const GroundMotion> {
      return std::make_shared<RecordMotion>(synthesize(o), time_scale, kStandardGravity);
    });

  MatchOptions m;
  if (r.has("ground.match_ec8") && r.has("ground.match_table"))
    r.fail("ground.match_table", "give ground.match_ec8 or ground.match_table, not both");
  if (r.has("ground.match_ec8")) {
    const std::string type = r.string("ground.match_ec8", "");
    if (type.size() != 1 || std::string("ABCDE").find(type[0]) == std::string::npos)
      r.fail("ground.match_ec8", "ground.match_ec8 = " + escaped_excerpt(type) + " must be an EC8 ground type, \"A\" to \"E\"");
    const double ag = r.number("ground.match_ag", 0.25);
    if (!(ag > 0.0 && ag <= 10.0))
      r.fail("ground.match_ag", "ground.match_ag must be the design ground acceleration in g, > 0 and at most 10");
    const double spectrum_type = r.number("ground.match_ec8_type", 1.0);
    if (spectrum_type != 1.0 && spectrum_type != 2.0)
      r.fail("ground.match_ec8_type", "ground.match_ec8_type must be 1 (EN 1998-1 Table 3.2) or 2 (Table 3.3)");
    m.target = TargetSpectrum::ec8(type[0], ag, static_cast<int>(spectrum_type));
  } else {
    for (const char* key : {"ground.match_ag", "ground.match_ec8_type"})
      if (r.has(key)) r.fail(key, std::string(key) + " belongs to ground.match_ec8, not to a target table");
    std::filesystem::path file = r.string("ground.match_table", "");
    if (file.is_relative() && !r.overridden("ground.match_table")) file = std::filesystem::path(r.name()).parent_path() / file;
    m.target = load_target_spectrum(file);
  }
  if (r.has("ground.match_band")) {
    const auto band = r.numbers("ground.match_band");
    if (band.size() != 2) r.fail("ground.match_band", "ground.match_band must be [shortest, longest] period in s");
    m.period_min = band[0];
    m.period_max = band[1];
  }
  m.tolerance = r.number("ground.match_tolerance", m.tolerance);
  m.damping = r.number("ground.match_damping", m.damping);
  if (!m.IsValid(&error)) {
    const std::string key = error.rfind("match.damping", 0) == 0     ? "ground.match_damping"
                            : error.rfind("match.tolerance", 0) == 0 ? "ground.match_tolerance"
                                                                     : "ground.match_band";
    r.fail(key, "ground matching: " + error);
  }
  const double samples_duration = static_cast<double>(synthesis_samples(o.duration, o.dt) - 1) * o.dt;
  if (!(samples_duration >= m.period_max))
    r.fail("ground.duration", "ground.duration = " + number_text(o.duration, 12) + " s is shorter than the matching band's longest period (" +
                                  number_text(m.period_max, 12) + " s): spectrum matching needs a record at least that long");
  const std::string table_stamp = r.has("ground.match_ec8") ? std::string() : file_stamp(m.target.name);
  return cached_ground(ground_key(r, time_scale, table_stamp), [&]() -> std::shared_ptr<const GroundMotion> {
    MatchReport report;
    Record matched = synthesize_matched(o, m, &report);
    return std::make_shared<RecordMotion>(std::move(matched), time_scale, kStandardGravity);
  });
}

}  // namespace

GroundSource filtered_noise_source() { return {"filtered-noise", filtered_noise_keys, read_filtered_noise}; }

}  // namespace adjoin::detail
