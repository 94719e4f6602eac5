#include "box_qp.hpp"

#include <algorithm>
#include <cmath>

namespace adjoin::detail {
namespace {

double bound_of(DamperState s, double f) { return s == DamperState::slip_positive ? f : -f; }

}  // namespace

BoxQpResult solve_box_qp(const Eigen::MatrixXd& s, const Eigen::VectorXd& w0, const Eigen::VectorXd& limit,
                         const std::vector<DamperState>& hint) {
  BoxQp qp(s);
  return qp.solve(w0, limit, hint);
}

SubsetInverses::System& SubsetInverses::find(const std::vector<int>& set) {
  auto it = cache_.find(set);
  if (it == cache_.end()) {
    const int m = static_cast<int>(set.size());
    Eigen::MatrixXd a(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) a(i, j) = s_(set[i], set[j]);
    System entry;
    // (A negative diagonal: a slipping bilinear element's row, whose compliance is negative;
    // the set's matrix is then symmetric indefinite, and LU with partial pivoting inverts it.)
    if ((a.diagonal().array() < 0.0).any()) entry.inverse = a.partialPivLu().inverse();
    else entry.inverse = a.ldlt().solve(Eigen::MatrixXd::Identity(m, m));
    entry.b.resize(m);
    entry.x.resize(m);
    it = cache_.emplace(set, std::move(entry)).first;
  }
  last_key_ = &it->first;
  last_ = &it->second;
  return it->second;
}

BoxQp::BoxQp(Eigen::MatrixXd s) : inverses_(std::move(s)) {}

void BoxQp::solve_held(const Eigen::VectorXd& w0, const std::vector<char>& held, const Eigen::VectorXd& fixed,
                       Eigen::VectorXd* q) {
  const int n = static_cast<int>(w0.size());
  held_.clear();
  for (int k = 0; k < n; ++k)
    if (held[k]) held_.push_back(k);
  double* qd = q->data();
  const double* fd = fixed.data();
  std::copy_n(fd, n, qd);
  if (held_.empty()) return;
  SubsetInverses::System& sys = inverses_.of(held_);
  const Eigen::MatrixXd& s = inverses_.matrix();
  // (the fixed forces that are not zero: with bilinear elements most are)
  fixed_.clear();
  for (int k = 0; k < n; ++k)
    if (!held[k] && fd[k] != 0.0) fixed_.push_back(k);
  for (std::size_t i = 0; i < held_.size(); ++i) {
    const int h = held_[i];
    double b = w0[h];
    for (int k : fixed_) b -= s(h, k) * fd[k];
    sys.b[static_cast<Eigen::Index>(i)] = b;
  }
  sys.solve();
  for (std::size_t i = 0; i < held_.size(); ++i) qd[held_[i]] = sys.x[static_cast<Eigen::Index>(i)];
}

const BoxQpResult& BoxQp::solve(const Eigen::VectorXd& w0, const Eigen::VectorXd& limit,
                                const std::vector<DamperState>& hint) {
  const Eigen::MatrixXd& s = inverses_.matrix();
  const int n = static_cast<int>(w0.size());
  BoxQpResult& r = r_;
  if (hint.size() == static_cast<std::size_t>(n)) r.state = hint;
  else r.state.assign(n, DamperState::stick);
  r.iterations = 0;
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(limit[k])) r.state[k] = DamperState::stick;  // held stuck: never at a bound
  r.q.setZero(n);
  r.w.resize(n);
  // (A limit may be infinite: a damper held stuck.)
  double scale = w0.cwiseAbs().maxCoeff() + 1e-300;
  for (int k = 0; k < n; ++k)
    if (std::isfinite(limit[k])) scale += s(k, k) * limit[k];
  const double tol = 1e-13 * scale;
  std::vector<int>& stuck = stuck_;
  for (r.iterations = 1; r.iterations <= 20 + 4 * n; ++r.iterations) {
    stuck.clear();
    for (int k = 0; k < n; ++k) {
      if (r.state[k] == DamperState::stick) stuck.push_back(k);
      else r.q[k] = bound_of(r.state[k], limit[k]);
    }
    if (!stuck.empty()) {
      const int m = static_cast<int>(stuck.size());
      SubsetInverses::System& sys = inverses_.of(stuck);
      for (int i = 0; i < m; ++i) {
        sys.b[i] = w0[stuck[i]];
        for (int k = 0; k < n; ++k)
          if (r.state[k] != DamperState::stick) sys.b[i] -= s(stuck[i], k) * r.q[k];
      }
      sys.solve();
      for (int i = 0; i < m; ++i) r.q[stuck[i]] = sys.x[i];
    }
    r.w.noalias() = w0 - s * r.q;
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
