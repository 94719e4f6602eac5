// ground.source = "record": an accelerogram file (any format of ground/record_file.hpp),
// processed (ground/processing.hpp) and scaled to the solver's units.
#include <array>
#include <filesystem>
#include <map>

#include "../ground_cache.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/ground/processing.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/ground/record_motion.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/solver/simulate.hpp"
#include "registry.hpp"

namespace adjoin::detail {
namespace {

constexpr std::array<KeySpec, 19> kKeys = {{
    {"ground.file", Kind::string},        {"ground.format", Kind::string},
    {"ground.units", Kind::string},       {"ground.dt", Kind::number},
    {"ground.time_column", Kind::string}, {"ground.accel_column", Kind::string},
    {"ground.channel", Kind::integer},
    {"ground.time_scale", Kind::number},
    {"ground.window_start", Kind::number}, {"ground.window_end", Kind::number},
    {"ground.baseline", Kind::integer},
    {"ground.pad_before", Kind::number},  {"ground.pad_after", Kind::number},
    {"ground.filter", Kind::string},      {"ground.f_low", Kind::number},
    {"ground.f_high", Kind::number},      {"ground.filter_order", Kind::integer},
    {"ground.resample_dt", Kind::number}, {"ground.scale_pga", Kind::number},
}};

std::span<const KeySpec> record_source_keys() { return kKeys; }

// source = "record": read, process, and scale to the solver's units. A dimensionless scene
// says what one unit of its time is in seconds (ground.time_scale, default 1 s); its
// accelerations are in g. An SI scene uses T0 = sqrt(m1/k1).
std::shared_ptr<const GroundMotion> read_record_source(const SceneReader& r, const Scales& scales) {
  if (!r.has("ground.file")) r.fail("ground", "missing key ground.file (the accelerogram to read)");
  std::filesystem::path file = r.string("ground.file", "");
  // Paths in a scene file are relative to that file's folder; a --set path to the working folder.
  if (file.is_relative() && !r.overridden("ground.file"))
    file = std::filesystem::path(r.name()).parent_path() / file;

  RecordFormat format;
  const std::string kind = r.string("ground.format", "auto");
  if (!parse_record_kind(kind, &format.kind))
    r.fail("ground.format", "ground.format = " + escaped_excerpt(kind) + " must be one of " + record_kind_names());
  if (r.has("ground.units")) {
    AccelUnit unit;
    const std::string units = r.string("ground.units", "");
    if (!parse_accel_unit(units, &unit))
      r.fail("ground.units", "ground.units = " + escaped_excerpt(units) + " must be \"g\", \"m/s2\", \"cm/s2\" (or \"gal\") or \"mm/s2\"");
    format.units = unit;
  }
  if (r.has("ground.dt")) format.dt = r.number("ground.dt");
  format.time_column = r.string("ground.time_column", "");
  format.accel_column = r.string("ground.accel_column", "");
  if (r.has("ground.channel")) {
    const auto channel = r.integer("ground.channel", 0);
    if (channel < 1 || channel > 100000) r.fail("ground.channel", "ground.channel = " + std::to_string(channel) + " must be a channel number 1, 2, ... (multi-channel COSMOS or DMG files)");
    format.channel = static_cast<int>(channel);
  }

  Processing processing;
  if (r.has("ground.window_start")) processing.window_t0 = r.number("ground.window_start");
  if (r.has("ground.window_end")) processing.window_t1 = r.number("ground.window_end");
  if (r.has("ground.baseline")) {
    const auto order = r.integer("ground.baseline", 0);
    if (order < 0 || order > 10) r.fail("ground.baseline", "ground.baseline = " + std::to_string(order) + " must be a polynomial order from 0 (mean) to 10");
    processing.baseline_order = static_cast<int>(order);
  }
  processing.pad_before = r.number("ground.pad_before", 0.0);
  processing.pad_after = r.number("ground.pad_after", 0.0);
  for (const char* key : {"ground.f_low", "ground.f_high", "ground.filter_order"})
    if (r.has(key) && !r.has("ground.filter"))
      r.fail(key, std::string(key) + " belongs to ground.filter (" + join_names(names<FilterType>(), "\"", ", ", " or ") +
                      "); without it no filter runs");
  if (r.has("ground.filter")) {
    ButterworthFilter filter;
    const std::string type = r.string("ground.filter", "");
    if (!parse_enum(type, &filter.type))
      r.fail("ground.filter", "ground.filter = " + escaped_excerpt(type) + " must be " + join_names(names<FilterType>(), "\"", ", ", " or "));
    // A low-pass filter has no lower corner, a high-pass one no upper corner.
    if (filter.type == FilterType::lowpass && r.has("ground.f_low")) r.fail("ground.f_low", "ground.f_low does not apply to a low-pass filter (its corner is ground.f_high)");
    if (filter.type == FilterType::highpass && r.has("ground.f_high")) r.fail("ground.f_high", "ground.f_high does not apply to a high-pass filter (its corner is ground.f_low)");
    filter.f_low = r.number("ground.f_low", 0.0);
    filter.f_high = r.number("ground.f_high", 0.0);
    const auto order = r.integer("ground.filter_order", 4);
    if (order < 1 || order > 20) r.fail("ground.filter_order", "ground.filter_order = " + std::to_string(order) + ": expected an order from 1 to 20");
    filter.order = static_cast<int>(order);
    processing.filter = filter;
  }
  if (r.has("ground.resample_dt")) processing.dt = r.number("ground.resample_dt");
  if (r.has("ground.scale_pga")) processing.target_pga = r.number("ground.scale_pga") * kStandardGravity;

  const double time_scale = record_time_scale(r, scales);
  return cached_ground(ground_key(r, time_scale, file_stamp(file)), [&]() -> std::shared_ptr<const GroundMotion> {
    Record record = adjoin::read_record(file, format);  // InputError names the file and line
    // One validation with `record process` (ground/processing.hpp), named by the scene's keys.
    if (const auto problem = check_processing(processing, record, 0.8 * physical_memory_bytes())) {
      static const std::map<ProcessingField, const char*> keys = {
          {ProcessingField::window_start, "ground.window_start"}, {ProcessingField::window_end, "ground.window_end"},
          {ProcessingField::baseline, "ground.baseline"},         {ProcessingField::pad_before, "ground.pad_before"},
          {ProcessingField::pad_after, "ground.pad_after"},       {ProcessingField::filter_order, "ground.filter_order"},
          {ProcessingField::f_low, "ground.f_low"},               {ProcessingField::f_high, "ground.f_high"},
          {ProcessingField::resample_dt, "ground.resample_dt"},   {ProcessingField::scale_pga, "ground.scale_pga"}};
      const std::string key = keys.at(problem->field);
      r.fail(r.has(key) ? key : "ground", key + ": " + problem->message + " (record " + file.string() + ")");
    }
    try {
      record = process(record, processing);
    } catch (const InputError& e) {
      r.fail("ground", e.what());
    }
    return std::make_shared<RecordMotion>(std::move(record), time_scale, kStandardGravity);
  });
}

}  // namespace

GroundSource record_source() { return {"record", record_source_keys, read_record_source}; }

}  // namespace adjoin::detail
