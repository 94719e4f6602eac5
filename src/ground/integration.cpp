// Trapezoid integration of an accelerogram (see integration.hpp).
#include "adjoin/ground/integration.hpp"

namespace adjoin {

MotionHistories integrate_record(const Record& record) {
  MotionHistories h;
  h.dt = record.dt;
  h.accel = record.accel;
  const std::size_t n = record.accel.size();
  h.velocity.assign(n, 0.0);
  h.displacement.assign(n, 0.0);
  const double half = 0.5 * record.dt;
  for (std::size_t i = 1; i < n; ++i) {
    h.velocity[i] = h.velocity[i - 1] + half * (record.accel[i - 1] + record.accel[i]);
    h.displacement[i] = h.displacement[i - 1] + half * (h.velocity[i - 1] + h.velocity[i]);
  }
  return h;
}

}  // namespace adjoin
