#pragma once
// A shear building's stiffness matrix in band form (internal to the structure stepper).
#include <Eigen/Dense>
#include <algorithm>
#include <cstdlib>
#include <vector>

#include "step_kernels.hpp"

namespace adjoin::detail {

// A stiffness matrix as a shear building's is: tridiagonal (the storeys), plus the few entries
// of links between the buildings' floors. Its product is three vector passes over the
// diagonals, O(n), instead of a sparse product's per-row loops of about three entries each
// (index loads, no vectors) or a dense product's O(n^2). Each row is summed in the order of its
// columns, as a dense product sums it (the links' entries left of the band first, those right
// of it last), so the products equal the dense ones bit for bit.
class Banded {
 public:
  Banded() = default;
  explicit Banded(const Eigen::MatrixXd& k) : diag_(k.diagonal()) {
    const Eigen::Index n = k.rows();
    if (n > 1) {
      sub_ = k.diagonal(-1);
      sup_ = k.diagonal(1);
    }
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = 0; i < n; ++i)
        if (k(i, j) != 0.0 && std::abs(i - j) > 1) (j < i ? before_ : after_).push_back({static_cast<int>(i), static_cast<int>(j), k(i, j)});
    for (const Entry& e : after_) after_rows_.push_back(e.i);
    std::sort(after_rows_.begin(), after_rows_.end());
    after_rows_.erase(std::unique(after_rows_.begin(), after_rows_.end()), after_rows_.end());
  }
  // The usual case: no entries left of the band and more than two rows, where a product is
  // one pass over the band (solver/step_kernels) and then the entries right of it.
  bool banded() const { return before_.empty() && diag_.size() > 2; }
  Tridiagonal diagonals() const { return {sub_.data(), diag_.data(), sup_.data()}; }
  // p += the entries right of the band times x, row by row in column order; `rows` lists them.
  void add_after(const Eigen::VectorXd& x, Eigen::VectorXd& p) const {
    for (const Entry& e : after_) p[e.i] += e.value * x[e.j];
  }
  const std::vector<int>& after_rows() const { return after_rows_; }
  // p = K x (p not x).
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& p) const {
    const Eigen::Index n = x.size();
    if (n == 2) {  // (the two-block scene's: apply_any's sums, written out; never an entry off the band)
      p[0] = (0.0 + diag_[0] * x[0]) + sup_[0] * x[1];
      p[1] = (0.0 + sub_[0] * x[0]) + diag_[1] * x[1];
      return;
    }
    apply_any(x, p);
  }

 private:
  // (Out of line: the two floors' path above pays none of its set-up.)
  [[gnu::noinline]] void apply_any(const Eigen::VectorXd& x, Eigen::VectorXd& p) const {
    const Eigen::Index n = x.size();
    if (banded()) {
      step_kernels().band(n, diagonals(), x.data(), p.data());
      add_after(x, p);
      return;
    }
    // (Plain loops: for one or two floors Eigen's dynamic-size set-up would be most of the
    // work. Each row is summed in column order, as above.)
    double* pd = p.data();
    const double* xd = x.data();
    for (Eigen::Index i = 0; i < n; ++i) pd[i] = 0.0;
    for (const Entry& e : before_) pd[e.i] += e.value * xd[e.j];
    for (Eigen::Index i = 1; i < n; ++i) pd[i] += sub_[i - 1] * xd[i - 1];
    for (Eigen::Index i = 0; i < n; ++i) pd[i] += diag_[i] * xd[i];
    for (Eigen::Index i = 0; i + 1 < n; ++i) pd[i] += sup_[i] * xd[i + 1];
    for (const Entry& e : after_) pd[e.i] += e.value * xd[e.j];
  }
 public:
  // (K x)_k alone, summed as apply() sums it; it reads x at columns() of k.
  double row(int k, const Eigen::VectorXd& x) const {
    const int n = static_cast<int>(diag_.size());
    double p = 0.0;
    for (const Entry& e : before_)
      if (e.i == k) p += e.value * x[e.j];
    if (k > 0) p += sub_[k - 1] * x[k - 1];
    p += diag_[k] * x[k];
    if (k < n - 1) p += sup_[k] * x[k + 1];
    for (const Entry& e : after_)
      if (e.i == k) p += e.value * x[e.j];
    return p;
  }
  std::vector<int> columns(int k) const {
    const int n = static_cast<int>(diag_.size());
    std::vector<int> out{k};
    if (k > 0) out.push_back(k - 1);
    if (k < n - 1) out.push_back(k + 1);
    for (const auto* list : {&before_, &after_})
      for (const Entry& e : *list)
        if (e.i == k) out.push_back(e.j);
    return out;
  }

 private:
  struct Entry {
    int i, j;
    double value;
  };
  Eigen::VectorXd diag_, sub_, sup_;  // K(i, i), K(i + 1, i), K(i, i + 1)
  std::vector<Entry> before_, after_;  // off the band, left and right of it, in column order
  std::vector<int> after_rows_;
};

}  // namespace adjoin::detail
