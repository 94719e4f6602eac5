#include "step_kernels.hpp"

#include "../detail/cpu_kernels.hpp"

#include <cmath>

namespace adjoin::detail {
namespace {

using Index = Eigen::Index;

ADJOIN_INLINE void free_rhs_body(Index n, const double* __restrict m, const double* __restrict x,
                                 const double* __restrict v, const double* __restrict cv, const double* __restrict p0,
                                 const double* __restrict off, Tridiagonal k, double c, double s,
                                 double* __restrict x1, double* __restrict p, double* __restrict rhs) {
  for (Index i = 0; i < n; ++i) x1[i] = x[i] + c * v[i];
  p[0] = k.di[0] * x1[0] + k.up[0] * x1[1];
  for (Index i = 1; i < n - 1; ++i) p[i] = k.lo[i - 1] * x1[i - 1] + k.di[i] * x1[i] + k.up[i] * x1[i + 1];
  p[n - 1] = k.lo[n - 2] * x1[n - 2] + k.di[n - 1] * x1[n - 1];
  for (Index i = 0; i < n; ++i) rhs[i] = m[i] * v[i] + c * ((((m[i] * s - cv[i]) - p0[i]) - p[i]) - off[i]);
}

ADJOIN_INLINE void end_velocities_body(Index n, const double* __restrict vf, const double* __restrict cvf,
                                       const double* __restrict rv, const double* __restrict rc, double h,
                                       double* __restrict v, double* __restrict cv) {
  for (Index i = 0; i < n; ++i) {
    v[i] = vf[i] - h * rv[i];
    cv[i] = cvf[i] - h * rc[i];
  }
}

ADJOIN_INLINE void trapezoid_body(Index n, const double* __restrict x0, const double* __restrict v0,
                                  const double* __restrict v1, double c, double* __restrict x1) {
  for (Index i = 0; i < n; ++i) x1[i] = x0[i] + c * (v0[i] + v1[i]);
}

ADJOIN_INLINE void band_body(Index n, Tridiagonal k, const double* __restrict x, double* __restrict p) {
  p[0] = k.di[0] * x[0] + k.up[0] * x[1];
  for (Index i = 1; i < n - 1; ++i) p[i] = k.lo[i - 1] * x[i - 1] + k.di[i] * x[i] + k.up[i] * x[i + 1];
  p[n - 1] = k.lo[n - 2] * x[n - 2] + k.di[n - 1] * x[n - 1];
}

ADJOIN_INLINE void accelerations_body(Index n, const double* __restrict m, const double* __restrict inv_m,
                                      const double* __restrict cv, const double* __restrict p, double ag,
                                      double* __restrict a) {
  for (Index i = 0; i < n; ++i) a[i] = ((m[i] * ag - cv[i]) - p[i]) * inv_m[i] - ag;
}

ADJOIN_INLINE void drifts_body(Index n, const double* __restrict s, const double* __restrict d,
                               const double* __restrict x, const double* __restrict v, double* __restrict f) {
  if (d == nullptr) {
    for (Index i = 1; i < n; ++i) f[i] = s[i] * (x[i] - x[i - 1]);
  } else {
    for (Index i = 1; i < n; ++i) f[i] = s[i] * (x[i] - x[i - 1]) + d[i] * (v[i] - v[i - 1]);
  }
}

ADJOIN_INLINE void axpy_body(Index n, double a, const double* __restrict x, double* __restrict y) {
  for (Index i = 0; i < n; ++i) y[i] += x[i] * a;
}

// (|x| <= limit is false for a NaN x; v - v is 0 for a finite v, NaN for an infinite or NaN one.
// The flags are combined with |, not ||, so that the loop vectorises.)
ADJOIN_INLINE bool out_of_range_body(Index n, const double* __restrict x, const double* __restrict v, double limit) {
  int bad = 0;
  for (Index i = 0; i < n; ++i) bad |= static_cast<int>(!(std::abs(x[i]) <= limit)) | static_cast<int>(!(v[i] - v[i] == 0.0));
  return bad != 0;
}

ADJOIN_INLINE void columns_body(Index rows, Index cols, const double* __restrict m, const double* __restrict q,
                                double* __restrict out) {
  for (Index r = 0; r < rows; ++r) out[r] = m[r] * q[0];
  for (Index j = 1; j < cols; ++j)
    for (Index r = 0; r < rows; ++r) out[r] += m[j * rows + r] * q[j];
}

ADJOIN_INLINE void some_columns_body(Index rows, Index stride, Index count, const int* __restrict which,
                                     const double* __restrict m, const double* __restrict q, double* __restrict out) {
  auto column = [&](Index j) { return m + static_cast<Index>(which[j]) * stride; };
  // (Each row's sum starts from 0.0: the first pass adds to it without storing it first.)
  Index j = 0;
  if (count >= 4) {
    const double* __restrict c0 = column(0);
    const double* __restrict c1 = column(1);
    const double* __restrict c2 = column(2);
    const double* __restrict c3 = column(3);
    const double q0 = q[which[0]], q1 = q[which[1]], q2 = q[which[2]], q3 = q[which[3]];
    for (Index r = 0; r < rows; ++r) out[r] = (((0.0 + q0 * c0[r]) + q1 * c1[r]) + q2 * c2[r]) + q3 * c3[r];
    j = 4;
  } else if (count > 0) {
    const double* __restrict c0 = column(0);
    const double q0 = q[which[0]];
    for (Index r = 0; r < rows; ++r) out[r] = 0.0 + q0 * c0[r];
    j = 1;
  } else {
    for (Index r = 0; r < rows; ++r) out[r] = 0.0;
  }
  for (; j + 4 <= count; j += 4) {  // (four columns a pass over out: the same sums, in the same order)
    const double* __restrict c0 = column(j);
    const double* __restrict c1 = column(j + 1);
    const double* __restrict c2 = column(j + 2);
    const double* __restrict c3 = column(j + 3);
    const double q0 = q[which[j]], q1 = q[which[j + 1]], q2 = q[which[j + 2]], q3 = q[which[j + 3]];
    for (Index r = 0; r < rows; ++r) out[r] = (((out[r] + q0 * c0[r]) + q1 * c1[r]) + q2 * c2[r]) + q3 * c3[r];
  }
  for (; j < count; ++j) {
    const double* __restrict col = column(j);
    const double qj = q[which[j]];
    for (Index r = 0; r < rows; ++r) out[r] += qj * col[r];
  }
}

ADJOIN_KERNEL(void, free_rhs,
              (Index n, const double* m, const double* x, const double* v, const double* cv, const double* p0,
               const double* off, Tridiagonal k, double c, double s, double* x1, double* p, double* rhs),
              (n, m, x, v, cv, p0, off, k, c, s, x1, p, rhs))
ADJOIN_KERNEL(void, end_velocities,
              (Index n, const double* vf, const double* cvf, const double* rv, const double* rc, double h, double* v,
               double* cv),
              (n, vf, cvf, rv, rc, h, v, cv))
ADJOIN_KERNEL(void, trapezoid, (Index n, const double* x0, const double* v0, const double* v1, double c, double* x1),
              (n, x0, v0, v1, c, x1))
ADJOIN_KERNEL(void, band, (Index n, Tridiagonal k, const double* x, double* p), (n, k, x, p))
ADJOIN_KERNEL(void, accelerations,
              (Index n, const double* m, const double* inv_m, const double* cv, const double* p, double ag, double* a),
              (n, m, inv_m, cv, p, ag, a))
ADJOIN_KERNEL(void, drifts, (Index n, const double* s, const double* d, const double* x, const double* v, double* f),
              (n, s, d, x, v, f))
ADJOIN_KERNEL(void, axpy, (Index n, double a, const double* x, double* y), (n, a, x, y))
ADJOIN_KERNEL(bool, out_of_range, (Index n, const double* x, const double* v, double limit), (n, x, v, limit))
ADJOIN_KERNEL(void, columns, (Index rows, Index cols, const double* m, const double* q, double* out), (rows, cols, m, q, out))
ADJOIN_KERNEL(void, some_columns,
              (Index rows, Index stride, Index count, const int* which, const double* m, const double* q, double* out),
              (rows, stride, count, which, m, q, out))
#undef ADJOIN_KERNEL

const StepKernels kBaseline{&free_rhs_base,      &end_velocities_base, &trapezoid_base, &band_base,
                            &accelerations_base, &drifts_base,         &axpy_base,      &out_of_range_base, &columns_base,
                            &some_columns_base};
#ifdef ADJOIN_HAVE_AVX2
const StepKernels kAvx2{&free_rhs_avx2,      &end_velocities_avx2, &trapezoid_avx2, &band_avx2,
                        &accelerations_avx2, &drifts_avx2,         &axpy_avx2,      &out_of_range_avx2, &columns_avx2,
                        &some_columns_avx2};
#endif

}  // namespace

const StepKernels& baseline_step_kernels() { return kBaseline; }

const StepKernels& step_kernels() {
#ifdef ADJOIN_HAVE_AVX2
  static const StepKernels& chosen = kernels_for_this_cpu(kBaseline, &kAvx2);
#else
  static const StepKernels& chosen = kernels_for_this_cpu(kBaseline, nullptr);
#endif
  return chosen;
}

}  // namespace adjoin::detail
