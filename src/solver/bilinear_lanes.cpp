#include "bilinear_lanes.hpp"

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
    if (el.j == -1) chain_starts.push_back(e);
  }
  chains = chains && !chain_starts.empty() && chain_starts.front() == 0;
  chain_starts.push_back(n);
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
#define ADJOIN_INLINE [[gnu::always_inline]] inline

ADJOIN_INLINE void chain_drifts_body(Index count, const int* __restrict starts, const double* __restrict x,
                                     double* __restrict d) {
  for (Index c = 0; c < count; ++c) {
    const Index s = starts[c], end = starts[c + 1];
    d[s] = x[s] - 0.0;
    for (Index e = s + 1; e < end; ++e) d[e] = x[e] - x[e - 1];
  }
}

// (The flags and the kept force are selected, not branched on, so that the loop vectorises;
// |q| <= bound is false for a NaN q, as bilinear_step.hpp's test, and for every q where the
// bound is -1.)
ADJOIN_INLINE bool test_body(Index n, const double* __restrict k, const double* __restrict bound,
                             const double* __restrict up, const double* __restrict d, double* __restrict flag,
                             double* __restrict q) {
  int any = 0;
  if (q == nullptr) {
    for (Index e = 0; e < n; ++e) {
      const bool stays = std::abs(k[e] * (d[e] - up[e])) <= bound[e];
      flag[e] = stays ? 0.0 : 1.0;
      any |= static_cast<int>(!stays);
    }
  } else {
    for (Index e = 0; e < n; ++e) {
      const double q1 = k[e] * (d[e] - up[e]);
      const bool stays = std::abs(q1) <= bound[e];
      flag[e] = stays ? 0.0 : 1.0;
      q[e] = stays ? q1 : q[e];
      any |= static_cast<int>(!stays);
    }
  }
  return any != 0;
}

ADJOIN_INLINE void chain_scatter_body(Index count, const int* __restrict starts, const double* __restrict f,
                                      double* __restrict p) {
  for (Index c = 0; c < count; ++c) {
    const Index s = starts[c], last = starts[c + 1] - 1;
    for (Index e = s; e < last; ++e) p[e] = (p[e] + f[e]) - f[e + 1];
    p[last] += f[last];
  }
}

ADJOIN_INLINE void chain_storeys_body(Index n, const double* __restrict offset, const double* __restrict q,
                                      const double* __restrict k, double* __restrict force, double* __restrict hyst) {
  for (Index e = 0; e < n; ++e) {
    force[e] += offset[e];
    hyst[e] = q[e] / k[e];
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ADJOIN_KERNEL(ret, name, params, args)        \
  ret name##_base params { return name##_body args; } \
  __attribute__((target("avx2"))) ret name##_avx2 params { return name##_body args; }
#define ADJOIN_HAVE_AVX2 1
#else
#define ADJOIN_KERNEL(ret, name, params, args) \
  ret name##_base params { return name##_body args; }
#endif

ADJOIN_KERNEL(void, chain_drifts, (Index count, const int* starts, const double* x, double* d), (count, starts, x, d))
ADJOIN_KERNEL(bool, test,
              (Index n, const double* k, const double* bound, const double* up, const double* d, double* flag, double* q),
              (n, k, bound, up, d, flag, q))
ADJOIN_KERNEL(void, chain_scatter, (Index count, const int* starts, const double* f, double* p), (count, starts, f, p))
ADJOIN_KERNEL(void, chain_storeys,
              (Index n, const double* offset, const double* q, const double* k, double* force, double* hyst),
              (n, offset, q, k, force, hyst))
#undef ADJOIN_KERNEL

const BilinearKernels kBaseline{&chain_drifts_base, &test_base, &chain_scatter_base, &chain_storeys_base};
#ifdef ADJOIN_HAVE_AVX2
const BilinearKernels kAvx2{&chain_drifts_avx2, &test_avx2, &chain_scatter_avx2, &chain_storeys_avx2};
#endif

}  // namespace

const BilinearKernels& baseline_bilinear_kernels() { return kBaseline; }

const BilinearKernels& bilinear_kernels() {
#ifdef ADJOIN_HAVE_AVX2
  static const BilinearKernels& chosen = __builtin_cpu_supports("avx2") ? kAvx2 : kBaseline;
  return chosen;
#else
  return kBaseline;
#endif
}

void bilinear_drifts(const BilinearKernels& kernels, const BilinearLayout& layout, const double* x, double* d) {
  if (layout.chains) {
    kernels.chain_drifts(static_cast<Index>(layout.chain_starts.size()) - 1, layout.chain_starts.data(), x, d);
    return;
  }
  for (int e = 0; e < layout.size(); ++e) d[e] = x[layout.i[e]] - (layout.j[e] >= 0 ? x[layout.j[e]] : 0.0);
}

void bilinear_scatter(const BilinearKernels& kernels, const BilinearLayout& layout, const double* f, double* p) {
  if (layout.chains) {
    kernels.chain_scatter(static_cast<Index>(layout.chain_starts.size()) - 1, layout.chain_starts.data(), f, p);
    return;
  }
  for (int e = 0; e < layout.size(); ++e) {  // (as Pair::add)
    if (layout.i[e] >= 0) p[layout.i[e]] += f[e];
    if (layout.j[e] >= 0) p[layout.j[e]] -= f[e];
  }
}

}  // namespace adjoin::detail
