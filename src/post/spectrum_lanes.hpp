#pragma once
// Lane kernels of the response spectrum (used by spectrum.cpp only, which is compiled without
// fused multiply-adds so that a lane computes what Oscillator::step computes, digit for digit).
#include <cstddef>

#include "spectrum_oscillator.hpp"

namespace adjoin::spectrum_detail {

// Oscillators sharing a sub-step count see the same excitation values, so four of them are
// advanced together, one per lane of a vector register (GCC vector extensions: AVX2 registers
// in the x86-64-v3 clone, pairs of SSE2 registers otherwise), and a group of eight uses two
// registers so that the processor overlaps two independent recursions. Each lane computes
// exactly what Oscillator::step computes, in the same order, so results do not depend on the
// grouping. The near-peak test is done for all lanes at once; the rare lanes that pass it go
// through the scalar Oscillator code and their thresholds are reloaded.
//
// GCC warns that passing these vectors by value has another ABI with and without AVX; they
// only pass between inlined helpers here, and the warning is given at the end of the
// translation unit, so it is turned off from here to the end of spectrum.cpp.
#pragma GCC diagnostic ignored "-Wpsabi"

using Vec = double __attribute__((vector_size(32)));
using Mask = long long __attribute__((vector_size(32)));
constexpr int kLanes = 4;

[[gnu::always_inline]] inline Vec vabs(Vec x) { return reinterpret_cast<Vec>(reinterpret_cast<Mask>(x) & 0x7fffffffffffffffLL); }
[[gnu::always_inline]] inline Vec vmax(Vec a, Vec b) { return a > b ? a : b; }
[[gnu::always_inline]] inline bool any(Mask m) { return ((m[0] | m[1]) | (m[2] | m[3])) != 0; }

template <int V>
struct Lanes {
  Vec a_uu[V], a_uv[V], b_u0[V], b_u1[V], a_vu[V], a_vv[V], b_v0[V], b_v1[V], c[V], w2[V];
  Vec u[V], v[V], a[V];

  explicit Lanes(const Oscillator* osc) {
    for (int r = 0; r < V; ++r)
      for (int l = 0; l < kLanes; ++l) {
        const Oscillator& o = osc[r * kLanes + l];
        const StepCoefficients& k = o.coefficients();
        a_uu[r][l] = k.a_uu, a_uv[r][l] = k.a_uv, b_u0[r][l] = k.b_u0, b_u1[r][l] = k.b_u1;
        a_vu[r][l] = k.a_vu, a_vv[r][l] = k.a_vv, b_v0[r][l] = k.b_v0, b_v1[r][l] = k.b_v1;
        c[r][l] = o.damping_term(), w2[r][l] = o.stiffness_term();
        u[r][l] = o.u(), v[r][l] = o.v(), a[r][l] = o.a_abs();
      }
  }
  void store_state(Oscillator* osc) const {
    for (int r = 0; r < V; ++r)
      for (int l = 0; l < kLanes; ++l) osc[r * kLanes + l].set_state(u[r][l], v[r][l], a[r][l]);
  }
};

// Advances the lanes over the record. Refine: peaks located exactly between sub-step points
// (Oscillator::step, four lanes at a time); otherwise peaks at the sub-step points only
// (Oscillator::step_sampled).
template <int V, bool Refine>
[[gnu::always_inline]] inline void advance_lanes(Oscillator* osc, const double* accel, std::size_t samples,
                                                 std::size_t n) {
  Lanes<V> s(osc);
  Vec pu[V], pv[V], pa[V];  // sampled: running peaks
  Vec tu[V], tv[V], ta[V];  // refined: thresholds of the near-peak test
  Vec au[V], av[V], aa[V];  // refined: |u|, |v|, |a_abs| at the start of the sub-step
  auto load_thresholds = [&](int r, int l) {
    const Oscillator& o = osc[r * kLanes + l];
    tu[r][l] = o.threshold_u(), tv[r][l] = o.threshold_v(), ta[r][l] = o.threshold_a();
  };
  for (int r = 0; r < V; ++r) {
    for (int l = 0; l < kLanes; ++l) {
      const Peaks& p = osc[r * kLanes + l].peaks();
      pu[r][l] = p.u, pv[r][l] = p.v, pa[r][l] = p.a;
      load_thresholds(r, l);
    }
    au[r] = vabs(s.u[r]), av[r] = vabs(s.v[r]), aa[r] = vabs(s.a[r]);
  }
  auto step = [&](double p0, double p1) {
    for (int r = 0; r < V; ++r) {
      const Vec u1 = s.a_uu[r] * s.u[r] + s.a_uv[r] * s.v[r] + s.b_u0[r] * p0 + s.b_u1[r] * p1;
      const Vec v1 = s.a_vu[r] * s.u[r] + s.a_vv[r] * s.v[r] + s.b_v0[r] * p0 + s.b_v1[r] * p1;
      const Vec a1 = -(s.c[r] * v1 + s.w2[r] * u1);
      const Vec au1 = vabs(u1), av1 = vabs(v1), aa1 = vabs(a1);
      if constexpr (Refine) {
        const Mask near = (vmax(au[r], au1) >= tu[r]) | (vmax(av[r], av1) >= tv[r]) | (vmax(aa[r], aa1) >= ta[r]);
        if (any(near)) [[unlikely]] {
          for (int l = 0; l < kLanes; ++l) {
            if (!near[l]) continue;
            Oscillator& o = osc[r * kLanes + l];
            o.set_state(s.u[r][l], s.v[r][l], s.a[r][l]);
            o.step_near_peak(p0, p1, u1[l], v1[l], a1[l]);
            load_thresholds(r, l);
          }
        }
        au[r] = au1, av[r] = av1, aa[r] = aa1;
      } else {
        pu[r] = vmax(pu[r], au1);
        pv[r] = vmax(pv[r], av1);
        pa[r] = vmax(pa[r], aa1);
      }
      s.u[r] = u1, s.v[r] = v1, s.a[r] = a1;
    }
  };
  const double inv_n = 1.0 / static_cast<double>(n);
  for (std::size_t i = 0; i + 1 < samples; ++i) {
    const double p0 = -accel[i], p1 = -accel[i + 1];
    if (n == 1) {
      step(p0, p1);
      continue;
    }
    const double dp = (p1 - p0) * inv_n;
    double p = p0;
    for (std::size_t j = 1; j <= n; ++j) {
      const double next = j == n ? p1 : p0 + dp * static_cast<double>(j);
      step(p, next);
      p = next;
    }
  }
  s.store_state(osc);
  if constexpr (!Refine)
    for (int r = 0; r < V; ++r)
      for (int l = 0; l < kLanes; ++l) osc[r * kLanes + l].set_peaks(Peaks{pu[r][l], pv[r][l], pa[r][l]});
}

}  // namespace adjoin::spectrum_detail
