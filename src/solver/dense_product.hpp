#pragma once
// y = A x for a column-major A, internal to the structure step: its one dense product per step
// ([A^-1; C A^-1] times the step's right-hand side). Each y_i is summed over the columns in
// order, from 0, as Eigen's matrix-vector product sums it below 128 columns, so the result is
// Eigen's bit for bit; it runs 4 rows at a time where the processor has AVX (Eigen, built for
// the baseline x86-64, uses 2), which halves the product's time. Larger products go to Eigen.
#include <Eigen/Dense>

namespace adjoin::detail {

class DenseProduct {
 public:
  DenseProduct() = default;
  explicit DenseProduct(Eigen::MatrixXd a);
  // y = A x (y not x; y sized A.rows(), x A.cols()).
  void apply(const double* x, double* y) const { apply(x, y, 0, a_.rows()); }
  // The rows first .. first + rows - 1 of A x, into y[0 .. rows - 1].
  void apply(const double* x, double* y, Eigen::Index first, Eigen::Index rows) const;
  // The two halves of A x (A has an even number of rows) into top and bottom, in one call:
  // apply(x, top, 0, r) and apply(x, bottom, r, r) for r = rows / 2, the same numbers.
  void apply_halves(const double* x, double* top, double* bottom) const {
    if (a_.rows() == 2 && a_.cols() == 1) {  // (a building of one floor: two products, inline)
      top[0] = 0.0 + a_(0, 0) * x[0];
      bottom[0] = 0.0 + a_(1, 0) * x[0];
      return;
    }
    apply_halves_any(x, top, bottom);
  }
  const Eigen::MatrixXd& matrix() const { return a_; }

 private:
  void apply_halves_any(const double* x, double* top, double* bottom) const;
  Eigen::MatrixXd a_;
  bool wide_ = false;  // the AVX kernel applies
};

}  // namespace adjoin::detail
