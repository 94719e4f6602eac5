#pragma once
// Extrema of a sampled signal between its samples.
//
// parabola_vertex: the vertex of the parabola through three equally spaced samples
// (t1 - h, y0), (t1, y1), (t1 + h, y2) whose middle one is a local extremum. Its error is
// O(h^3) against O(h^2) for the sample itself, so a peak converges at the solver's own order
// rather than at the sampling's, provided the signal is smooth there.
//
// cubic_extremum: the same from four samples (below), O(h^3) in time.
//
// step_extremum: the extremum inside one step [a.t, b.t] of a signal whose derivative is
// known at the samples (a displacement and its velocity) and changes sign in the step. A
// response's derivative has kinks where the damper switches (the acceleration jumps with the
// damper force), and the extremum of the gap or the stroke sits exactly on such a switch
// (where the relative velocity reaches zero). A parabola spanning the kink is then only first
// order. So: in a step without a switch, the extremum of the cubic Hermite interpolant of
// (y, y') at both ends (O(h^4) in the value, O(h^3) in time); in a step with a located switch
// t_kink, the derivative is extrapolated from each side with its own one-sided second
// derivative (y'' at a from the left piece, at b from the right), which is exact to O(h^2)
// on either side of the kink, and the root is taken on the side where it lies.
#include <cmath>

namespace adjoin {

struct Vertex {
  double t, y;
};

inline Vertex parabola_vertex(double t1, double h, double y0, double y1, double y2) {
  const double curvature = y0 - 2.0 * y1 + y2;
  if (curvature == 0.0) return {t1, y1};
  double delta = 0.5 * (y0 - y2) / curvature;  // in units of h, within [-1/2, 1/2] at an extremum
  if (delta > 0.5) delta = 0.5;
  if (delta < -0.5) delta = -0.5;
  return {t1 + delta * h, y1 - 0.25 * (y0 - y2) * delta};
}

// The extremum of the cubic through four equally spaced samples (t0 + k h, y_k), k = 0..3,
// looked for in [t0 + h, t0 + 3h] (where a local extremum of the samples at k = 2 puts it),
// nearest t0 + 2h. Its time error is O(h^3) against the parabola's O(h^2), whose constant
// depends on where the extremum falls between the samples: that made peak times' errors
// irregular in h, beyond what an estimate from two runs can follow. Falls back to the
// parabola through the last three samples when the cubic has no extremum there.
inline Vertex cubic_extremum(double t0, double h, double y0, double y1, double y2, double y3) {
  // Newton form on s = (t - t0) / h: y = y0 + d1 s + d2 s (s - 1) + d3 s (s - 1)(s - 2).
  const double d1 = y1 - y0;
  const double d2 = 0.5 * (y2 - 2.0 * y1 + y0);
  const double d3 = (y3 - 3.0 * y2 + 3.0 * y1 - y0) / 6.0;
  // dy/ds = A s^2 + B s + C.
  const double A = 3.0 * d3, B = 2.0 * d2 - 6.0 * d3, C = d1 - d2 + 2.0 * d3;
  double best = -1.0;
  auto consider = [&](double r) {
    if (std::isfinite(r) && r >= 1.0 && r <= 3.0 && (best < 0.0 || std::abs(r - 2.0) < std::abs(best - 2.0))) best = r;
  };
  if (std::abs(A) > 1e-14 * (std::abs(B) + std::abs(C))) {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      const double q = -0.5 * (B + (B >= 0.0 ? r : -r));
      if (q != 0.0) consider(C / q);
      consider(q / A);
    }
  } else if (B != 0.0) {
    consider(-C / B);
  }
  if (best < 0.0) return parabola_vertex(t0 + 2.0 * h, h, y1, y2, y3);
  const double y = y0 + best * (d1 + (best - 1.0) * (d2 + (best - 2.0) * d3));
  return {t0 + best * h, y};
}

// A sample of a signal with its first and second time derivatives.
struct Sample {
  double t, y, dy, ddy;
};

inline Vertex step_extremum(const Sample& a, const Sample& b, double t_kink) {
  const double h = b.t - a.t;
  if (std::isfinite(t_kink) && t_kink > a.t && t_kink < b.t) {
    // Left piece: y'(t) = a.dy + a.ddy (t - a.t) on [a.t, t_kink].
    const double end_left = a.dy + a.ddy * (t_kink - a.t);
    if (a.dy == 0.0) return {a.t, a.y};
    if (end_left * a.dy <= 0.0) {
      const double tau = a.ddy != 0.0 ? -a.dy / a.ddy : t_kink - a.t;
      return {a.t + tau, a.y + a.dy * tau + 0.5 * a.ddy * tau * tau};
    }
    // Right piece: y'(t) = b.dy + b.ddy (t - b.t) on [t_kink, b.t].
    const double start_right = b.dy + b.ddy * (t_kink - b.t);
    if (start_right * b.dy <= 0.0 && b.ddy != 0.0) {
      const double tau = -b.dy / b.ddy;  // <= 0
      if (a.t + h + tau >= t_kink) return {b.t + tau, b.y + b.dy * tau + 0.5 * b.ddy * tau * tau};
    }
    // The derivative changes sign at the kink itself (it reaches zero there).
    const double tau = t_kink - a.t;
    return {t_kink, a.y + a.dy * tau + 0.5 * a.ddy * tau * tau};
  }
  // Cubic Hermite on s = (t - a.t) / h in [0, 1]: y'(s) h = A s^2 + B s + C.
  const double A = 6.0 * (a.y - b.y) + 3.0 * h * (a.dy + b.dy);
  const double B = -6.0 * (a.y - b.y) - h * (4.0 * a.dy + 2.0 * b.dy);
  const double C = h * a.dy;
  double s = -1.0;
  auto take = [&](double r) {
    if (std::isfinite(r) && r >= 0.0 && r <= 1.0 && (s < 0.0 || r < s)) s = r;  // the first root
  };
  if (std::abs(A) > 1e-14 * (std::abs(B) + std::abs(C))) {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      const double q = -0.5 * (B + (B >= 0.0 ? r : -r));
      if (q != 0.0) take(C / q);
      take(q / A);
    }
  } else if (B != 0.0) {
    take(-C / B);
  }
  if (s < 0.0) s = std::abs(a.dy) <= std::abs(b.dy) ? 0.0 : 1.0;
  const double s2 = s * s, s3 = s2 * s;
  const double y = (2 * s3 - 3 * s2 + 1) * a.y + (s3 - 2 * s2 + s) * h * a.dy + (-2 * s3 + 3 * s2) * b.y +
                   (s3 - s2) * h * b.dy;
  return {a.t + s * h, y};
}

}  // namespace adjoin
