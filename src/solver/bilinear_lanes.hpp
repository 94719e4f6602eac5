#pragma once
// The bilinear elements' states for the step's passes over all of them (internal to the
// solver): what every step reads or writes of every element — its force q, slip u_p, offset
// -k_h u_p, and whether the fast test applies — as arrays (structure of arrays), beside the
// per-element states (bilinear_step.hpp) that only the elements near or past yield need. The
// passes (a drift, a test of |k_h (d - u_p)| <= F_h, the offsets into the floors' forces) are
// loops the compiler vectorises, built for the baseline x86-64 and for AVX2 as the step kernels
// are (step_kernels.hpp): the same operations in the same order either way, so the results do
// not depend on the processor, and each element's numbers are those of bilinear_step.hpp's
// scalar functions bit for bit.
#include <Eigen/Dense>
#include <vector>

#include "bilinear_step.hpp"

namespace adjoin::detail {

// The elements' constants as arrays, and whether they form chains: each building's storey
// laws in order (element e on floor e, joined to floor e - 1, or to the ground where a chain
// starts), the common layout, whose drifts and offsets are contiguous passes.
struct BilinearLayout {
  BilinearLayout() = default;
  explicit BilinearLayout(const std::vector<BilinearElement>& elements);
  std::vector<double> k, limit;          // k_h and F_h per element
  std::vector<int> i, j;                 // its floors (j = -1: the ground)
  std::vector<int> starts;               // the chains' first elements but element 0's
  static constexpr std::size_t kMaxChainStarts = 8;
  bool chains = false;                   // the layout above (else the passes gather and scatter per element)
  int size() const { return static_cast<int>(k.size()); }
};

// Per run: the per-element states and the arrays every step passes over. `bound[e]` is F_h
// where the element is elastic at t_n and nothing in this step decided otherwise (its end is
// then only its force, if that stays within the yield surface, |q| <= F_h), else -1 (no force
// passes the test).
struct BilinearStates {
  std::vector<BilinearState> el;
  std::vector<double> q, up, offset, bound;
  std::vector<double> d, flag;  // (scratch: the pass's drifts and which elements left the test)

  BilinearStates() = default;
  explicit BilinearStates(const BilinearLayout& layout);
  BilinearState& operator[](int e) { return el[static_cast<std::size_t>(e)]; }
  const BilinearState& operator[](int e) const { return el[static_cast<std::size_t>(e)]; }
  // After element e's slip or phase changed (its end, not on the fast path): the arrays' copy.
  void settled(int e, const BilinearLayout& layout) {
    const BilinearState& st = el[static_cast<std::size_t>(e)];
    up[e] = st.up;
    offset[e] = -layout.k[e] * st.up;  // (as BilinearState::offset)
    bound[e] = st.phase == YieldPhase::elastic ? layout.limit[e] : -1.0;
  }
};

// The passes. n is the number of elements.
struct BilinearKernels {
  using Index = Eigen::Index;
  // flag[e] = 0 where |k (d - up)| <= bound (the element stays elastic), else 1; with q
  // (non-null) also q[e] = k (d - up) where 0. The number of flags 1.
  Index (*test)(Index n, const double* k, const double* bound, const double* up, const double* d, double* flag, double* q);
  // The same for chains, from the floors' x: d[e] = x[e] - x[e - 1], or x[e] - 0.0 where a
  // chain starts (element 0 and the `count` starts).
  Index (*chain_test)(Index n, Index count, const int* starts, const double* x, const double* k, const double* bound,
                     const double* up, double* d, double* flag, double* q);
  // Each element's force f[e] into p, +f at its first floor and -f at its second, in the
  // elements' order, for chains: p[e] = (p[e] + f[e]) - f[e + 1], but p[e] + f[e] where e + 1
  // starts a chain (at most BilinearLayout::kMaxChainStarts starts).
  void (*chain_scatter)(Index n, Index count, const int* starts, const double* f, double* p);
  // force[e] += offset[e], hyst[e] = q[e] / k[e] (a chain's storeys: element e is storey e).
  void (*chain_storeys)(Index n, const double* offset, const double* q, const double* k, double* force, double* hyst);
};

// The kernels for this processor (chosen once), and the baseline ones (tests compare the two).
const BilinearKernels& bilinear_kernels();
const BilinearKernels& baseline_bilinear_kernels();

// The passes over a layout, chains or not: the drifts d = x_i - x_j (x_-1 = 0) and the test
// of each element's force k_h (d - u_p) against its bound, into b.d and b.flag (and b.q
// where it passes, with `keep`), the number of elements that failed it; the offsets f into p (+ at
// i, - at j, in order).
int bilinear_test(const BilinearKernels& kernels, const BilinearLayout& layout, const double* x, BilinearStates& b, bool keep);
void bilinear_scatter(const BilinearKernels& kernels, const BilinearLayout& layout, const double* f, double* p);

}  // namespace adjoin::detail
