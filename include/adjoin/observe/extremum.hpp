#pragma once
// The extremum of a smooth sampled signal between its samples: the vertex of the parabola
// through three equally spaced samples (t1 - h, y0), (t1, y1), (t1 + h, y2) whose middle one
// is a local extremum. Its error is O(h^3) against O(h^2) for the sample itself, so a peak or
// a minimum gap converges at the solver's own order rather than at the sampling's.
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

}  // namespace adjoin
