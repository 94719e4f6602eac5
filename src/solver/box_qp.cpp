#include "box_qp.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace adjoin::detail {
namespace {

double bound_of(DamperState s, double f) { return s == DamperState::slip_positive ? f : -f; }

}  // namespace

BoxQpResult solve_box_qp(const Eigen::MatrixXd& s, const Eigen::VectorXd& w0, const Eigen::VectorXd& limit,
                         const std::vector<DamperState>& hint) {
  BoxQp qp(s);
  return qp.solve(w0, limit, hint);
}

Eigen::MatrixXd SubsetInverses::invert(const std::vector<int>& set) const {
  const int m = static_cast<int>(set.size());
  Eigen::MatrixXd a(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) a(i, j) = s_(set[i], set[j]);
  // (A negative diagonal: a slipping bilinear element's row, whose compliance is negative;
  // the set's matrix is then symmetric indefinite, and LU with partial pivoting inverts it.)
  if ((a.diagonal().array() < 0.0).any()) return a.partialPivLu().inverse();
  return a.ldlt().solve(Eigen::MatrixXd::Identity(m, m));
}

bool SubsetInverses::update_from_last(const std::vector<int>& set, Eigen::MatrixXd* inverse) const {
  // (A small set is updated only when it holds a slipping bilinear element's row, negative on
  // the diagonal and after the dampers': the dampers' own small systems keep the inversion's
  // rounding.)
  const bool small = set.size() < kMinUpdateSize && !(!set.empty() && s_(set.back(), set.back()) < 0.0);
  if (last_ == nullptr || last_->generation >= kMaxGeneration || small || last_key_->empty()) return false;
  // The elements removed and added, each ascending (a merge of the two sorted sets).
  const std::vector<int>& last = *last_key_;
  int removed[kMaxChanges], added[kMaxChanges];
  int n_removed = 0, n_added = 0;
  for (std::size_t a = 0, b = 0; a < last.size() || b < set.size();) {
    const bool only_last = b == set.size() || (a < last.size() && last[a] < set[b]);
    const bool only_set = !only_last && (a == last.size() || set[b] < last[a]);
    if (!only_last && !only_set) {
      ++a;
      ++b;
      continue;
    }
    if (n_removed + n_added == kMaxChanges) return false;
    if (only_last) removed[n_removed++] = last[a++];
    else added[n_added++] = set[b++];
  }
  // The inverse in work_[0] and work_[1] by turns (column-major, m x m), allocated once.
  // A pivot below this fraction of its element's own scale loses digits: invert instead.
  constexpr double kSmallPivot = 1e-6;
  std::vector<int>& key = key_;
  key.assign(last.begin(), last.end());
  Eigen::Index m = last_->inverse.rows();
  const auto most = static_cast<std::size_t>(m + n_added);
  for (std::vector<double>& w : work_)
    if (w.size() < most * most) w.resize(most * most);
  if (c_.size() < most) c_.resize(most);
  if (u_.size() < most) u_.resize(most);
  double* w = work_[0].data();
  double* next = work_[1].data();
  std::copy_n(last_->inverse.data(), m * m, w);
  for (int k = 0; k < n_removed; ++k) {
    // Removing element r (at p): the Schur complement of W's p-th pivot.
    const int r = removed[k];
    const auto p = static_cast<Eigen::Index>(std::lower_bound(key.begin(), key.end(), r) - key.begin());
    const double pivot = w[p + p * m];
    if (!(std::abs(pivot * s_(r, r)) > kSmallPivot)) return false;
    const Eigen::Index mm = m - 1;
    for (Eigen::Index j = 0, jj = 0; j <= mm; ++j) {
      if (j == p) continue;
      for (Eigen::Index i = 0, ii = 0; i <= mm; ++i) {
        if (i == p) continue;
        next[ii++ + jj * mm] = w[i + j * m] - w[i + p * m] * w[p + j * m] / pivot;
      }
      ++jj;
    }
    std::swap(w, next);
    m = mm;
    key.erase(key.begin() + p);
  }
  for (int k = 0; k < n_added; ++k) {
    // Adding element a (at p): the bordered inverse, with the Schur complement d - c'W c.
    const int a = added[k];
    const auto p = static_cast<Eigen::Index>(std::lower_bound(key.begin(), key.end(), a) - key.begin());
    for (Eigen::Index i = 0; i < m; ++i) c_[static_cast<std::size_t>(i)] = s_(key[static_cast<std::size_t>(i)], a);
    const Eigen::Map<const Eigen::VectorXd> c(c_.data(), m);
    Eigen::Map<Eigen::VectorXd> u(u_.data(), m);
    u.noalias() = Eigen::Map<const Eigen::MatrixXd>(w, m, m) * c;
    const double schur = s_(a, a) - c.dot(u);
    if (!(std::abs(schur) > kSmallPivot * std::abs(s_(a, a)))) return false;
    const Eigen::Index mp = m + 1;
    auto at = [p](Eigen::Index i) { return i < p ? i : i + 1; };
    for (Eigen::Index j = 0; j < m; ++j)
      for (Eigen::Index i = 0; i < m; ++i) next[at(i) + at(j) * mp] = w[i + j * m] + u[i] * u[j] / schur;
    for (Eigen::Index i = 0; i < m; ++i) next[at(i) + p * mp] = next[p + at(i) * mp] = -u[i] / schur;
    next[p + p * mp] = 1.0 / schur;
    std::swap(w, next);
    m = mp;
    key.insert(key.begin() + p, a);
  }
  *inverse = Eigen::Map<const Eigen::MatrixXd>(w, m, m);
  return true;
}

SubsetInverses::System& SubsetInverses::find(const std::vector<int>& set) {
  auto it = cache_.find(set);
  if (it == cache_.end()) {
    const int m = static_cast<int>(set.size());
    System entry;
    if (update_from_last(set, &entry.inverse)) {
      entry.generation = last_->generation + 1;
    } else {
      entry.inverse = invert(set);
      entry.generation = 0;
    }
    entry.b.resize(m);
    entry.x.resize(m);
    it = cache_.emplace(set, std::move(entry)).first;
  }
  before_key_ = last_key_;
  before_ = last_;
  last_key_ = &it->first;
  last_ = &it->second;
  return it->second;
}

BoxQp::BoxQp(Eigen::MatrixXd s) : inverses_(std::move(s)) {}

void BoxQp::solve_held(const Eigen::VectorXd& w0, const std::vector<char>& held, const Eigen::VectorXd& fixed,
                       Eigen::VectorXd* q, const std::vector<int>* candidates) {
  const int n = static_cast<int>(w0.size());
  double* qd = q->data();
  const double* fd = fixed.data();
  if (n == 1 && candidates == nullptr) {  // one damper: held, S_00^-1 w0 (as below); else fixed
    qd[0] = held[0] != 0 ? inverses_.single() * w0[0] : fd[0];
    return;
  }
  std::copy_n(fd, n, qd);
  // The held unknowns, and the fixed forces that are not zero (with bilinear elements most
  // are), listed in one pass without a branch (scratch_ holds n + 1 places for each list).
  scratch_.resize(2 * (static_cast<std::size_t>(n) + 1));
  int* held_list = scratch_.data();
  int* fixed_list = held_list + n + 1;
  int n_held = 0, n_fixed = 0;
  auto consider = [&](int k) {
    const int is_held = held[k] != 0 ? 1 : 0;
    held_list[n_held] = k;
    fixed_list[n_fixed] = k;
    n_held += is_held;
    n_fixed += (1 - is_held) & (fd[k] != 0.0 ? 1 : 0);
  };
  if (candidates != nullptr) {
    for (int k : *candidates) consider(k);
  } else {
    for (int k = 0; k < n; ++k) consider(k);
  }
  if (n_held == 0) return;
  held_.assign(held_list, held_list + n_held);
  fixed_.assign(fixed_list, fixed_list + n_fixed);
  SubsetInverses::System& sys = inverses_.of(held_);
  const Eigen::MatrixXd& s = inverses_.matrix();
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
