#pragma once
// Nonlinear viscous dampers in the structure step (internal to the solver): a dashpot device
// or link with F = c |w|^alpha sign w, 0 < alpha < 1 (alpha = 1 is the linear dashpot, which
// stays in C). Its force is not Lipschitz at w = 0, so the step solves for the force, not by
// a fixed point on the velocity, and needs no regularisation:
//
// Each element's step force Q (its impulse over the step / h) enters the step as a damper's
// does, v_n+1 = v_free - h A^-1 B_v' Q, so the elements' relative velocities at the step's
// end are w_1 = w~ - G Q, G = h B_v A^-1 B_v' (symmetric positive definite), w~ their
// velocities without their own step forces. Q is the exact mean of the law over the step for a
// relative velocity linear in time from w_0 to w_1 (trapezoidal steps),
//     Q = c (|w_1|^(1+alpha) - |w_0|^(1+alpha)) / ((1 + alpha) (w_1 - w_0)),
// which for alpha = 1 is the trapezoidal rule's (F_0 + F_1) / 2 and, unlike it, integrates
// the cusp of the force where w passes through zero (|t - t_0|^alpha) without an O(h^(1+alpha))
// error; it is the end force F(w_1) on a backward-Euler step. Q increases with w_1, so
// w_1 + G Q(w_1) = w~ has one solution, the minimum of a convex function: found by
// Gauss-Seidel over the elements, each a scalar monotone equation solved by Newton's method
// safeguarded by bisection (exact to rounding; no tolerance on the physics).
#include <Eigen/Dense>
#include <vector>

namespace adjoin::detail {

struct ViscousLaw {
  double c = 0.0, alpha = 1.0;
  double force(double w) const;                     // c |w|^alpha sign w
  double mean(double w0, double w1) const;          // over w linear in time from w0 to w1
  double mean_slope(double w0, double w1) const;    // d mean / d w1
  double slope(double w) const;                     // dF/dw (infinite at 0 for alpha < 1)
};

// Solves w1 + G Q(w1) = w_tilde for the elements' end velocities w1 (in: a first guess) and
// step forces q; `end_force`: the backward-Euler step's Q = F(w1). Newton's method on the whole
// system (J = I + G diag(Q'), a small dense LU), each iterate kept only if it lowers the
// residual; where it does not (near a turning velocity, where Q' is unbounded), Gauss-Seidel
// over the elements, each exact. Sized once: a solve allocates nothing.
class ViscousSolver {
 public:
  explicit ViscousSolver(std::vector<ViscousLaw> laws);
  // False if neither converged (never seen; the caller stops with the time).
  bool solve(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w0, bool end_force,
             Eigen::VectorXd& w1, Eigen::VectorXd& q);
  const std::vector<ViscousLaw>& laws() const { return laws_; }

 private:
  bool newton(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w0, bool end_force,
              Eigen::VectorXd& w1, Eigen::VectorXd& q, double tolerance);
  bool gauss_seidel(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w0, bool end_force,
                    Eigen::VectorXd& w1, Eigen::VectorXd& q, double tolerance);
  double residual(const Eigen::MatrixXd& g, const Eigen::VectorXd& w_tilde, const Eigen::VectorXd& w, const Eigen::VectorXd& q,
                  Eigen::VectorXd& r) const;
  void forces(const Eigen::VectorXd& w0, bool end_force, const Eigen::VectorXd& w, Eigen::VectorXd& q) const;

  std::vector<ViscousLaw> laws_;
  Eigen::VectorXd r_, r_try_, w_try_, q_try_, slope_, step_;
  Eigen::MatrixXd jacobian_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

}  // namespace adjoin::detail
