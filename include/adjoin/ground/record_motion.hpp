#pragma once
// A recorded accelerogram seen by the solver as a ground-motion source.
//
// The solver works in dimensionless time t (units of T0 seconds) and acceleration (units of
// `accel_scale` m/s^2: g for SI scenes, so that a_g is "in g"). The record holds the ground
// acceleration u'' in m/s^2 at t_s = i dt; the forcing is a_g = -u'':
//
//     ag(t) = -(piecewise-linear interpolation of accel at t_s = t T0) / accel_scale,
//
// zero before t = 0 and after the record ends (duration() = record duration / T0).
#include <string>

#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/ground/record.hpp"

namespace adjoin {

class RecordMotion final : public GroundMotion {
 public:
  // time_scale T0 [s] > 0; accel_scale [m/s^2 per dimensionless unit] > 0. InputError if the
  // record is empty or its dt is not positive.
  RecordMotion(Record record, double time_scale, double accel_scale);

  double ag(double t) const override;
  std::string describe() const override;
  double duration() const override;
  double sample_interval() const override { return record_.dt / time_scale_; }

  const Record& record() const { return record_; }
  double time_scale() const { return time_scale_; }
  double accel_scale() const { return accel_scale_; }

 private:
  Record record_;
  double time_scale_, accel_scale_;
  double pga_ = 0.0;  // m/s^2
};

}  // namespace adjoin
