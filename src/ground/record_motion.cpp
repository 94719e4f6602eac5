#include "adjoin/ground/record_motion.hpp"

#include <cmath>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"

namespace adjoin {

RecordMotion::RecordMotion(Record record, double time_scale, double accel_scale)
    : record_(std::move(record)), time_scale_(time_scale), accel_scale_(accel_scale) {
  if (record_.accel.empty()) throw InputError(record_.source + ": the record has no samples");
  if (!(record_.dt > 0.0) || !std::isfinite(record_.dt))
    throw InputError(record_.source + ": the record's dt must be positive");
  if (!(time_scale_ > 0.0) || !std::isfinite(time_scale_)) throw InputError("record source: time scale T0 must be positive");
  if (!(accel_scale_ > 0.0) || !std::isfinite(accel_scale_))
    throw InputError("record source: acceleration scale must be positive");
  for (double a : record_.accel) pga_ = std::max(pga_, std::abs(a));
}

double RecordMotion::ag(double t) const {
  const double x = t * time_scale_ / record_.dt;  // position in samples
  if (!(x >= 0.0)) return 0.0;
  const std::size_t last = record_.accel.size() - 1;
  if (x >= static_cast<double>(last)) return x == static_cast<double>(last) ? -record_.accel[last] / accel_scale_ : 0.0;
  const auto i = static_cast<std::size_t>(x);
  const double fraction = x - static_cast<double>(i);
  const double a = record_.accel[i] + fraction * (record_.accel[i + 1] - record_.accel[i]);
  return -a / accel_scale_;
}

double RecordMotion::duration() const { return record_.duration() / time_scale_; }

std::string RecordMotion::describe() const {
  std::ostringstream s;
  s.precision(4);
  s << "record " << record_.source << " (PGA " << pga_ / kStandardGravity << " g, dt " << record_.dt << " s, "
    << record_.accel.size() << " points, " << record_.duration() << " s)";
  return s.str();
}

}  // namespace adjoin
