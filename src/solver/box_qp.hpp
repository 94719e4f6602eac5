#pragma once
// The friction dampers' step (SPEC §5, "the non-smooth step"), internal to the solver.
//
// With the link velocities at the end of a step affine in the dampers' step forces Q,
// w = w0 - S Q (S symmetric positive definite: the dampers' Delassus matrix), the set-valued
// law Q_k in F_k Sign(w_k) for every damper k is exactly the optimality condition of
//
//     minimise 1/2 Q'SQ - Q'w0   subject to  |Q_k| <= F_k,
//
// a strictly convex box-constrained quadratic problem with a unique solution. It is found by an
// active-set method: each damper is stuck (w_k = 0, Q_k free) or slipping (Q_k = +-F_k); the
// stuck forces solve the linear system of the stuck dampers; a stuck force beyond its limit
// starts to slip, a slip whose velocity opposes its force sticks; repeat. With one damper it
// is the closed form (stick if |w0| <= F S, else slip). Finite in practice; a projected
// Gauss-Seidel sweep finishes any case the active set cycles on (never seen in tests).
#include <Eigen/Dense>
#include <map>
#include <vector>

namespace adjoin::detail {

enum class DamperState { stick, slip_positive, slip_negative };

struct BoxQpResult {
  Eigen::VectorXd q;                 // the step forces
  Eigen::VectorXd w;                 // w0 - S q
  std::vector<DamperState> state;    // stuck (w = 0) or slipping in the direction of q
  int iterations = 0;
};

// `hint`: the states to start from (the last step's), or empty. A limit may be infinite (a
// damper held stuck).
BoxQpResult solve_box_qp(const Eigen::MatrixXd& s, const Eigen::VectorXd& w0, const Eigen::VectorXd& limit,
                         const std::vector<DamperState>& hint = {});

// The inverses of a symmetric matrix's principal submatrices S_ss, one per index set s, each
// computed when its set is first met and kept (a time loop meets a handful of sets again and
// again; at most 2^n). A new set mostly differs from the last one used by an element or two (a
// damper that sticks, a storey that yields): its inverse is then the last one's bordered
// update, O(m^2) a changed element instead of O(m^3) (kMaxChanges elements at most, and at most
// kMaxGeneration updates in a row before an inversion from scratch, so rounding cannot pile up
// beyond a few units in the last place of the inverse;
// a small pivot also falls back to the inversion). Sets below kMinUpdateSize are inverted: it
// costs little there, and a few dampers' systems keep the inversion's rounding (a block held by
// its sliders comes to rest with velocities 0 bit for bit), unless they hold a slipping bilinear
// element (a yielding building meets hundreds of small sets: updated, each costs a tenth).
class SubsetInverses {
 public:
  SubsetInverses() = default;
  explicit SubsetInverses(Eigen::MatrixXd s) : s_(std::move(s)) {}
  static constexpr int kMaxChanges = 4;
  static constexpr int kMaxGeneration = 16;
  static constexpr std::size_t kMinUpdateSize = 8;
  struct System {
    Eigen::MatrixXd inverse;  // S_ss^-1
    Eigen::VectorXd b, x;     // work vectors of the set's size
    int generation = 0;       // bordered updates since the last inversion from scratch
    // x = S_ss^-1 b, each x_i summed over the columns in order (as Eigen's lazyProduct sums
    // it), in plain loops: the sets are small, where Eigen's dynamic-size setup dominates.
    void solve() {
      const Eigen::Index m = b.size();
      const double* a = inverse.data();
      const double* bd = b.data();
      double* xd = x.data();
      for (Eigen::Index i = 0; i < m; ++i) xd[i] = a[i] * bd[0];
      for (Eigen::Index j = 1; j < m; ++j)
        for (Eigen::Index i = 0; i < m; ++i) xd[i] += a[j * m + i] * bd[j];
    }
  };
  System& of(const std::vector<int>& set) {
    // Consecutive calls mostly meet the same set, or the one before (a step's trial and its
    // decided set): check those two (inline, element by element) before the map.
    if (same(last_key_, set)) return *last_;
    if (same(before_key_, set)) {
      std::swap(last_key_, before_key_);
      std::swap(last_, before_);
      return *last_;
    }
    return find(set);
  }
  const Eigen::MatrixXd& matrix() const { return s_; }
  // One unknown's S_00^-1: the inverse of(set {0}) holds, kept after the first call (so that a
  // one-damper step need not look its set up).
  double single() {
    if (!single_known_) {
      single_ = of(std::vector<int>{0}).inverse(0, 0);
      single_known_ = true;
    }
    return single_;
  }

 private:
  System& find(const std::vector<int>& set);
  static bool same(const std::vector<int>* key, const std::vector<int>& set) {
    if (key == nullptr || key->size() != set.size()) return false;
    bool equal = true;
    for (std::size_t i = 0; i < set.size(); ++i) equal = equal && (*key)[i] == set[i];
    return equal;
  }
  Eigen::MatrixXd invert(const std::vector<int>& set) const;
  // The inverse for `set` from the last set's by bordered updates; false where not worth it or
  // not safe (too many changes, a small pivot).
  bool update_from_last(const std::vector<int>& set, Eigen::MatrixXd* inverse) const;
  Eigen::MatrixXd s_;
  // update_from_last's work (kept: it allocates nothing once grown)
  mutable std::vector<double> work_[2], c_, u_;
  mutable std::vector<int> key_;
  std::map<std::vector<int>, System> cache_;
  const std::vector<int>* last_key_ = nullptr;  // the last set's key in cache_
  System* last_ = nullptr;
  const std::vector<int>* before_key_ = nullptr;  // ... and the one before it
  System* before_ = nullptr;
  double single_ = 0.0;  // single()'s
  bool single_known_ = false;
};

// The same for many problems with one S (a time loop's: the Delassus matrix is constant for a
// fixed step). Each stuck set's system S_ss is inverted once and kept (the dampers are few and
// S_ss is well conditioned: a product with its inverse is as accurate as a solve, and much
// faster than a dynamic-size LDLT solve at these sizes), and the work vectors are reused, so a
// solve allocates nothing once its stuck sets have been seen.
class BoxQp {
 public:
  explicit BoxQp(Eigen::MatrixXd s);
  // Valid until the next call.
  const BoxQpResult& solve(const Eigen::VectorXd& w0, const Eigen::VectorXd& limit,
                           const std::vector<DamperState>& hint = {});
  // The forces of the dampers `held` stuck (w_k = 0) when the others' are `fixed`: a linear
  // solve, q_H = S_HH^-1 (w0_H - S_HF fixed_F), q_F = fixed_F (what solve() returns with
  // infinite limits for the held and the fixed forces taken out of w0, without its iterations).
  // `candidates` (ascending), if given: the only unknowns that may be held or fixed nonzero.
  void solve_held(const Eigen::VectorXd& w0, const std::vector<char>& held, const Eigen::VectorXd& fixed,
                  Eigen::VectorXd* q, const std::vector<int>* candidates = nullptr);
  // One unknown's S_00^-1, as solve_held uses it (a one-damper step's own solve).
  double single() { return inverses_.single(); }

 private:
  SubsetInverses inverses_;
  std::vector<int> stuck_, held_, fixed_, scratch_;
  BoxQpResult r_;
};

}  // namespace adjoin::detail
