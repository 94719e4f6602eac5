#pragma once
// Locating a stick -> slip onset between grid points (internal to the solver; used by the
// two-block implicit scheme and the structure step alike).
#include <cmath>
#include <limits>

namespace adjoin::detail {

// Where the stick force q(t) reaches `target` (+-mu) near t_n: the root of the parabola
// through (t_n - h, q_prev), (t_n, q_now), (t_n + h, q_next) (or of the line through the last
// two when q_prev is not a stick force), as a time offset from t_n in units of h, within
// [lo, 1]. Second-order interpolation of grid values gives the instant at order 2 or better.
inline double locate_onset(double target, bool have_prev, double q_prev, double q_now, double q_next, double lo) {
  const double c = q_now - target;
  const double b = have_prev ? 0.5 * (q_next - q_prev) : q_next - q_now;
  const double a = have_prev ? 0.5 * (q_next - 2.0 * q_now + q_prev) : 0.0;
  auto in_range = [lo](double x) { return std::isfinite(x) && x >= lo && x <= 1.0; };
  double best = std::numeric_limits<double>::quiet_NaN();
  auto consider = [&](double x) {
    if (in_range(x) && (!std::isfinite(best) || std::abs(x - 0.5) < std::abs(best - 0.5))) best = x;
  };
  if (std::abs(a) > 1e-14 * (std::abs(b) + std::abs(c))) {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      const double q = -0.5 * (b + (b >= 0.0 ? r : -r));  // the stable quadratic formula
      if (q != 0.0) consider(c / q);
      consider(q / a);
    }
  }
  if (!std::isfinite(best) && b != 0.0) consider(-c / b);
  return std::isfinite(best) ? best : 1.0;
}

}  // namespace adjoin::detail
