#pragma once
// Recorded accelerograms: an acceleration history sampled at a uniform step.
//
// Readers (record_file.hpp) turn files into a Record; processing (processing.hpp) transforms
// one Record into another; RecordMotion (record_motion.hpp) lets the solver see a Record as a
// ground-motion source. Accelerations are held in m/s^2 whatever unit the file used.
#include <string>
#include <vector>

#include "adjoin/core/enum_names.hpp"  // AccelUnit, its names (to_string: "g", "m/s2", ...)

namespace adjoin {

// Factor that converts a value in `unit` to m/s^2.
double to_m_s2(AccelUnit unit);
// "g", "m/s2", "cm/s2" (also "gal"), "mm/s2"; false on an unknown name.
bool parse_accel_unit(const std::string& name, AccelUnit* unit);

struct Record {
  std::string source;       // file it came from (or "synthetic ...")
  std::string description;  // header text, event/station when known
  double dt = 0.0;          // s, > 0
  std::vector<double> accel;  // m/s^2, accel[i] at t = i dt

  double duration() const { return accel.empty() ? 0.0 : dt * static_cast<double>(accel.size() - 1); }
};

}  // namespace adjoin
