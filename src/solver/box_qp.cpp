#include "box_qp.hpp"

#include <algorithm>
#include <cmath>

namespace adjoin::detail {
namespace {

double bound_of(DamperState s, double f) { return s == DamperState::slip_positive ? f : -f; }

}  // namespace

BoxQpResult solve_box_qp(const Eigen::MatrixXd& s, const Eigen::VectorXd& w0, const Eigen::VectorXd& limit,
                         const std::vector<DamperState>& hint) {
  const int n = static_cast<int>(w0.size());
  BoxQpResult r;
  r.state = hint.size() == static_cast<std::size_t>(n) ? hint : std::vector<DamperState>(n, DamperState::stick);
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(limit[k])) r.state[k] = DamperState::stick;  // held stuck: never at a bound
  r.q = Eigen::VectorXd::Zero(n);
  // (A limit may be infinite: a damper held stuck.)
  double scale = w0.cwiseAbs().maxCoeff() + 1e-300;
  for (int k = 0; k < n; ++k)
    if (std::isfinite(limit[k])) scale += s(k, k) * limit[k];
  const double tol = 1e-13 * scale;
  for (r.iterations = 1; r.iterations <= 20 + 4 * n; ++r.iterations) {
    std::vector<int> stuck;
    for (int k = 0; k < n; ++k) {
      if (r.state[k] == DamperState::stick) stuck.push_back(k);
      else r.q[k] = bound_of(r.state[k], limit[k]);
    }
    if (!stuck.empty()) {
      const int m = static_cast<int>(stuck.size());
      Eigen::MatrixXd a(m, m);
      Eigen::VectorXd b(m);
      for (int i = 0; i < m; ++i) {
        b[i] = w0[stuck[i]];
        for (int k = 0; k < n; ++k)
          if (r.state[k] != DamperState::stick) b[i] -= s(stuck[i], k) * r.q[k];
        for (int j = 0; j < m; ++j) a(i, j) = s(stuck[i], stuck[j]);
      }
      const Eigen::VectorXd x = a.ldlt().solve(b);
      for (int i = 0; i < m; ++i) r.q[stuck[i]] = x[i];
    }
    r.w = w0 - s * r.q;
    // The worst violation: a stuck force beyond its limit, or a slip against its velocity.
    int worst = -1;
    double amount = 0.0;
    for (int k = 0; k < n; ++k) {
      double v = 0.0;
      if (r.state[k] == DamperState::stick) v = (std::abs(r.q[k]) - limit[k]) * 1.0;
      else if (r.state[k] == DamperState::slip_positive) v = -r.w[k];
      else v = r.w[k];
      // Compare forces and velocities on one scale: a velocity v corresponds to a force v / S_kk.
      if (r.state[k] != DamperState::stick) v /= s(k, k);
      if (v > amount + tol / s(k, k)) {
        amount = v;
        worst = k;
      }
    }
    if (worst < 0) return r;
    if (r.state[worst] == DamperState::stick)
      r.state[worst] = r.q[worst] > 0.0 ? DamperState::slip_positive : DamperState::slip_negative;
    else
      r.state[worst] = DamperState::stick;
  }
  // Cycling (not seen): projected Gauss-Seidel to convergence from the last iterate.
  for (int sweep = 0; sweep < 100000; ++sweep) {
    double change = 0.0;
    for (int k = 0; k < n; ++k) {
      const double residual = w0[k] - s.row(k).dot(r.q) + s(k, k) * r.q[k];
      const double next = std::clamp(residual / s(k, k), -limit[k], limit[k]);
      change = std::max(change, std::abs(next - r.q[k]));
      r.q[k] = next;
    }
    if (change <= 1e-15 * (scale / s.diagonal().minCoeff())) break;
  }
  r.w = w0 - s * r.q;
  for (int k = 0; k < n; ++k)
    r.state[k] = std::abs(r.q[k]) < limit[k] * (1 - 1e-12) ? DamperState::stick
                 : (r.q[k] > 0.0 ? DamperState::slip_positive : DamperState::slip_negative);
  return r;
}

}  // namespace adjoin::detail
