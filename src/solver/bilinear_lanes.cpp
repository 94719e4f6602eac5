#include "bilinear_lanes.hpp"

#include "../detail/cpu_kernels.hpp"

#include <cmath>

namespace adjoin::detail {

BilinearLayout::BilinearLayout(const std::vector<BilinearElement>& elements) {
  const int n = static_cast<int>(elements.size());
  chains = n > 0;
  for (int e = 0; e < n; ++e) {
    const BilinearElement& el = elements[static_cast<std::size_t>(e)];
    k.push_back(el.k);
    limit.push_back(el.limit);
    i.push_back(el.i);
    j.push_back(el.j);
    chains = chains && el.storey_law && el.i == e && el.storey == e && (el.j == -1 || el.j == e - 1);
    if (e > 0 && el.j == -1) starts.push_back(e);
  }
  chains = chains && starts.size() <= kMaxChainStarts;
}

BilinearStates::BilinearStates(const BilinearLayout& layout)
    : el(static_cast<std::size_t>(layout.size())),
      q(static_cast<std::size_t>(layout.size()), 0.0),
      up(static_cast<std::size_t>(layout.size()), 0.0),
      offset(static_cast<std::size_t>(layout.size()), -0.0),  // (-k_h u_p at u_p = 0)
      bound(layout.limit),                                   // (elastic, from rest)
      d(static_cast<std::size_t>(layout.size()), 0.0),
      flag(static_cast<std::size_t>(layout.size()), 0.0) {}

namespace {

using Index = Eigen::Index;

// (The flags and the kept force are selected, not branched on, so that the loops vectorise;
// |q| <= bound is false for a NaN q, as bilinear_step.hpp's test, and for every q where the
// bound is -1. Each loop is written out: the vectoriser keeps __restrict only so.)
ADJOIN_INLINE Index test_body(Index n, const double* __restrict k, const double* __restrict bound,
                             const double* __restrict up, const double* __restrict d, double* __restrict flag,
                             double* __restrict q) {
  Index failed = 0;
  if (q == nullptr) {
    for (Index e = 0; e < n; ++e) {
      const bool stays = std::abs(k[e] * (d[e] - up[e])) <= bound[e];
      flag[e] = stays ? 0.0 : 1.0;
      failed += stays ? 0 : 1;
    }
  } else {
    for (Index e = 0; e < n; ++e) {
      const double q1 = k[e] * (d[e] - up[e]);
      const bool stays = std::abs(q1) <= bound[e];
      flag[e] = stays ? 0.0 : 1.0;
      q[e] = stays ? q1 : q[e];
      failed += stays ? 0 : 1;
    }
  }
  return failed;
}

// (Every drift against the floor below, then those where a chain starts again, against 0.0:
// x[e] - 0.0 exactly as the per-element formula gives it; element 0 starts one.)
ADJOIN_INLINE Index chain_test_body(Index n, Index count, const int* __restrict starts, const double* __restrict x,
                                   const double* __restrict k, const double* __restrict bound,
                                   const double* __restrict up, double* __restrict d, double* __restrict flag,
                                   double* __restrict q) {
  d[0] = x[0] - 0.0;
  for (Index e = 1; e < n; ++e) d[e] = x[e] - x[e - 1];
  for (Index c = 0; c < count; ++c) d[starts[c]] = x[starts[c]] - 0.0;
  return test_body(n, k, bound, up, d, flag, q);
}

// (Every element's force into its floor and, subtracted, the floor below; where the next
// element starts a chain, that floor's p[e] + f[e] alone, from p as it was.)
ADJOIN_INLINE void chain_scatter_body(Index n, Index count, const int* __restrict starts, const double* __restrict f,
                                      double* __restrict p) {
  double before[BilinearLayout::kMaxChainStarts];
  for (Index c = 0; c < count; ++c) before[c] = p[starts[c] - 1];
  for (Index e = 0; e + 1 < n; ++e) p[e] = (p[e] + f[e]) - f[e + 1];
  p[n - 1] += f[n - 1];
  for (Index c = 0; c < count; ++c) p[starts[c] - 1] = before[c] + f[starts[c] - 1];
}

ADJOIN_INLINE void chain_storeys_body(Index n, const double* __restrict offset, const double* __restrict q,
                                      const double* __restrict k, double* __restrict force, double* __restrict hyst) {
  for (Index e = 0; e < n; ++e) {
    force[e] += offset[e];
    hyst[e] = q[e] / k[e];
  }
}

ADJOIN_KERNEL(Index, chain_test,
              (Index n, Index count, const int* starts, const double* x, const double* k, const double* bound,
               const double* up, double* d, double* flag, double* q),
              (n, count, starts, x, k, bound, up, d, flag, q))
ADJOIN_KERNEL(Index, test,
              (Index n, const double* k, const double* bound, const double* up, const double* d, double* flag, double* q),
              (n, k, bound, up, d, flag, q))
ADJOIN_KERNEL(void, chain_scatter, (Index n, Index count, const int* starts, const double* f, double* p),
              (n, count, starts, f, p))
ADJOIN_KERNEL(void, chain_storeys,
              (Index n, const double* offset, const double* q, const double* k, double* force, double* hyst),
              (n, offset, q, k, force, hyst))
#undef ADJOIN_KERNEL

const BilinearKernels kBaseline{&test_base, &chain_test_base, &chain_scatter_base, &chain_storeys_base};
#ifdef ADJOIN_HAVE_AVX2
const BilinearKernels kAvx2{&test_avx2, &chain_test_avx2, &chain_scatter_avx2, &chain_storeys_avx2};
#endif

}  // namespace

const BilinearKernels& baseline_bilinear_kernels() { return kBaseline; }

const BilinearKernels& bilinear_kernels() {
#ifdef ADJOIN_HAVE_AVX2
  static const BilinearKernels& chosen = kernels_for_this_cpu(kBaseline, &kAvx2);
#else
  static const BilinearKernels& chosen = kernels_for_this_cpu(kBaseline, nullptr);
#endif
  return chosen;
}

int bilinear_test(const BilinearKernels& kernels, const BilinearLayout& layout, const double* x, BilinearStates& b, bool keep) {
  const int n = layout.size();
  double* q = keep ? b.q.data() : nullptr;
  if (layout.chains)
    return static_cast<int>(kernels.chain_test(n, static_cast<Eigen::Index>(layout.starts.size()), layout.starts.data(), x, layout.k.data(),
                              b.bound.data(), b.up.data(), b.d.data(), b.flag.data(), q));
  for (int e = 0; e < n; ++e) b.d[e] = x[layout.i[e]] - (layout.j[e] >= 0 ? x[layout.j[e]] : 0.0);
  return static_cast<int>(kernels.test(n, layout.k.data(), b.bound.data(), b.up.data(), b.d.data(), b.flag.data(), q));
}

void bilinear_scatter(const BilinearKernels& kernels, const BilinearLayout& layout, const double* f, double* p) {
  if (layout.chains) {
    kernels.chain_scatter(layout.size(), static_cast<Eigen::Index>(layout.starts.size()), layout.starts.data(), f, p);
    return;
  }
  for (int e = 0; e < layout.size(); ++e) {  // (as Pair::add)
    if (layout.i[e] >= 0) p[layout.i[e]] += f[e];
    if (layout.j[e] >= 0) p[layout.j[e]] -= f[e];
  }
}

}  // namespace adjoin::detail
