#pragma once
// The structure step's passes over the floors (internal to solver/structure_solver.cpp), in
// plain loops the compiler vectorises. Each is built twice, for the baseline x86-64 (vectors
// of 2 doubles) and for AVX2 (4), and the second is used where the processor has it. An
// element is computed by the same operations in the same order either way (no fused
// multiply-add, no reassociation), so the two give the same results bit for bit; each loop
// also forms its elements as the Eigen expressions it replaces did.
#include <Eigen/Dense>

namespace adjoin::detail {

// A tridiagonal matrix's diagonals: lo[i] = K(i + 1, i), di[i] = K(i, i), up[i] = K(i, i + 1).
struct Tridiagonal {
  const double* lo = nullptr;
  const double* di = nullptr;
  const double* up = nullptr;
};

struct StepKernels {
  using Index = Eigen::Index;
  // The free step's right-hand side, K tridiagonal and n > 2: x1 = x + c v, p = K x1,
  // rhs = m v + c ((((m s - cv) - p0) - p) - off).
  void (*free_rhs)(Index n, const double* m, const double* x, const double* v, const double* cv, const double* p0,
                   const double* off, Tridiagonal k, double c, double s, double* x1, double* p, double* rhs);
  // v = vf - h rv, cv = cvf - h rc.
  void (*end_velocities)(Index n, const double* vf, const double* cvf, const double* rv, const double* rc, double h,
                         double* v, double* cv);
  // x1 = x0 + c (v0 + v1).
  void (*trapezoid)(Index n, const double* x0, const double* v0, const double* v1, double c, double* x1);
  // p = K x, K tridiagonal and n > 2.
  void (*band)(Index n, Tridiagonal k, const double* x, double* p);
  // a = (m ag - cv - p) / m - ag, with inv_m = 1 / m: ((m ag - cv) - p) inv_m - ag.
  void (*accelerations)(Index n, const double* m, const double* inv_m, const double* cv, const double* p, double ag,
                        double* a);
  // f[i] = s[i] (x[i] - x[i - 1]) + d[i] (v[i] - v[i - 1]) for 0 < i < n; without d (null), the
  // first term alone.
  void (*drifts)(Index n, const double* s, const double* d, const double* x, const double* v, double* f);
  // y += a x.
  void (*axpy)(Index n, double a, const double* x, double* y);
  // Whether some |x_i| exceeds `limit` or some x_i or v_i is not finite.
  bool (*out_of_range)(Index n, const double* x, const double* v, double limit);
  // out = m q for a column-major m (rows x cols, cols > 0), each row summed over the columns in
  // order from the first product: m(r, 0) q_0 + m(r, 1) q_1 + ...
  void (*columns)(Index rows, Index cols, const double* m, const double* q, double* out);
  // out = sum over the listed columns `which` (count of them, in order) of m's column k times
  // q[k], m column-major with column stride `stride`: each row from 0, the products added in
  // the list's order (a product with a sparse q: its nonzero entries listed).
  void (*some_columns)(Index rows, Index stride, Index count, const int* which, const double* m, const double* q,
                       double* out);
};

// The kernels for this processor (chosen once).
const StepKernels& step_kernels();
// The baseline ones (tests compare the two).
const StepKernels& baseline_step_kernels();

}  // namespace adjoin::detail
