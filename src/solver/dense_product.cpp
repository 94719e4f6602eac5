#include "dense_product.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define ADJOIN_AVX_PRODUCT 1
#endif

namespace adjoin::detail {
namespace {

// Eigen splits its sums into blocks of columns from 128 columns on; below, one sum per row.
constexpr Eigen::Index kEigenBlockColumns = 128;

#ifdef ADJOIN_AVX_PRODUCT
// Multiplies and adds separately, as Eigen's baseline kernel does (no fused multiply-add: that
// rounds once, not twice, and would change the sums).
// The column-major a has leading dimension `stride`.
[[gnu::always_inline]] __attribute__((target("avx"))) inline void product_avx_body(const double* a, Eigen::Index stride,
                                                                                     Eigen::Index rows, Eigen::Index cols,
                                                                                     const double* x, double* y) {
  Eigen::Index i = 0;
  for (; i + 16 <= rows; i += 16) {
    __m256d c0 = _mm256_setzero_pd(), c1 = _mm256_setzero_pd(), c2 = _mm256_setzero_pd(), c3 = _mm256_setzero_pd();
    for (Eigen::Index j = 0; j < cols; ++j) {
      const double* col = a + j * stride + i;
      const __m256d b = _mm256_set1_pd(x[j]);
      c0 = _mm256_add_pd(c0, _mm256_mul_pd(_mm256_loadu_pd(col), b));
      c1 = _mm256_add_pd(c1, _mm256_mul_pd(_mm256_loadu_pd(col + 4), b));
      c2 = _mm256_add_pd(c2, _mm256_mul_pd(_mm256_loadu_pd(col + 8), b));
      c3 = _mm256_add_pd(c3, _mm256_mul_pd(_mm256_loadu_pd(col + 12), b));
    }
    _mm256_storeu_pd(y + i, c0);
    _mm256_storeu_pd(y + i + 4, c1);
    _mm256_storeu_pd(y + i + 8, c2);
    _mm256_storeu_pd(y + i + 12, c3);
  }
  for (; i + 4 <= rows; i += 4) {
    __m256d c0 = _mm256_setzero_pd();
    for (Eigen::Index j = 0; j < cols; ++j) c0 = _mm256_add_pd(c0, _mm256_mul_pd(_mm256_loadu_pd(a + j * stride + i), _mm256_set1_pd(x[j])));
    _mm256_storeu_pd(y + i, c0);
  }
  if (i < rows) {
    // The last 1 to 3 rows in one register too, its other lanes masked off (neither read nor
    // written): each lane sums its row in the same order as a scalar loop, so the same bits,
    // for a building's few floors in a quarter of the scalar loop's instructions.
    // (The mask: `left` lanes of all ones, read from a table.)
    alignas(32) static constexpr long long kLanes[8] = {-1, -1, -1, -1, 0, 0, 0, 0};
    const __m256i mask = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kLanes + 4 - (rows - i)));
    __m256d c0 = _mm256_setzero_pd();
    for (Eigen::Index j = 0; j < cols; ++j)
      c0 = _mm256_add_pd(c0, _mm256_mul_pd(_mm256_maskload_pd(a + j * stride + i, mask), _mm256_set1_pd(x[j])));
    _mm256_maskstore_pd(y + i, mask, c0);
  }
}
__attribute__((target("avx"))) void product_avx(const double* a, Eigen::Index stride, Eigen::Index rows, Eigen::Index cols,
                                                const double* x, double* y) {
  product_avx_body(a, stride, rows, cols, x, y);
}
// Rows 0 .. rows - 1 into top, rows .. 2 rows - 1 into bottom: one call for both halves.
__attribute__((target("avx"))) void product_avx_halves(const double* a, Eigen::Index stride, Eigen::Index rows, Eigen::Index cols,
                                                       const double* x, double* top, double* bottom) {
  product_avx_body(a, stride, rows, cols, x, top);
  product_avx_body(a + rows, stride, rows, cols, x, bottom);
}
#endif

// One or two rows (a building of one floor; below Eigen's blocks of columns): plain loops, each y_i summed from 0 over the
// columns in order, as the lanes above and Eigen sum it (a call to the vector kernel and its
// masked lanes cost more than these few products).
constexpr Eigen::Index kSmallRows = 2;
void product_small(const double* a, Eigen::Index stride, Eigen::Index rows, Eigen::Index cols, const double* x, double* y) {
  for (Eigen::Index i = 0; i < rows; ++i) {
    double sum = 0.0;
    for (Eigen::Index j = 0; j < cols; ++j) sum += a[j * stride + i] * x[j];
    y[i] = sum;
  }
}

// Eigen's product, out of line: inlined into apply() its set-up (six saved registers and a
// stack frame) was paid by every call, the AVX kernel's too (35 instructions a call).
[[gnu::noinline]] void product_eigen(const Eigen::MatrixXd& a, const double* x, double* y, Eigen::Index first,
                                     Eigen::Index rows) {
  Eigen::Map<Eigen::VectorXd>(y, rows).noalias() = a.middleRows(first, rows) * Eigen::Map<const Eigen::VectorXd>(x, a.cols());
}

}  // namespace

DenseProduct::DenseProduct(Eigen::MatrixXd a) : a_(std::move(a)) {
#ifdef ADJOIN_AVX_PRODUCT
  wide_ = a_.cols() < kEigenBlockColumns && __builtin_cpu_supports("avx");
#endif
}

void DenseProduct::apply(const double* x, double* y, Eigen::Index first, Eigen::Index rows) const {
  if (rows <= kSmallRows && a_.cols() < kEigenBlockColumns) {
    product_small(a_.data() + first, a_.rows(), rows, a_.cols(), x, y);
    return;
  }
#ifdef ADJOIN_AVX_PRODUCT
  if (wide_) {
    product_avx(a_.data() + first, a_.rows(), rows, a_.cols(), x, y);
    return;
  }
#endif
  product_eigen(a_, x, y, first, rows);
}

void DenseProduct::apply_halves_any(const double* x, double* top, double* bottom) const {
  const Eigen::Index rows = a_.rows() / 2;
  if (rows <= kSmallRows && a_.cols() < kEigenBlockColumns) {
    product_small(a_.data(), a_.rows(), rows, a_.cols(), x, top);
    product_small(a_.data() + rows, a_.rows(), rows, a_.cols(), x, bottom);
    return;
  }
#ifdef ADJOIN_AVX_PRODUCT
  if (wide_) {
    product_avx_halves(a_.data(), a_.rows(), rows, a_.cols(), x, top, bottom);
    return;
  }
#endif
  product_eigen(a_, x, top, 0, rows);
  product_eigen(a_, x, bottom, rows, rows);
}

}  // namespace adjoin::detail
