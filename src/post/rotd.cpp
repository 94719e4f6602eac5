// RotDnn and GMRotI50 spectra of a pair of horizontal components (the method is described in
// adjoin/post/rotd.hpp).
#include "adjoin/post/rotd.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <thread>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"
#include "../detail/simd_clones.hpp"
#include "spectrum_oscillator.hpp"

// The angle loops use GCC vector extensions (two angles a register); the vectors only pass
// between inlined helpers of this file.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace adjoin {

namespace {

using spectrum_detail::kMaxRefineTheta;
using spectrum_detail::kMaxTerms;
using spectrum_detail::taylor_terms;
using spectrum_detail::turning_value;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Two angles a register (SSE2, which every x86-64 has; the 256-bit form without AVX went
// through the stack).
using Vec = double __attribute__((vector_size(16)));
using Mask = long long __attribute__((vector_size(16)));
constexpr std::size_t kLanes = 2;

inline Vec vmax(Vec a, Vec b) { return a > b ? a : b; }
inline Vec vabs(Vec x) { return vmax(x, -x); }
inline Vec splat(double x) { return Vec{x, x}; }

// The angles k * step, k = 0 .. count - 1, with cos and sin padded to whole vectors (the
// padding repeats angle 0, and its peaks are never read).
struct Angles {
  std::size_t count = 0;
  std::size_t blocks = 0;
  double step = 1.0;
  std::vector<Vec> cos, sin;

  explicit Angles(double step_degrees) : step(step_degrees) {
    count = static_cast<std::size_t>(std::llround(180.0 / step_degrees));
    blocks = (count + kLanes - 1) / kLanes;
    cos.assign(blocks, splat(1.0));
    sin.assign(blocks, splat(0.0));
    for (std::size_t k = 0; k < count; ++k) {
      // Exact at the multiples of 90 degrees.
      const double degrees = static_cast<double>(k) * step_degrees;
      double c = std::cos(degrees * std::numbers::pi / 180.0), s = std::sin(degrees * std::numbers::pi / 180.0);
      if (std::abs(degrees - 90.0) < 1e-9) c = 0.0, s = 1.0;
      if (degrees == 0.0) c = 1.0, s = 0.0;
      cos[k / kLanes][k % kLanes] = c;
      sin[k / kLanes][k % kLanes] = s;
    }
  }
  double cos_of(std::size_t k) const { return cos[k / kLanes][k % kLanes]; }
  double sin_of(std::size_t k) const { return sin[k / kLanes][k % kLanes]; }
};

double smallest(const std::vector<Vec>& peaks, std::size_t count) {
  double m = peaks[0][0];
  for (std::size_t k = 1; k < count; ++k) m = std::min(m, peaks[k / kLanes][k % kLanes]);
  return m;
}

// Sampled peaks of |x1 cos + x2 sin| over all points, rotating only the points that can hold
// one. The points farthest out in four directions (0, 45, 90, 135 degrees) give, rotated to
// every angle, a lower bound L of the smallest peak over the angles (RotD00); a point with
// |(x1, x2)| < L is below every angle's peak, so only the points with |(x1, x2)| >= L (a few
// per cent of a record) are rotated.
void sampled_peaks(const double* x1, const double* x2, const double* r2, std::size_t n, const Angles& angles,
                   std::vector<Vec>& peaks) {
  std::array<double, 4> best{};
  std::array<std::size_t, 4> at{};
  for (std::size_t k = 0; k < n; ++k) {
    const double d[4] = {std::abs(x1[k]), std::abs(x1[k] + x2[k]), std::abs(x2[k]), std::abs(x1[k] - x2[k])};
    for (std::size_t j = 0; j < 4; ++j)
      if (d[j] > best[j]) best[j] = d[j], at[j] = k;
  }
  auto rotate = [&](std::size_t k) {
    const Vec a = splat(x1[k]), b = splat(x2[k]);
    for (std::size_t j = 0; j < angles.blocks; ++j)
      peaks[j] = vmax(peaks[j], vabs(a * angles.cos[j] + b * angles.sin[j]));
  };
  for (std::size_t k : at) rotate(k);
  const double floor = smallest(peaks, angles.count), floor2 = floor * floor;
  for (std::size_t k = 0; k < n; ++k)
    if (r2[k] >= floor2) rotate(k);
}

// The excitation p = -a at sub-step point k (n sub-steps a record interval), as the stepping
// loop computes it.
inline double excitation_at(std::span<const double> a, std::size_t k, std::size_t n, double inv_n) {
  const std::size_t i = k / n, j = k % n;
  if (j == 0) return -a[i];
  const double p0 = -a[i], p1 = -a[i + 1];
  return p0 + (p1 - p0) * inv_n * static_cast<double>(j);
}

// Largest |H| on [0, h] of the cubic Hermite interpolant of (y0, y0') and (y1, y1').
inline double hermite_max(double y0, double d0, double y1, double d1, double h) {
  // H(s) = y0 + d0 s + c2 s^2 + c3 s^3.
  const double delta = (y1 - y0) / h;
  const double c2 = (3.0 * delta - 2.0 * d0 - d1) / h;
  const double c3 = (d0 + d1 - 2.0 * delta) / (h * h);
  double best = std::max(std::abs(y0), std::abs(y1));
  auto consider = [&](double s) {
    if (s > 0.0 && s < h) best = std::max(best, std::abs(y0 + s * (d0 + s * (c2 + s * c3))));
  };
  // H'(s) = d0 + 2 c2 s + 3 c3 s^2.
  const double qa = 3.0 * c3, qb = 2.0 * c2, qc = d0;
  if (std::abs(qa) * h < 1e-12 * (std::abs(qb) + std::abs(qc) / h)) {
    if (qb != 0.0) consider(-qc / qb);
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double root = std::sqrt(disc);
      const double q = -0.5 * (qb + (qb >= 0.0 ? root : -root));
      if (q != 0.0) consider(q / qa), consider(qc / q);
    }
  }
  return best;
}

// ---- Pairs of oscillators, four periods at a time --------------------------------------------
//
// Periods sharing a sub-step count n see the same excitation values, so the pairs of
// oscillators of four of them are stepped together, one period a lane of a four-double vector
// (AVX2 in the x86-64-v3 clone, two SSE2 registers otherwise), as the single spectrum does. The
// histories are kept interleaved by lane ([point * 4 + lane]), and the two passes over them
// that follow (sampled peaks beyond the floor, turning points between sub-step points) test all
// four lanes at once; the rare points that pass go to the scalar code of their lane. Each lane
// computes what the scalar recursion x1 = a_uu x + a_uv v + b_u0 p + b_u1 p' computes, in that
// order (this file is compiled without contracted multiply-adds), so angle 0 reproduces the
// single component's spectrum and results do not depend on the grouping.
constexpr std::size_t kGroup = 4;
using Vec4 = double __attribute__((vector_size(32)));
using Mask4 = long long __attribute__((vector_size(32)));

[[gnu::always_inline]] inline Vec4 load4(const double* p) {
  Vec4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store4(double* p, Vec4 v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline Vec4 abs4(Vec4 x) {
  return reinterpret_cast<Vec4>(reinterpret_cast<Mask4>(x) & 0x7fffffffffffffffLL);
}
[[gnu::always_inline]] inline Vec4 max4(Vec4 a, Vec4 b) { return a > b ? a : b; }
[[gnu::always_inline]] inline bool any4(Mask4 m) { return ((m[0] | m[1]) | (m[2] | m[3])) != 0; }

// Up to four (period, damping) tasks sharing a sub-step count n: their step coefficients by
// lane (unused lanes repeat lane 0 and are discarded).
struct Group {
  std::size_t n = 1;
  std::size_t lanes = 0;
  std::size_t task[kGroup] = {};
  double omega[kGroup] = {}, zeta[kGroup] = {};
  double a_uu[kGroup] = {}, a_uv[kGroup] = {}, b_u0[kGroup] = {}, b_u1[kGroup] = {};
  double a_vu[kGroup] = {}, a_vv[kGroup] = {}, b_v0[kGroup] = {}, b_v1[kGroup] = {};
};

// Raises a lane's peaks at every angle with one point (x, y).
void rotate_into(std::vector<Vec>& peaks, const Angles& angles, double x, double y) {
  const Vec a = splat(x), b = splat(y);
  for (std::size_t j = 0; j < angles.blocks; ++j) peaks[j] = vmax(peaks[j], vabs(a * angles.cos[j] + b * angles.sin[j]));
}

// The angles cut into sectors of neighbouring blocks, so that a point is rotated only into the
// sectors where it can raise a peak: within a sector of half-width delta around the angle c,
// |u . e(theta)| <= |u . e(c)| + |u| sin(delta), and a sector is skipped when that bound is
// below the sector's smallest peak. Points beyond the floor lie mostly along one direction,
// so they reach one or two of the eight sectors instead of every angle.
struct Sectors {
  static constexpr std::size_t kCount = 8;
  std::size_t first[kCount + 1] = {};  // blocks [first[s], first[s + 1])
  double c[kCount] = {}, s[kCount] = {}, spread[kCount] = {};

  explicit Sectors(const Angles& angles) {
    for (std::size_t k = 0; k <= kCount; ++k) first[k] = angles.blocks * k / kCount;
    for (std::size_t k = 0; k < kCount; ++k) {
      // The angles held by the sector (padding repeats angle 0, which the last sector's
      // bound then covers too: its spread reaches 180 degrees round to 0).
      const double lo = static_cast<double>(first[k] * kLanes) * angles.step;
      double hi = static_cast<double>(first[k + 1] * kLanes - 1) * angles.step;
      if (first[k + 1] * kLanes > angles.count) hi = 180.0;
      const double centre = 0.5 * (lo + hi) * std::numbers::pi / 180.0;
      const double half = 0.5 * (hi - lo) * std::numbers::pi / 180.0;
      c[k] = std::cos(centre), s[k] = std::sin(centre);
      spread[k] = std::min(1.0, std::sin(half) * (1.0 + 1e-12) + 1e-15);
    }
  }
};

// Smallest peak over the blocks [from, to) (padding lanes included: they hold angle 0's peak).
inline double smallest_in(const std::vector<Vec>& peaks, std::size_t from, std::size_t to) {
  Vec m = peaks[from];
  for (std::size_t j = from + 1; j < to; ++j) m = m < peaks[j] ? m : peaks[j];
  return std::min(m[0], m[1]);
}

// Raises a lane's peaks with one point (x, y), sector by sector; floors[k] is the smallest peak
// of sector k, kept up to date.
inline void rotate_by_sector(std::vector<Vec>& peaks, const Angles& angles, const Sectors& sectors, double* floors,
                             double x, double y) {
  const double r = std::sqrt(x * x + y * y);
  for (std::size_t k = 0; k < Sectors::kCount; ++k) {
    if (std::abs(x * sectors.c[k] + y * sectors.s[k]) + r * sectors.spread[k] < floors[k]) continue;
    const Vec a = splat(x), b = splat(y);
    for (std::size_t j = sectors.first[k]; j < sectors.first[k + 1]; ++j)
      peaks[j] = vmax(peaks[j], vabs(a * angles.cos[j] + b * angles.sin[j]));
    floors[k] = smallest_in(peaks, sectors.first[k], sectors.first[k + 1]);
  }
}

// One lane's search for peaks between sub-step points.
struct LaneRefiner {
  std::span<const double> a1, a2;
  const Angles* angles = nullptr;
  std::vector<Vec>* peaks = nullptr;
  std::size_t n = 1;
  double inv_n = 1.0, h = 0.0, c = 0.0, w2 = 0.0, margin2 = 0.0, margin4 = 0.0;
  int terms = 0;
  double floor = 0.0;  // the smallest peak over the angles

  // A turning point of the rotated response inside sub-step s at angle index j: its exact value
  // where it can beat the angle's peak.
  bool consider(std::size_t s, std::size_t j, double r0, double r1, double w0, double w1) {
    std::vector<Vec>& pk = *peaks;
    // (A copy, written back below: clang binds no reference to a vector-extension element.)
    const double peak = pk[j / kLanes][j % kLanes];
    if (!(w0 * w1 < 0.0) || std::max(std::abs(r0), std::abs(r1)) + margin2 < peak) return false;
    if (hermite_max(r0, w0, r1, w1, h) + margin4 < peak) return false;
    // The exact turning point of the rotated response (as Oscillator::refine).
    const double cl = angles->cos_of(j), sl = angles->sin_of(j);
    const double e0 = excitation_at(a1, s, n, inv_n) * cl + excitation_at(a2, s, n, inv_n) * sl;
    const double e1 = excitation_at(a1, s + 1, n, inv_n) * cl + excitation_at(a2, s + 1, n, inv_n) * sl;
    std::array<double, kMaxTerms + 4> d{};
    d[0] = r0;
    d[1] = w0;
    d[2] = e0 - c * d[1] - w2 * d[0];
    d[3] = (e1 - e0) / h - c * d[2] - w2 * d[1];
    for (int q = 4; q < terms + 3; ++q)
      d[static_cast<std::size_t>(q)] = -c * d[static_cast<std::size_t>(q - 1)] - w2 * d[static_cast<std::size_t>(q - 2)];
    const double value = turning_value(d.data(), terms, h, w0, w1);
    if (!(value > peak)) return false;
    pk[j / kLanes][j % kLanes] = value;
    return true;
  }

  // Sub-step s, from (x0, y0) with velocity (vx0, vy0) to (x1, y1) with (vx1, vy1); says
  // whether an angle's peak rose.
  bool substep(std::size_t s, double x0, double y0, double x1, double y1, double vx0, double vy0, double vx1,
               double vy1) {
    constexpr double kDegree = std::numbers::pi / 180.0;
    const Angles& an = *angles;
    const auto count = static_cast<std::ptrdiff_t>(an.count);
    bool changed = false;
    // The rotated velocity v . e(theta) changes sign inside the sub-step exactly for the angles
    // between the normals to the velocity at its ends: an arc as wide as the velocity turns.
    const double dot = vx0 * vx1 + vy0 * vy1, cross = vx0 * vy1 - vy0 * vx1;
    if (dot > 0.0 && std::abs(cross) < 0.25 * dot) {  // turns by less than 14 degrees: the arc only
      const double normal = std::atan2(vy0, vx0) / kDegree + 90.0;
      const double turn = std::atan2(cross, dot) / kDegree;
      const auto first = static_cast<std::ptrdiff_t>(std::floor((normal + std::min(turn, 0.0)) / an.step)) - 1;
      const auto last = static_cast<std::ptrdiff_t>(std::ceil((normal + std::max(turn, 0.0)) / an.step)) + 1;
      for (std::ptrdiff_t index = first; index <= last; ++index) {
        const auto j = static_cast<std::size_t>(((index % count) + count) % count);
        const double cs = an.cos_of(j), sn = an.sin_of(j);
        changed |= consider(s, j, x0 * cs + y0 * sn, x1 * cs + y1 * sn, vx0 * cs + vy0 * sn, vx1 * cs + vy1 * sn);
      }
    } else {
      std::vector<Vec>& pk = *peaks;
      const Vec sx0 = splat(x0), sy0 = splat(y0), sx1 = splat(x1), sy1 = splat(y1);
      const Vec svx0 = splat(vx0), svy0 = splat(vy0), svx1 = splat(vx1), svy1 = splat(vy1);
      for (std::size_t j = 0; j < an.blocks; ++j) {
        const Vec cs = an.cos[j], sn = an.sin[j];
        const Vec r0 = sx0 * cs + sy0 * sn, r1 = sx1 * cs + sy1 * sn;
        const Vec w0 = svx0 * cs + svy0 * sn, w1 = svx1 * cs + svy1 * sn;
        const Mask near = (w0 * w1 < 0.0) & (vmax(vabs(r0), vabs(r1)) + margin2 >= pk[j]);
        if ((near[0] | near[1]) == 0) continue;
        for (std::size_t l = 0; l < kLanes; ++l)
          if (near[l] && j * kLanes + l < an.count) changed |= consider(s, j * kLanes + l, r0[l], r1[l], w0[l], w1[l]);
      }
    }
    if (changed) floor = smallest(*peaks, an.count);
    return changed;
  }

  // Squared reach |(x, y)| below which a sub-step's ends cannot lead to a new peak: the floor
  // less the quadratic margin (negative: every sub-step is looked at).
  double reach2() const {
    const double r = floor - margin2;
    return r > 0.0 ? r * r * (1.0 - 1e-12) : -1.0;
  }
};

// What a group's first sweep leaves, per lane: the points farthest out in four directions (0,
// 45, 90, 135 degrees) and the largest |v|^2 and |(x, y)|^2.
struct GroupBounds {
  double far_x[4][kGroup] = {}, far_y[4][kGroup] = {};
  double v2max[kGroup] = {}, r2max[kGroup] = {};
};

// What the second sweep needs, per lane: the peaks to raise, the floor beyond which a point is
// rotated in, the sectors' smallest peaks, and the between-points search (null: none).
struct GroupSearch {
  std::vector<Vec>* peaks = nullptr;  // [kGroup]
  const Angles* angles = nullptr;
  const Sectors* sectors = nullptr;
  double floor2[kGroup] = {};
  double sector_floor[kGroup][Sectors::kCount] = {};
  LaneRefiner* lanes[kGroup] = {};
};

// One sub-step of the four lanes, from (x0, y0, vx0, vy0) to (x1, y1, vx1, vy1), with the lanes
// whose end point is beyond the floor and whose ends reach the search threshold.
struct SubStep {
  double x0[kGroup], y0[kGroup], vx0[kGroup], vy0[kGroup], x1[kGroup], y1[kGroup], vx1[kGroup], vy1[kGroup];
  bool beyond[kGroup], reach[kGroup];
};

// The rare work of the second sweep at sub-step s; says whether a threshold rose.
[[gnu::noinline]] bool search_substep(GroupSearch& search, std::size_t s, const SubStep& at) {
  bool raised = false;
  for (std::size_t l = 0; l < kGroup; ++l) {
    LaneRefiner* lane = search.lanes[l];
    if (at.beyond[l]) {
      double* floors = search.sector_floor[l];
      rotate_by_sector(search.peaks[l], *search.angles, *search.sectors, floors, at.x1[l], at.y1[l]);
      if (lane) lane->floor = *std::min_element(floors, floors + Sectors::kCount), raised = true;
    }
    if (at.reach[l])
      raised |= lane->substep(s, at.x0[l], at.y0[l], at.x1[l], at.y1[l], at.vx0[l], at.vy0[l], at.vx1[l], at.vy1[l]);
  }
  return raised;
}

// Steps the group's pairs over the record, twice: the first sweep (Search = false) finds the
// bounds, the second repeats the same arithmetic and looks for the peaks. Nothing is stored
// between the two: a stored history (four doubles a lane and sub-step point) cost more in
// memory traffic than stepping again.
template <bool Search>
[[gnu::always_inline]] inline void sweep_kernel(const Group& g, const double* a1, const double* a2,
                                                std::size_t samples, GroupBounds& bounds, GroupSearch* search) {
  const Vec4 auu = load4(g.a_uu), auv = load4(g.a_uv), bu0 = load4(g.b_u0), bu1 = load4(g.b_u1);
  const Vec4 avu = load4(g.a_vu), avv = load4(g.a_vv), bv0 = load4(g.b_v0), bv1 = load4(g.b_v1);
  const std::size_t n = g.n;
  const Vec4 zero = {0.0, 0.0, 0.0, 0.0};
  Vec4 x = zero, y = zero, vx = zero, vy = zero;
  Vec4 far[4] = {zero, zero, zero, zero}, fx[4] = {zero, zero, zero, zero}, fy[4] = {zero, zero, zero, zero};
  Vec4 v2m = zero, r2m = zero;
  // Second sweep: thresholds of the two tests, |(x, y)|^2 at the sub-step's start.
  Vec4 f2 = zero, t2 = zero, r2a = zero;
  double threshold[kGroup];
  auto reload_thresholds = [&] {
    for (std::size_t l = 0; l < kGroup; ++l)
      threshold[l] = search->lanes[l] ? search->lanes[l]->reach2() : std::numeric_limits<double>::infinity();
    t2 = load4(threshold);
  };
  if constexpr (Search) {
    f2 = load4(search->floor2);
    reload_thresholds();
  }
  std::size_t s = 0;  // the sub-step's index
  auto advance = [&](double p, double pn, double q, double qn) {
    const Vec4 x1 = auu * x + auv * vx + bu0 * p + bu1 * pn;
    const Vec4 vx1 = avu * x + avv * vx + bv0 * p + bv1 * pn;
    const Vec4 y1 = auu * y + auv * vy + bu0 * q + bu1 * qn;
    const Vec4 vy1 = avu * y + avv * vy + bv0 * q + bv1 * qn;
    const Vec4 r2 = x1 * x1 + y1 * y1;
    if constexpr (!Search) {
      const Vec4 d[4] = {abs4(x1), abs4(x1 + y1), abs4(y1), abs4(x1 - y1)};
      for (int j = 0; j < 4; ++j) {
        const Mask4 m = d[j] > far[j];
        far[j] = m ? d[j] : far[j];
        fx[j] = m ? x1 : fx[j];
        fy[j] = m ? y1 : fy[j];
      }
      r2m = max4(r2m, r2);
      v2m = max4(v2m, vx1 * vx1 + vy1 * vy1);
    } else {
      // Rare (a few per cent of points): a point beyond its lane's floor, or a sub-step whose
      // ends reach its lane's threshold. The work is done out of line so that the loop keeps
      // its vectors in registers.
      const Mask4 beyond = r2 >= f2, reach = max4(r2a, r2) >= t2;
      if (any4(beyond | reach)) [[unlikely]] {
        SubStep at;
        store4(at.x0, x), store4(at.y0, y), store4(at.vx0, vx), store4(at.vy0, vy);
        store4(at.x1, x1), store4(at.y1, y1), store4(at.vx1, vx1), store4(at.vy1, vy1);
        for (std::size_t l = 0; l < kGroup; ++l) at.beyond[l] = beyond[l] != 0, at.reach[l] = reach[l] != 0;
        if (search_substep(*search, s, at)) reload_thresholds();
      }
      r2a = r2;
    }
    x = x1, vx = vx1, y = y1, vy = vy1;
    ++s;
  };
  const double inv_n = 1.0 / static_cast<double>(n);
  for (std::size_t i = 0; i + 1 < samples; ++i) {
    const double p0 = -a1[i], p1 = -a1[i + 1], q0 = -a2[i], q1 = -a2[i + 1];
    if (n == 1) {
      advance(p0, p1, q0, q1);
      continue;
    }
    const double dp = (p1 - p0) * inv_n, dq = (q1 - q0) * inv_n;
    double p = p0, q = q0;
    for (std::size_t j = 1; j <= n; ++j) {
      const double pn = j == n ? p1 : p0 + dp * static_cast<double>(j);
      const double qn = j == n ? q1 : q0 + dq * static_cast<double>(j);
      advance(p, pn, q, qn);
      p = pn, q = qn;
    }
  }
  if constexpr (!Search) {
    for (std::size_t j = 0; j < 4; ++j) store4(bounds.far_x[j], fx[j]), store4(bounds.far_y[j], fy[j]);
    store4(bounds.v2max, v2m), store4(bounds.r2max, r2m);
  }
}

ADJOIN_SIMD_CLONES void bound_group(const Group& g, const double* a1, const double* a2, std::size_t samples,
                                    GroupBounds& bounds) {
  sweep_kernel<false>(g, a1, a2, samples, bounds, nullptr);
}
ADJOIN_SIMD_CLONES void search_group(const Group& g, const double* a1, const double* a2, std::size_t samples,
                                     GroupBounds& bounds, GroupSearch& search) {
  sweep_kernel<true>(g, a1, a2, samples, bounds, &search);
}

// Peaks D(theta) [m] at every angle of the group's pairs (periods > 0), into peaks[lane].
void group_peaks(double dt, std::span<const double> a1, std::span<const double> a2, const Group& g,
                 const RotDOptions& options, const Angles& angles, const Sectors& sectors,
                 const spectrum_detail::ExcitationBounds& excitation, std::vector<Vec> (&peaks)[kGroup]) {
  const std::size_t samples = a1.size(), n = g.n;
  GroupBounds bounds;
  bound_group(g, a1.data(), a2.data(), samples, bounds);

  // Sampled peaks: the farthest points in four directions, rotated to every angle, give a floor
  // (a lower bound of the smallest peak over the angles); only the points at or beyond it can
  // hold an angle's peak, a few per cent of a record.
  GroupSearch search;
  search.peaks = peaks, search.angles = &angles, search.sectors = &sectors;
  for (std::size_t l = 0; l < kGroup; ++l) {
    peaks[l].assign(angles.blocks, splat(0.0));
    for (std::size_t j = 0; j < 4; ++j) rotate_into(peaks[l], angles, bounds.far_x[j][l], bounds.far_y[j][l]);
    const double floor = smallest(peaks[l], angles.count);
    search.floor2[l] = l < g.lanes ? floor * floor : std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < Sectors::kCount; ++k)
      search.sector_floor[l][k] = sectors.first[k] < sectors.first[k + 1]
                                      ? smallest_in(peaks[l], sectors.first[k], sectors.first[k + 1])
                                      : std::numeric_limits<double>::infinity();
  }

  // Peaks between sub-step points. |u''|, |u'''| and |u''''| of the displacement vector are
  // bounded from the largest excitation, velocity and displacement (p'' = 0 inside a
  // sub-step), with a factor 2 for the sub-steps' interiors.
  const double h = dt / static_cast<double>(n);
  LaneRefiner refiners[kGroup];
  for (std::size_t l = 0; l < g.lanes && options.refine_peaks && samples > 1; ++l) {
    const double omega = g.omega[l];
    if (omega * h > kMaxRefineTheta) continue;
    LaneRefiner& r = refiners[l];
    r.a1 = a1, r.a2 = a2, r.angles = &angles, r.peaks = &peaks[l];
    r.n = n, r.inv_n = 1.0 / static_cast<double>(n), r.h = h;
    r.c = 2.0 * g.zeta[l] * omega, r.w2 = omega * omega;
    const double vmax = std::sqrt(bounds.v2max[l]), rmax = std::sqrt(bounds.r2max[l]);
    const double b2 = 2.0 * (excitation.p + r.c * vmax + r.w2 * rmax);
    const double b3 = 2.0 * (excitation.slope + r.c * b2 + r.w2 * vmax);
    const double b4 = 2.0 * (r.c * b3 + r.w2 * b2);
    r.margin2 = 0.125 * h * h * b2;          // max - end values, quadratic bound
    r.margin4 = h * h * h * h / 384.0 * b4;  // cubic Hermite interpolation error
    r.terms = taylor_terms(omega * h);
    r.floor = smallest(peaks[l], angles.count);
    search.lanes[l] = &r;
  }
  search_group(g, a1.data(), a2.data(), samples, bounds, search);
}

void check_pair(double dt, std::span<const double> a1, std::span<const double> a2) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream out;
    out << "RotD spectrum: the time step must be a positive number, got dt = " << dt;
    throw InputError(out.str());
  }
  if (a1.empty() || a2.empty()) throw InputError("RotD spectrum: a component's acceleration history is empty");
  if (a1.size() != a2.size()) {
    std::ostringstream out;
    out << "RotD spectrum: the two components must have the same number of samples, got " << a1.size() << " and "
        << a2.size() << " (pad the shorter with zeros)";
    throw InputError(out.str());
  }
  for (int comp = 0; comp < 2; ++comp) {
    const std::span<const double> a = comp == 0 ? a1 : a2;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!std::isfinite(a[i])) {
        std::ostringstream out;
        out << "RotD spectrum: component " << comp + 1 << ", acceleration sample " << i << " (t = "
            << static_cast<double>(i) * dt << " s) is not a finite number";
        throw InputError(out.str());
      }
  }
}

}  // namespace

double percentile_linear(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double position = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double f = position - static_cast<double>(below);
  return values[below] + f * (values[above] - values[below]);
}

bool RotDOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  SpectrumOptions so;
  so.periods = periods;
  so.dampings = dampings;
  so.points_per_period = points_per_period;
  so.max_substeps = max_substeps;
  if (!so.IsValid(error)) return false;
  for (double p : percentiles)
    if (!(p >= 0.0 && p <= 100.0)) {
      std::ostringstream out;
      out << "RotD percentiles must be from 0 to 100, got " << p;
      return fail(out.str());
    }
  const double quarter = std::isfinite(angle_step) && angle_step > 0.0 ? 90.0 / angle_step : 0.0;
  if (!(quarter >= 1.0 && quarter <= 900.0) || std::abs(quarter - std::round(quarter)) > 1e-9 * quarter) {
    std::ostringstream out;
    out << "RotD angle step must divide 90 degrees into 1 to 900 equal parts (1 is usual), got " << angle_step;
    return fail(out.str());
  }
  return true;
}

RotatedPeaks rotated_peaks(std::span<const double> x1, std::span<const double> x2, double angle_step) {
  RotDOptions check;
  check.angle_step = angle_step;
  std::string error;
  if (!check.IsValid(&error)) throw InputError(error);
  if (x1.size() != x2.size()) throw InputError("rotated peaks: the two histories must have the same length");
  const Angles angles(angle_step);
  std::vector<double> r2(x1.size());
  for (std::size_t k = 0; k < x1.size(); ++k) r2[k] = x1[k] * x1[k] + x2[k] * x2[k];
  std::vector<Vec> peaks(angles.blocks, splat(0.0));
  sampled_peaks(x1.data(), x2.data(), r2.data(), x1.size(), angles, peaks);
  std::vector<double> values(angles.count);
  for (std::size_t k = 0; k < angles.count; ++k) values[k] = peaks[k / kLanes][k % kLanes];
  RotatedPeaks out;
  const auto lo = std::min_element(values.begin(), values.end()), hi = std::max_element(values.begin(), values.end());
  out.rotd00 = *lo;
  out.rotd100 = *hi;
  out.angle00 = static_cast<double>(lo - values.begin()) * angle_step;
  out.angle100 = static_cast<double>(hi - values.begin()) * angle_step;
  out.rotd50 = percentile_linear(values, 50.0);
  return out;
}

RotDSpectrum rotd_spectrum(double dt, std::span<const double> a1, std::span<const double> a2,
                           const RotDOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  check_pair(dt, a1, a2);
  RotDSpectrum out;
  out.periods = options.periods.empty() ? default_spectrum_periods() : options.periods;
  out.dampings = options.dampings;
  out.percentiles = options.percentiles;
  out.angle_step = options.angle_step;
  const Angles angles(options.angle_step);
  const Sectors sectors(angles);
  // Bounds of |(p1, p2)| and of its slope over the record, for the peak search's margins.
  spectrum_detail::ExcitationBounds bounds;
  for (std::size_t i = 0; i < a1.size(); ++i) {
    bounds.p = std::max(bounds.p, std::sqrt(a1[i] * a1[i] + a2[i] * a2[i]));
    if (i > 0) {
      const double d1 = a1[i] - a1[i - 1], d2 = a2[i] - a2[i - 1];
      bounds.slope = std::max(bounds.slope, std::sqrt(d1 * d1 + d2 * d2) / dt);
    }
  }
  const std::size_t np = out.periods.size(), total = np * out.dampings.size();
  out.values.resize(total);

  // Peaks at every angle: the tasks (period > 0, damping) in groups of four sharing a sub-step
  // count, most sub-steps first; then the periods 0 (the ground itself), one a task.
  SpectrumOptions so;
  so.points_per_period = options.points_per_period;
  so.max_substeps = options.max_substeps;
  std::map<std::size_t, std::vector<std::size_t>, std::greater<>> by_substeps;
  std::vector<std::size_t> ground_tasks;
  for (std::size_t t = 0; t < total; ++t) {
    const double period = out.periods[t % np];
    if (period == 0.0) ground_tasks.push_back(t);
    else by_substeps[spectrum_substeps(dt, period, so)].push_back(t);
  }
  std::vector<Group> groups;
  for (const auto& [n, tasks] : by_substeps)
    for (std::size_t first = 0; first < tasks.size(); first += kGroup) {
      Group g;
      g.n = n;
      g.lanes = std::min(kGroup, tasks.size() - first);
      const double h = dt / static_cast<double>(n);
      for (std::size_t l = 0; l < kGroup; ++l) {
        const std::size_t task = tasks[first + (l < g.lanes ? l : 0)];
        g.task[l] = task;
        g.omega[l] = kTwoPi / out.periods[task % np];
        g.zeta[l] = out.dampings[task / np];
        const StepCoefficients k = step_coefficients(g.omega[l], g.zeta[l], h);
        g.a_uu[l] = k.a_uu, g.a_uv[l] = k.a_uv, g.b_u0[l] = k.b_u0, g.b_u1[l] = k.b_u1;
        g.a_vu[l] = k.a_vu, g.a_vv[l] = k.a_vv, g.b_v0[l] = k.b_v0, g.b_v1[l] = k.b_v1;
      }
      groups.push_back(g);
    }
  const std::size_t items = groups.size() + ground_tasks.size();
  auto start = [&](std::size_t task) -> RotDValues& {
    RotDValues& v = out.values[task];
    v.period = out.periods[task % np];
    v.damping = out.dampings[task / np];
    v.by_angle.resize(angles.count);
    return v;
  };
  std::atomic<std::size_t> next{0};
  auto work = [&]() {
    std::vector<Vec> peaks[kGroup];
    for (std::size_t item = next.fetch_add(1); item < items; item = next.fetch_add(1)) {
      if (item < groups.size()) {
        const Group& g = groups[item];
        group_peaks(dt, a1, a2, g, options, angles, sectors, bounds, peaks);
        for (std::size_t l = 0; l < g.lanes; ++l) {
          RotDValues& v = start(g.task[l]);
          const double scale = g.omega[l] * g.omega[l] / kStandardGravity;
          for (std::size_t k = 0; k < angles.count; ++k) v.by_angle[k] = peaks[l][k / kLanes][k % kLanes] * scale;
        }
      } else {
        RotDValues& v = start(ground_tasks[item - groups.size()]);
        std::vector<double> r2(a1.size());
        for (std::size_t k = 0; k < a1.size(); ++k) r2[k] = a1[k] * a1[k] + a2[k] * a2[k];
        peaks[0].assign(angles.blocks, splat(0.0));
        sampled_peaks(a1.data(), a2.data(), r2.data(), a1.size(), angles, peaks[0]);
        for (std::size_t k = 0; k < angles.count; ++k) v.by_angle[k] = peaks[0][k / kLanes][k % kLanes] / kStandardGravity;
      }
    }
  };
  spectrum_detail::run_workers(options.threads, items, work);

  // Percentiles and angles.
  const std::size_t quarter = angles.count / 2;  // the angle index of 90 degrees
  for (RotDValues& v : out.values) {
    const auto lo = std::min_element(v.by_angle.begin(), v.by_angle.end());
    const auto hi = std::max_element(v.by_angle.begin(), v.by_angle.end());
    v.rotd00 = *lo;
    v.rotd100 = *hi;
    v.angle00 = static_cast<double>(lo - v.by_angle.begin()) * angles.step;
    v.angle100 = static_cast<double>(hi - v.by_angle.begin()) * angles.step;
    v.rotd50 = percentile_linear(v.by_angle, 50.0);
    for (double p : options.percentiles) v.extra.push_back(percentile_linear(v.by_angle, p));
    v.psa1 = v.by_angle[0];
    v.psa2 = v.by_angle[quarter];
  }

  // GMRotI50, per damping.
  out.gmroti50_angle.assign(out.dampings.size(), 0.0);
  for (std::size_t d = 0; d < out.dampings.size(); ++d) {
    std::vector<double> penalty(quarter, 0.0);
    std::vector<double> gm(quarter);
    std::size_t used = 0;
    for (std::size_t i = 0; i < np; ++i) {
      const RotDValues& v = out.values[d * np + i];
      if (!(v.period > 0.0)) continue;
      for (std::size_t j = 0; j < quarter; ++j) gm[j] = std::sqrt(v.by_angle[j] * v.by_angle[j + quarter]);
      const double median = percentile_linear(gm, 50.0);
      if (!(median > 0.0)) continue;
      for (std::size_t j = 0; j < quarter; ++j) {
        const double r = gm[j] / median - 1.0;
        penalty[j] += r * r;
      }
      ++used;
    }
    const std::size_t best =
        used == 0 ? 0 : static_cast<std::size_t>(std::min_element(penalty.begin(), penalty.end()) - penalty.begin());
    out.gmroti50_angle[d] = static_cast<double>(best) * angles.step;
    for (std::size_t i = 0; i < np; ++i) {
      RotDValues& v = out.values[d * np + i];
      v.gmroti50 = std::sqrt(v.by_angle[best] * v.by_angle[best + quarter]);
    }
  }
  return out;
}

RotDSpectrum rotd_spectrum(const Record& first, const Record& second, const RotDOptions& options) {
  if (!(std::abs(first.dt - second.dt) <= 1e-9 * std::max(first.dt, second.dt))) {
    std::ostringstream out;
    out << "RotD spectrum: the two components must have the same time step, got dt = " << first.dt << " s ("
        << first.source << ") and " << second.dt << " s (" << second.source << ")";
    throw InputError(out.str());
  }
  return rotd_spectrum(first.dt, first.accel, second.accel, options);
}

}  // namespace adjoin
