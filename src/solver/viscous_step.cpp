#include "viscous_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace adjoin::detail {
namespace {

double sign(double w) { return w > 0.0 ? 1.0 : (w < 0.0 ? -1.0 : 0.0); }

// Below this |w_1 - w_0| / max(|w_0|, |w_1|) the mean is taken from its Taylor series about the
// midpoint (both ends on one side of zero, far from it): the difference quotient would lose
// digits to cancellation there, the series' next term is below rounding.
constexpr double kSeriesBelow = 1e-2;

// One element's scalar equation w + g Q(w) = b, increasing in w: Newton's method, each step
// kept inside a bracket that the residual's sign shrinks (bisection when Newton leaves it or
// its slope is infinite, at w = 0 for alpha < 1).
double solve_scalar(const ViscousLaw& law, double g, double b, double w0, bool end_force, double guess) {
  auto q_of = [&](double w) { return end_force ? law.force(w) : law.mean(w0, w); };
  auto slope_of = [&](double w) { return end_force ? law.slope(w) : law.mean_slope(w0, w); };
  // Q increases with w, so the root lies between b and b - g Q(b).
  const double qb = q_of(b);
  double lo = std::min(b, b - g * qb), hi = std::max(b, b - g * qb);
  if (lo == hi) return b;
  double w = std::clamp(guess, lo, hi);
  for (int it = 0; it < 300; ++it) {
    const double r = w + g * q_of(w) - b;
    if (r == 0.0) return w;
    (r > 0.0 ? hi : lo) = w;
    const double d = 1.0 + g * slope_of(w);
    double next = std::isfinite(d) ? w - r / d : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == w || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo), std::abs(hi))) return next;
    w = next;
  }
  return w;
}

}  // namespace

double ViscousLaw::force(double w) const { return c * std::pow(std::abs(w), alpha) * sign(w); }

double ViscousLaw::slope(double w) const {
  if (alpha == 1.0) return c;
  return w == 0.0 ? std::numeric_limits<double>::infinity() : c * alpha * std::pow(std::abs(w), alpha - 1.0);
}

double ViscousLaw::mean(double w0, double w1) const {
  const double d = w1 - w0, big = std::max(std::abs(w0), std::abs(w1));
  if (big == 0.0) return 0.0;
  if (std::abs(d) <= kSeriesBelow * big) {
    // F(m) + F''(m) d^2 / 24 + F''''(m) d^4 / 1920 (m the midpoint, |d / m| <= 2 %).
    const double m = 0.5 * (w0 + w1), am = std::abs(m), r2 = (d / am) * (d / am);
    const double a = alpha;
    return force(m) * (1.0 + a * (a - 1.0) * r2 / 24.0 + a * (a - 1.0) * (a - 2.0) * (a - 3.0) * r2 * r2 / 1920.0);
  }
  // The antiderivative of |w|^alpha sign w is |w|^(1+alpha) / (1 + alpha), even in w.
  const double p = 1.0 + alpha;
  return c * (std::pow(std::abs(w1), p) - std::pow(std::abs(w0), p)) / (p * d);
}

double ViscousLaw::mean_slope(double w0, double w1) const {
  const double d = w1 - w0, big = std::max(std::abs(w0), std::abs(w1));
  if (std::abs(d) <= kSeriesBelow * big || big == 0.0) return 0.5 * slope(0.5 * (w0 + w1));
  return (force(w1) - mean(w0, w1)) / d;
}

ViscousSolver::ViscousSolver(std::vector<ViscousLaw> laws) : laws_(std::move(laws)) {
  const auto nv = static_cast<Eigen::Index>(laws_.size());
  for (Eigen::VectorXd* v : {&r_, &r_try_, &w_try_, &q_try_, &slope_, &step_}) v->resize(nv);
  jacobian_.resize(nv, nv);
  lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(nv);
}

void ViscousSolver::forces(const Eigen::VectorXd& w0, bool end_force, const Eigen::VectorXd& w, Eigen::VectorXd& q) const {
  for (std::size_t k = 0; k < laws_.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    q[i] = end_force ? laws_[k].force(w[i]) : laws_[k].mean(w0[i], w[i]);
  }
}

// r = w + G q - w_tilde; its largest entry.
double ViscousSolver::residual(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w,
                               const Eigen::VectorXd& q, Eigen::VectorXd& r) const {
  r = w - w_tilde;
  r.noalias() += g * q;
  return r.cwiseAbs().maxCoeff();
}

bool ViscousSolver::solve(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w0, bool end_force,
                          Eigen::VectorXd& w1, Eigen::VectorXd& q) {
  const double tolerance = 1e-14 * (w_tilde.cwiseAbs().maxCoeff() + w0.cwiseAbs().maxCoeff());
  if (laws_.size() > 1 && newton(g, w_tilde, w0, end_force, w1, q, tolerance)) return true;
  return gauss_seidel(g, w_tilde, w0, end_force, w1, q, tolerance);
}

bool ViscousSolver::newton(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w0, bool end_force,
                           Eigen::VectorXd& w1, Eigen::VectorXd& q, double tolerance) {
  const auto nv = static_cast<Eigen::Index>(laws_.size());
  forces(w0, end_force, w1, q);
  double norm = residual(g, w_tilde, w1, q, r_);
  for (int it = 0; it < 30; ++it) {
    if (norm <= tolerance) return true;
    for (Eigen::Index k = 0; k < nv; ++k) {
      const auto& law = laws_[static_cast<std::size_t>(k)];
      slope_[k] = end_force ? law.slope(w1[k]) : law.mean_slope(w0[k], w1[k]);
      if (!std::isfinite(slope_[k])) return false;
    }
    jacobian_ = g * slope_.asDiagonal();
    jacobian_.diagonal().array() += 1.0;
    lu_.compute(jacobian_);
    step_ = lu_.solve(r_);
    w_try_ = w1 - step_;
    forces(w0, end_force, w_try_, q_try_);
    const double next = residual(g, w_tilde, w_try_, q_try_, r_try_);
    if (!(next < norm)) return false;  // (Gauss-Seidel takes over from the best iterate)
    w1.swap(w_try_);
    q.swap(q_try_);
    r_.swap(r_try_);
    norm = next;
  }
  return norm <= tolerance;
}

bool ViscousSolver::gauss_seidel(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w0,
                                 bool end_force, Eigen::VectorXd& w1, Eigen::VectorXd& q, double tolerance) {
  const auto nv = static_cast<Eigen::Index>(laws_.size());
  forces(w0, end_force, w1, q);
  for (int sweep = 0; sweep < 2000; ++sweep) {
    double change = 0.0;
    for (Eigen::Index k = 0; k < nv; ++k) {
      const auto& law = laws_[static_cast<std::size_t>(k)];
      const double b = w_tilde[k] - g.row(k).dot(q) + g(k, k) * q[k];
      const double w = solve_scalar(law, g(k, k), b, w0[k], end_force, w1[k]);
      change = std::max(change, std::abs(w - w1[k]));
      w1[k] = w;
      q[k] = end_force ? law.force(w) : law.mean(w0[k], w);
    }
    if (nv == 1 || change <= tolerance) return true;
  }
  return false;
}

}  // namespace adjoin::detail
