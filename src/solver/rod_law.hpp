#pragma once
// A rod's constitutive law discretised by a convolution quadrature (internal to the solver).
//
//     f + tau_f D^g f = k (x + tau_x D^g x),   D^g z(t_m) ~ h^{-g} sum_j w_j z_{m-j}
//
// solved for the current force: with y = k tau_x x - tau_f f (one history channel),
//
//     f_m = [k (1 + tau_x w_0 h^{-g}) x_m + h^{-g} (sum_{j>=1} w_j y_{m-j} + extra)] /
//           (1 + tau_f w_0 h^{-g})
//
// so f_m = stiffness() * x_m + offset(extra): affine in x_m, which lets implicit schemes fold
// the rod into an effective stiffness. An elastic rod is f = k x with no history at all.
#include <cmath>
#include <memory>
#include <vector>

#include "adjoin/fractional/history.hpp"
#include "adjoin/structure/parameters.hpp"

namespace adjoin::detail {

class RodLaw {
 public:
  // `weights` w_0..w_N of the quadrature for this rod's order (ignored for elastic rods).
  RodLaw(const Rod& rod, double k, double h, HistoryEngine engine, std::vector<double> weights)
      : RodLaw(rod, k, h, weights.empty() ? 1.0 : weights[0], nullptr) {
    if (!elastic_) history_ = make_history(engine, std::move(weights));  // after w0 was read
  }
  // The same with the history made by the caller (the soe engine is made from the rule and
  // order, not from the weights); w0 = the quadrature's first weight.
  RodLaw(const Rod& rod, double k, double h, double w0, std::unique_ptr<ConvolutionHistory> history)
      : k_(k), elastic_(rod.elastic), tau_x_(rod.tau_x), tau_f_(rod.tau_f), history_(std::move(history)) {
    if (elastic_) { stiffness_ = k; return; }
    const double hg = std::pow(h, -rod.order);
    denominator_ = 1.0 + tau_f_ * w0 * hg;
    stiffness_ = effective_stiffness(rod, k, h, w0);
    history_scale_ = hg / denominator_;
  }

  // The stiffness() of a law with these parameters, whose weights begin with w0 (a model's
  // assembly needs it before the laws, which hold the run's history, exist).
  static double effective_stiffness(const Rod& rod, double k, double h, double w0) {
    if (rod.elastic) return k;
    const double hg = std::pow(h, -rod.order);
    return k * (1.0 + rod.tau_x * w0 * hg) / (1.0 + rod.tau_f * w0 * hg);
  }

  bool elastic() const { return elastic_; }
  // df_m/dx_m: the instantaneous (effective) stiffness at this step size.
  double stiffness() const { return stiffness_; }
  // f_m - stiffness() x_m, given any extra history terms (starting corrections).
  double offset(double extra = 0.0) const {
    return elastic_ ? 0.0 : history_scale_ * (history_->lag_sum() + extra);
  }
  double force(double x, double extra = 0.0) const { return stiffness_ * x + offset(extra); }
  // Records (x_m, f_m) in the history; call once per step, in order.
  void commit(double x, double f) {
    if (!elastic_) history_->push(k_ * tau_x_ * x - tau_f_ * f);
  }
  // The law's numbers for a caller that keeps the history elsewhere (fractional/history_set.hpp):
  // offset() = history_scale() (lag sum + extra); commit pushes value_of_x() x - value_of_f() f.
  double history_scale() const { return history_scale_; }
  double value_of_x() const { return k_ * tau_x_; }
  double value_of_f() const { return tau_f_; }
  std::size_t bytes() const { return elastic_ ? 0 : history_->bytes(); }
  double weight_error() const { return elastic_ ? 0.0 : history_->weight_error(); }
  std::size_t modes() const { return elastic_ ? 0 : history_->modes(); }

 private:
  double k_;
  bool elastic_;
  double tau_x_, tau_f_;
  std::unique_ptr<ConvolutionHistory> history_;
  double stiffness_ = 0.0, denominator_ = 1.0, history_scale_ = 0.0;
};

// A rod's law with its history over `count` lags of the weights of `rule` (tolerance: the soe
// engine's, see soe_history.hpp).
inline RodLaw make_rod_law(const Rod& rod, double k, double h, HistoryEngine engine, WeightRule rule, std::size_t count,
                           double tolerance) {
  if (rod.elastic) return RodLaw(rod, k, h, 1.0, nullptr);
  if (engine == HistoryEngine::soe)
    return RodLaw(rod, k, h, convolution_weights(rule, rod.order, 1)[0], make_history(engine, rule, rod.order, count, tolerance));
  return RodLaw(rod, k, h, engine, convolution_weights(rule, rod.order, count));
}

}  // namespace adjoin::detail
