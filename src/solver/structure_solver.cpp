#include "adjoin/solver/structure_solver.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <tuple>

#include "adjoin/core/errors.hpp"
#include "adjoin/solver/options.hpp"
#include "adjoin/fractional/weights.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/modal.hpp"
#include "box_qp.hpp"
#include "contact_step.hpp"
#include "dense_product.hpp"
#include "step_kernels.hpp"
#include "time_loop.hpp"
#include "onset.hpp"
#include "rod_law.hpp"

namespace adjoin {
namespace {

using structure::DeviceType;
using structure::LinkType;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Modes with omega h above this are not resolved by the step (as the two-block implicit
// scheme's kResolvedOmegaH): trapezoidal mechanics passes them undamped.
constexpr double kResolvedOmegaH = 1.0;

// A two-node element: dof i and dof j (-1: the ground); its deformation is x_i - x_j.
struct Pair {
  int i = -1, j = -1;
  double of(const Eigen::VectorXd& x) const { return (i >= 0 ? x[i] : 0.0) - (j >= 0 ? x[j] : 0.0); }
  void add(Eigen::VectorXd& f, double value) const {
    if (i >= 0) f[i] += value;
    if (j >= 0) f[j] -= value;
  }
  void add(Eigen::MatrixXd& k, double value) const {
    if (i >= 0) k(i, i) += value;
    if (j >= 0) k(j, j) += value;
    if (i >= 0 && j >= 0) {
      k(i, j) -= value;
      k(j, i) -= value;
    }
  }
};

struct ZenerElement {
  Pair pair;
  int storey = -1;  // the storey it stands in (A's first), or -1 for a link
  std::unique_ptr<detail::RodLaw> law;
  double force = 0.0;
};

Rod rod_of(const structure::Zener& z) { return Rod{z.order, z.tau_x, z.tau_f, false}; }

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
  detail::Tridiagonal diagonals() const { return {sub_.data(), diag_.data(), sup_.data()}; }
  // p += the entries right of the band times x, row by row in column order; `rows` lists them.
  void add_after(const Eigen::VectorXd& x, Eigen::VectorXd& p) const {
    for (const Entry& e : after_) p[e.i] += e.value * x[e.j];
  }
  const std::vector<int>& after_rows() const { return after_rows_; }
  // p = K x (p not x).
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& p) const {
    const Eigen::Index n = x.size();
    if (banded()) {
      detail::step_kernels().band(n, diagonals(), x.data(), p.data());
      add_after(x, p);
      return;
    }
    p.setZero();
    for (const Entry& e : before_) p[e.i] += e.value * x[e.j];
    if (n > 1) p.tail(n - 1) += sub_.cwiseProduct(x.head(n - 1));
    p += diag_.cwiseProduct(x);
    if (n > 1) p.head(n - 1) += sup_.cwiseProduct(x.tail(n - 1));
    for (const Entry& e : after_) p[e.i] += e.value * x[e.j];
  }
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

}  // namespace

std::size_t StructureSolverOptions::steps() const {
  return static_cast<std::size_t>(std::ceil(t_end / h * (1.0 - 1e-12)));
}

bool StructureSolverOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!(std::isfinite(h) && h > 0.0)) return fail("solver.h must be a positive step (s)");
  if (!(std::isfinite(t_end) && t_end > 0.0)) return fail("solver.t_end must be a positive duration (s)");
  if (const std::string problem = step_count_problem(t_end, h); !problem.empty()) return fail(problem);
  if (!(history_tolerance >= 1e-15 && history_tolerance < 1.0))
    return fail("solver.history_tolerance must lie in [1e-15, 1) (a relative error of the weights)");
  return true;
}

namespace {

struct Block {
  int offset = 0, size = 0;
  Eigen::LDLT<Eigen::MatrixXd> a;  // A's diagonal block, factorised
  Eigen::MatrixXd c;               // C's diagonal block
  detail::DenseProduct step;       // [A^-1; C A^-1] of the block (2 size x size)
};
struct StepMatrices {
  double theta = 0.5;
  std::vector<Block> blocks;
  // A^-1 B' (the floors' velocity response to the dampers' step forces) and C A^-1 B' (the
  // damping forces of that response): per step the velocities are v = v_free - h A^-1 B' Q
  // and their damping forces C v = C v_free - h C A^-1 B' Q, O(n nf) for any Q tried.
  Eigen::MatrixXd a_inv_bt, c_a_inv_bt;
  detail::DenseProduct damper_response;  // [A^-1 B'; C A^-1 B']: one product per step
  Eigen::MatrixXd delassus;              // S = h B A^-1 B'
  std::unique_ptr<detail::BoxQp> box_qp;
  Eigen::MatrixXd a_inv_bc, c_a_inv_bc, contact_friction;  // A^-1 B_c', C A^-1 B_c', B_c A^-1 B_f'
  Eigen::VectorXd kappa;                                   // B_c A^-1 B_c' per pair
  Eigen::MatrixXd trial_rows;  // the trial's rows of A^-1 B' and C A^-1 B' (below)
};

// What the stepper's set-up assembles and needs only while it builds the step's matrices.
struct Assembly {
  Eigen::MatrixXd k0_dense, k_eff_dense;    // K0, and K_eff (the Zener elements at their effective stiffness)
  Eigen::MatrixXd bf, bc;                   // B of the friction dampers, of the contact pairs with a law
  bool coupled = false;                     // a link other than friction enters A = M + h/2 C + h^2/4 K
  std::vector<std::pair<int, int>> ranges;  // A's diagonal blocks: (offset, size)
};

// The structure step as a stepper of the one time loop (solver/time_loop.hpp): the set-up
// (assembly, the step's matrices, the checks) in the constructor, one grid step in advance().
class StructureStepper {
 public:
  StructureStepper(const StructureSolverOptions& options_, const structure::Structure& s_, const GroundMotion& ground_)
      : options(options_), s(s_), ground(ground_), kernels(detail::step_kernels()) {
    check_inputs();
    h = options.h;
    n_steps = options.steps();
    n = s.dofs();
    // The set-up: the structure assembled (the matrices only it needs kept in `a`), the
    // step's matrices, the restart rule, the dampers' trial rows, the work vectors.
    Assembly a;
    assemble_elements(a);
    assemble_dampers(a);
    assemble_contacts(a);
    // The step's matrices for the mechanics' weight theta of the step's end (x_n+1 = x_n +
    // h ((1 - theta) v_n + theta v_n+1), and the same for v): 1/2 the trapezoidal rule of every
    // step, 1 the backward-Euler restart after a switch (below). Each is formed and factorised
    // once (constant for a fixed h): A = M + theta h C + theta^2 h^2 K_eff.
    //
    // Inherent damping is per building and a friction link enters the step through the dampers'
    // forces only, so without spring, dashpot or Zener links A and C are block diagonal, one
    // block per building: each is handled on its own (half the dense work of the whole for two
    // equal buildings). Per step a block needs v_free = A^-1 rhs and its damping forces C v_free:
    // both from one matrix-vector product with [A^-1; C A^-1], formed once. (A triangular solve
    // pair costs as many multiplications but runs at a fraction of a product's speed at these
    // sizes; A is M + O(h) and well conditioned, so its explicit inverse is as accurate as the
    // solve.)
    if (s.b && !a.coupled) a.ranges = {{0, s.a.floors()}, {s.a.floors(), s.b->floors()}};
    else a.ranges = {{0, n}};
    trapezoidal = step_matrices(0.5, a);
    restart_steps = restart_rule(a);
    if (restart_steps > 0) backward = step_matrices(1.0, a);
    sm = trapezoidal.get();
    index_blocks_and_dampers(a);
    prepare_trial();
    allocate_workspace();
    assemble_storeys();
  }


  std::tuple<const structure::Structure&, const StructureSolverOptions&> info() const { return {s, options}; }
  std::size_t steps() const { return n_steps; }
  bool restarts() const { return restart_steps > 0; }
  std::size_t history_bytes() const {
    std::size_t bytes = 0;
    for (const auto& e : zener) bytes += e.law->bytes();
    return bytes;
  }
  double history_error() const {
    double error = 0.0;
    for (const auto& e : zener) error = std::max(error, e.law->weight_error());
    return error;
  }
  std::size_t history_modes() const {
    std::size_t modes = 0;
    for (const auto& e : zener) modes = std::max(modes, e.law->modes());
    return modes;
  }
  // The impacts to report before the state advance() returned (time_loop.hpp's impacts()).
  const std::vector<Impact>& impacts() const { return step_impacts; }

  // The state at t = 0.
  const StructureState& start() {
    first.t = 0.0;
    first.x = options.x0.size() == n ? options.x0 : Eigen::VectorXd::Zero(n);
    first.v = options.v0.size() == n ? options.v0 : Eigen::VectorXd::Zero(n);
    first.ag = g * ground.ag(0.0);
    first.link_force = first.link_stroke = first.link_velocity = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.links.size()));
    first.link_phase.assign(s.links.size(), Phase::stick);
    const auto n_contacts = static_cast<Eigen::Index>(s.contacts.size());
    first.contact_force = first.contact_work = first.contact_dissipated = Eigen::VectorXd::Zero(n_contacts);
    first.contact_gap.resize(n_contacts);
    for (std::size_t k = 0; k < s.contacts.size(); ++k) first.contact_gap[static_cast<Eigen::Index>(k)] = s.contacts[k].gap;
    first.link_switch.assign(s.links.size(), kNaN);
    for (auto& e : zener) e.law->commit(0.0, 0.0);
    cv_now = c * first.v;  // C v at t_n

    first.a_abs = Eigen::VectorXd::Zero(n);
    k0.apply(first.x, internal);
    fill_links(first, friction_now);
    // At rest no storey, damper or link force acts yet, so no floor accelerates absolutely
    // (its relative acceleration is the ground's, a_g): exactly 0, as the formula gives it.
    if (!(first.x.isZero() && first.v.isZero())) first.a_abs = (mass * first.ag - cv_now - internal).cwiseProduct(inv_mass) - Eigen::VectorXd::Constant(n, first.ag);
    second = first;
    now_p = &first;
    next_p = &second;
    return first;

  }

  // The step from t_n to t_n+1 (n = step): the state at t_n+1.
  const StructureState& advance(std::size_t step) {
    StructureState& now = *now_p;
    StructureState& next = *next_p;
    // (next's phases and switches are set below for the friction links; the other links' stay
    // as both states began.)
    next.t = static_cast<double>(step + 1) * h;
    next.ag = g * ground.ag(next.t);
    // The Zener elements' history terms: constant through the step (until commit).
    for (std::size_t e = 0; e < zener.size(); ++e) offsets[static_cast<Eigen::Index>(e)] = zener[e].law->offset();
    if (!zener.empty()) {  // (else it stays zero)
      off_dof.setZero();
      for (std::size_t e = 0; e < zener.size(); ++e) zener[e].pair.add(off_dof, offsets[static_cast<Eigen::Index>(e)]);
    }
    // The step after a switch, where the restart applies, is backward Euler.
    const bool restart = restart_left > 0;
    if (restart) --restart_left;
    sm = restart ? backward.get() : trapezoidal.get();
    // Trapezoidal: rhs = M v + h/2 (M 1 (ag_n + ag_n+1) - C v - P - K_eff (x + h/2 v) - offsets);
    // backward Euler: rhs = M v + h (M 1 ag_n+1 - K_eff x - offsets). (x1: the predictor, in
    // x1's storage; p1 = K_eff x1.)
    if (restart) {
      k_eff.apply(now.x, p1);
      rhs = mass.cwiseProduct(now.v) + h * (mass * next.ag - p1 - off_dof);
    } else if (k_eff.banded()) {
      kernels.free_rhs(n, mass.data(), now.x.data(), now.v.data(), cv_now.data(), internal.data(), off_dof.data(),
                       k_eff.diagonals(), 0.5 * h, now.ag + next.ag, x1.data(), p1.data(), rhs.data());
      if (!k_eff.after_rows().empty()) {  // (the links' entries, then their rows' right-hand side again)
        k_eff.add_after(x1, p1);
        const double s_ag = now.ag + next.ag;
        for (int i : k_eff.after_rows())
          rhs[i] = mass[i] * now.v[i] + 0.5 * h * ((((mass[i] * s_ag - cv_now[i]) - internal[i]) - p1[i]) - off_dof[i]);
      }
    } else {
      x1 = now.x + 0.5 * h * now.v;
      k_eff.apply(x1, p1);
      rhs = mass.cwiseProduct(now.v) + 0.5 * h * (mass * (now.ag + next.ag) - cv_now - internal - p1 - off_dof);
    }
    // v_free = A^-1 rhs and its damping forces C v_free: the step's only O(n^2) work (with
    // dense C).
    for (const Block& b : sm->blocks) {
      b.step.apply(rhs.data() + b.offset, v_free.data() + b.offset, 0, b.size);
      b.step.apply(rhs.data() + b.offset, cv_free.data() + b.offset, b.size, b.size);
    }
    // The dampers' step, decided per damper as in the two-block scheme, from a trial step in
    // which the dampers stuck at t_n stay stuck and the slipping ones slip on:
    //  - stuck at t_n: it starts to slip if its stuck force at t_{n+1} leaves the cone, at the
    //    instant located between the grid stuck forces; its step force is the stuck force
    //    (about linear) up to it and the limit after;
    //  - slipping in direction d: it slips on if its velocity keeps its sign; otherwise at the
    //    located zero crossing it sticks if the force that would keep it stuck there lies in
    //    the cone, and reverses if not (the impulse split at the crossing).
    // The dampers held stuck then take the forces that keep them stuck (a linear solve: the
    // box QP with infinite limits for them and the others' forces fixed).
    for (int f = 0; f < nf; ++f) {
      q_step[f] = 0.0;
      onset[f] = crossing[f] = kink_theta[f] = kNaN;  // (kink_theta: slips ended in the step)
      kink_jump[f] = 0.0;
      decided[f] = detail::DamperState::stick;
      w_free[f] = v_free[fi[f]] - v_free[fj[f]];
    }
    // The end of the trial step for step forces q, at the dampers' floors: v and x (there and
    // where P there needs them), C v and P (Zener forces at their offsets), as the step's end
    // below computes them everywhere.
    auto trial_state = [&](const Eigen::VectorXd& q) {
      trial_product(q);
      for (std::size_t t = 0; t < trial_dofs.size(); ++t) {
        const int k = trial_dofs[t];
        v1[k] = v_free[k] - h * trial_change[t];
        x1[k] = restart ? now.x[k] + h * v1[k] : now.x[k] + 0.5 * h * (now.v[k] + v1[k]);
      }
      for (std::size_t d = 0; d < damper_dofs.size(); ++d) {
        const int k = damper_dofs[d];
        cv1[k] = cv_free[k] - h * trial_change[nt + d];
        p1[k] = k0.row(k, x1) + contact_bt[k];
        for (const auto& [e, sign] : damper_zener[d]) {
          const auto& el = zener[static_cast<std::size_t>(e)];
          p1[k] += sign * (el.law->stiffness() * el.pair.of(x1) + offsets[e]);
        }
      }
    };
    // Solves for the held dampers (limit infinite) with the others' step forces fixed.
    auto solve_held = [&](const std::vector<char>& hold_, const Eigen::VectorXd& fixed_, Eigen::VectorXd* q) {
      sm->box_qp->solve_held(w_free, hold_, fixed_, q);
    };
    // The contact pairs' step: each pair's relative motion through the step under its free
    // relative acceleration (the structure's free step with the dampers as they were), its
    // impulse then applied to the free step as a step force before the dampers decide.
    // The dampers as they were: the stuck ones held, the slipping ones at their limits.
    auto hold_as_phased = [&] {
      fixed.setZero();
      for (int f = 0; f < nf; ++f) {
        const Phase ph = now.link_phase[friction[f]];
        hold[f] = ph == Phase::stick;
        if (!hold[f]) fixed[f] = ph == Phase::slip_right ? limit[f] : -limit[f];
      }
    };
    bool any_contact = false;
    // One pass of the contact pairs with the dampers' step forces q_f (their impulses are
    // applied to the free step held in v_free0, cv_free0).
    auto contact_pass = [&](const Eigen::VectorXd& q_f) {
      any_contact = false;
      contact_bt.setZero();
      step_impacts.clear();
      for (int ci = 0; ci < nc; ++ci) {
        const Pair& p = contact_pair[active[ci]];
        detail::ContactStepIn in;
        in.t0 = now.t;
        in.h = h;
        in.delta0 = p.of(now.x) - s.contacts[active[ci]].gap;
        in.w0 = p.of(now.v);
        in.a = (p.of(v_free0) - (nf > 0 ? h * sm->contact_friction.row(ci).dot(q_f) : 0.0) - in.w0) / h;
        in.kappa = sm->kappa[ci];
        contact_impulse[ci] = contact_moment[ci] = contact_end_force[ci] = 0.0;
        contact_memory[ci] = memory_before[ci];
        if (contact_stepper[ci].quiet(contact_memory[ci], in)) continue;
        const detail::ContactStepOut out = contact_stepper[ci].step(contact_memory[ci], in, step_impacts);
        contact_impulse[ci] = out.impulse;
        contact_moment[ci] = out.moment;
        contact_end_force[ci] = out.force;
        step_work[ci] = out.work;
        p.add(contact_bt, out.force);
        any_contact = any_contact || out.touched;
      }
      v_free = v_free0;
      cv_free = cv_free0;
      if (any_contact) {
        v_free.noalias() -= sm->a_inv_bc * contact_impulse;
        cv_free.noalias() -= sm->c_a_inv_bc * contact_impulse;
      }
      for (int f = 0; f < nf; ++f) w_free[f] = v_free[fi[f]] - v_free[fj[f]];
    };
    if (nc > 0) {
      v_free0 = v_free;
      cv_free0 = cv_free;
      memory_before = contact_memory;
      std::fill(step_work.begin(), step_work.end(), 0.0);
      q_trial.setZero();
      if (nf > 0 && step > 0) {
        hold_as_phased();
        solve_held(hold, fixed, &q_trial);
      }
      contact_pass(q_trial);
    }
    if (nf > 0 && step == 0) {  // from rest: the closed-form relay of the box QP
      const detail::BoxQpResult& r = sm->box_qp->solve(w_free, limit, states);
      q_step = r.q;
      decided = r.state;
    } else if (nf > 0) {
      hold_as_phased();
      solve_held(hold, fixed, &q_trial);
      trial_state(q_trial);
      grid_forces(cv1, p1, now.link_phase, &q1, &stick1);
      for (int f = 0; f < nf; ++f) w1[f] = v1[fi[f]] - v1[fj[f]];
      std::fill(hold2.begin(), hold2.end(), false);
      fixed2.setZero();
      for (int f = 0; f < nf; ++f) {
        const double lim = limit[f];
        if (hold[f]) {
          const double q_now = stick_force_now[f];
          if (std::abs(q_now) > lim) {  // beyond the cone at t_n already: slipping since before t_n
            const double d = q_now > 0.0 ? 1.0 : -1.0;
            if (stick_start_t[f] > now.t - h) {
              // A stick that began inside the last step (at a reversal): the onset lies on the
              // line between the stuck forces at its start and at t_n.
              const double r = (d * lim - stick_start_q[f]) / (q_now - stick_start_q[f]);
              onset[f] = (stick_start_t[f] + std::clamp(r, 0.0, 1.0) * (now.t - stick_start_t[f]) - now.t) / h;
            } else {
              onset[f] = std::min(detail::locate_onset(d * lim, prev_stuck[f], stick_force_prev[f], q_now, stick1[f], -1.0), 0.0);
            }
            fixed2[f] = d * lim;
            decided[f] = d > 0.0 ? detail::DamperState::slip_positive : detail::DamperState::slip_negative;
          } else if (std::abs(stick1[f]) > lim) {
            const double d = stick1[f] > 0.0 ? 1.0 : -1.0;
            const double theta = detail::locate_onset(d * lim, prev_stuck[f], stick_force_prev[f], q_now, stick1[f], 0.0);
            onset[f] = theta;
            fixed2[f] = theta * 0.5 * (q_now + d * lim) + (1.0 - theta) * d * lim;
            decided[f] = d > 0.0 ? detail::DamperState::slip_positive : detail::DamperState::slip_negative;
          } else {
            hold2[f] = true;
            decided[f] = detail::DamperState::stick;
          }
        } else {
          const double d = fixed[f] > 0.0 ? 1.0 : -1.0;
          const double w_now = now.link_velocity[friction[f]];
          if (w1[f] * d > 0.0) {  // slips on
            fixed2[f] = d * lim;
            decided[f] = states[f];
            continue;
          }
          // On the parabola through the damper's velocities at t_{n-1}, t_n and the end of
          // slipping on, when t_{n-1} was in this slip too (as the two-block scheme does: a
          // line's error depends on where in the step the crossing falls).
          const double theta = prev_same_slip[f] ? detail::locate_onset(0.0, true, w_prev[f], w_now, w1[f], 0.0)
                               : (w_now != w1[f] ? std::clamp(w_now / (w_now - w1[f]), 0.0, 1.0) : 1.0);
          crossing[f] = theta;
          // The force that would keep it stuck, at t_n and at the end of slipping on.
          const double s0 = would_stick(cv_now, nc > 0 ? total_now : internal, friction_now, f);
          const double s1 = would_stick(cv1, p1, q1, f);
          const double at = s0 + theta * (s1 - s0);
          kink_theta[f] = theta;
          if (std::abs(at) <= lim) {
            hold2[f] = true;
            decided[f] = detail::DamperState::stick;
            stick_start_t[f] = now.t + theta * h;
            stick_start_q[f] = at;
            kink_jump[f] = at - d * lim;
          } else {
            fixed2[f] = lim * d * (2.0 * theta - 1.0);
            decided[f] = d > 0.0 ? detail::DamperState::slip_negative : detail::DamperState::slip_positive;
            kink_jump[f] = -2.0 * d * lim;
          }
        }
      }
      // (Mostly the dampers go on as they were, and the trial's forces are the step's.)
      if (hold2 == hold && fixed2 == fixed) q_step = q_trial;
      else solve_held(hold2, fixed2, &q_step);
      // A starting damper that the others leave no room to slip stays stuck this step.
      if (std::any_of(onset.begin(), onset.end(), [](double t) { return !std::isnan(t); }))
        w_end.noalias() = w_free - sm->delassus * q_step;
      bool again = false;
      for (int f = 0; f < nf; ++f)
        if (!std::isnan(onset[f]) && w_end[f] * fixed2[f] <= 0.0) {
          hold2[f] = true;
          onset[f] = kNaN;
          decided[f] = detail::DamperState::stick;
          again = true;
        }
      if (again) solve_held(hold2, fixed2, &q_step);
    }
    states.swap(decided);  // (decided is filled again at the next step)
    // The dampers' decided step forces move the pairs too: the contact step is taken again
    // with them, so that each pair's end of step is its own (no penetration for the Newton
    // law, the compliant force consistent with the floors' motion); the dampers keep their
    // decisions.
    if (any_contact && nf > 0) contact_pass(q_step);
    for (int ci = 0; ci < nc; ++ci) contact_work[ci] += step_work[ci];
    if (nf > 0) {
      sm->damper_response.apply(q_step.data(), response_q.data());
      kernels.end_velocities(n, v_free.data(), cv_free.data(), response_q.data(), response_q.data() + n, h, next.v.data(),
                             cv_next.data());
    } else {
      next.v = v_free;
      cv_next = cv_free;
    }
    // Stick exact: a stuck damper's two floors get one velocity, bit for bit (their
    // mass-weighted mean, which moves them by rounding only).
    // (touched: the stuck dampers' floors, ascending, from damper_dofs: sorted and unique.)
    std::fill(touched_flag.begin(), touched_flag.end(), 0);
    for (int f = 0; f < nf; ++f)
      if (states[f] == detail::DamperState::stick) touched_flag[pi[f]] = touched_flag[pj[f]] = 1;
    touched.clear();
    for (std::size_t d = 0; d < damper_dofs.size(); ++d)
      if (touched_flag[d]) touched.push_back(damper_dofs[d]);
    for (int k : touched) v_pre[k] = next.v[k];
    for (int pass = 0; pass < 2; ++pass)
      for (int f = 0; f < nf; ++f)
        if (states[f] == detail::DamperState::stick) {
          const int i = fi[f], j = fj[f];
          const double v = (mass[i] * next.v[i] + mass[j] * next.v[j]) / (mass[i] + mass[j]);
          next.v[i] = next.v[j] = v;
        }
    // ... and C v follows those moves column by column (O(n) each), not by a product with C.
    for (int k : touched) {
      const double dv = next.v[k] - v_pre[k];
      if (dv == 0.0) continue;
      const Block& b = trapezoidal->blocks[block_of[k]];  // (C's other rows are zero in column k; theta plays no part)
      kernels.axpy(b.size, dv, b.c.col(k - b.offset).data(), cv_next.data() + b.offset);
    }
    if (restart) {
      next.x = now.x + h * next.v;
    } else {
      kernels.trapezoid(n, now.x.data(), now.v.data(), next.v.data(), 0.5 * h, next.x.data());
      // (A backward-Euler step's own first-order error is larger than the kinks'.)
      if (step > 0 && std::any_of(kink_theta.begin(), kink_theta.end(), [](double t) { return !std::isnan(t); }))
        integrate_kinks(states, kink_theta, kink_jump, &next.x);
    }
    // The contact impulses' timing inside the step: the step's displacement takes each as
    // spread over the step (h/2 of its velocity change for the trapezoidal rule, h for
    // backward Euler); A^-1 B_c' ((1 - theta) h I - J) makes the pair's penetration its own.
    if (any_contact) {
      if (restart) next.x.noalias() -= sm->a_inv_bc * contact_moment;
      else next.x.noalias() += sm->a_inv_bc * (0.5 * h * contact_impulse - contact_moment);
    }
    k0.apply(next.x, p_next);
    for (std::size_t e = 0; e < zener.size(); ++e) {
      auto& el = zener[e];
      el.force = el.law->stiffness() * el.pair.of(next.x) + offsets[static_cast<Eigen::Index>(e)];
      el.pair.add(p_next, el.force);
    }
    // Phases from the step's dampers, with the switches located above.
    for (int f = 0; f < nf; ++f) {
      const int l = friction[f];
      const Phase before = now.link_phase[l];
      const Phase after = states[f] == detail::DamperState::stick ? Phase::stick
                          : (states[f] == detail::DamperState::slip_positive ? Phase::slip_right : Phase::slip_left);
      next.link_phase[l] = after;
      next.link_switch[l] = kNaN;
      if (after == before || step == 0) continue;
      const double theta = before == Phase::stick ? onset[f] : crossing[f];
      next.link_switch[l] = now.t + (std::isnan(theta) ? 1.0 : theta) * h;
      restart_left = restart_steps;  // the next step restarts (when the restart applies)
    }
    // The grid point's forces with the contacts' (kept apart from `internal`: the trapezoidal
    // rule must not see the contact forces, whose impulse the contact step gives).
    if (nc > 0) total_next = p_next + contact_bt;
    const Eigen::VectorXd& p_grid = nc > 0 ? total_next : p_next;
    grid_forces(cv_next, p_grid, next.link_phase, &q_grid, &stick_grid);
    // Absolute accelerations at the grid point: x'' - a_g.
    // The dampers' forces B' q are added at their floors only.
    kernels.accelerations(n, mass.data(), inv_mass.data(), cv_next.data(), p_grid.data(), next.ag, next.a_abs.data());
    if (nf > 0) {
      damper_bt(q_grid);
      for (std::size_t d = 0; d < damper_dofs.size(); ++d) {
        const int k = damper_dofs[d];
        next.a_abs[k] = (mass[k] * next.ag - cv_next[k] - p_grid[k] - btq_dampers[d]) * inv_mass[k] - next.ag;
      }
    }
    fill_links(next, q_grid);
    if (kernels.out_of_range(n, next.x.data(), next.v.data(), 1e6)) {
      std::ostringstream m;
      m << "the response became " << (next.x.allFinite() ? "larger than 1e6 m" : "non-finite") << " at t = " << next.t
        << " s at solver.h = " << h << " s; check the ground motion's scale and the structure's units";
      throw NumericalError(m.str(), next.t);
    }
    for (auto& e : zener) e.law->commit(e.pair.of(next.x), e.force);
    for (std::size_t k = 0; k < s.contacts.size(); ++k)
      next.contact_gap[static_cast<Eigen::Index>(k)] = s.contacts[k].gap - contact_pair[k].of(next.x);
    for (int ci = 0; ci < nc; ++ci) {
      const Eigen::Index k = active[ci];
      next.contact_force[k] = contact_end_force[ci];
      next.contact_work[k] = contact_work[ci];
      next.contact_dissipated[k] =
          contact_work[ci] - (contact_memory[ci].engaged ? contact_stepper[ci].stored(-next.contact_gap[k]) : 0.0);
    }
    // The impacts that ended in the step (impacts(), reported before the state) and, after the
    // last step, those still going on.
    if (step + 1 == n_steps)
      for (int ci = 0; ci < nc; ++ci)
        if (contact_memory[ci].engaged) {
          Impact i = contact_memory[ci].current;
          i.duration = next.t - i.start;
          i.complete = false;
          step_impacts.push_back(i);
        }
    // Ready for the next step (nothing below changes the state returned).
    internal.swap(p_next);
    if (nc > 0) {
      total_now.swap(total_next);
      contact_bt_now.swap(contact_bt);
    }
    cv_now.swap(cv_next);
    // (q_grid and stick_grid are written whole by the next grid_forces.)
    friction_now.swap(q_grid);
    stick_force_prev.swap(stick_force_now);
    stick_force_now.swap(stick_grid);
    for (int f = 0; f < nf; ++f) {
      const Phase ph = now.link_phase[friction[f]];
      prev_stuck[f] = ph == Phase::stick && step > 0;
      prev_same_slip[f] = step > 0 && ph != Phase::stick && next.link_phase[friction[f]] == ph;
      w_prev[f] = now.link_velocity[friction[f]];
    }
    std::swap(now_p, next_p);
    return *now_p;
    }

 private:
  // The inputs the set-up relies on.
  void check_inputs() const {
    std::string error;
    if (!options.IsValid(&error)) throw InputError(error);
    if (!s.IsValid(&error)) throw InputError(error);
    for (const Eigen::VectorXd* v : {&options.x0, &options.v0})
      if (v->size() != 0 && (v->size() != s.dofs() || !v->allFinite()))
        throw InputError("the initial displacements and velocities need one finite value per floor");
    if (options.x0.size() != 0 && !options.x0.isZero()) {
      bool relaxed = false;  // an element whose state at t = 0 is relaxed (or stuck)
      for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr})
        if (b)
          for (const auto& d : b->devices) relaxed = relaxed || d.type == DeviceType::zener;
      for (const auto& l : s.links) relaxed = relaxed || l.type == LinkType::zener || l.type == LinkType::friction;
      if (relaxed) throw InputError("initial displacements need a structure without Zener elements and friction links");
    }
  }

  void assemble_elements(Assembly& a) {
    // ---- assembly: M, C, elastic K0, Zener elements, friction links ----
    mass.resize(n);
    c = Eigen::MatrixXd::Zero(n, n);
    a.k0_dense = Eigen::MatrixXd::Zero(n, n);
    std::map<double, std::vector<double>> weights;  // per order
    const WeightRule rule = options.quadrature == StructureSolverOptions::Quadrature::bdf2 ? WeightRule::bdf2
                                                                                          : WeightRule::grunwald_letnikov;
    auto zener_law = [&](const structure::Zener& z) {
      if (options.history == HistoryEngine::soe)  // made from the rule and order, no weights kept
        return std::make_unique<detail::RodLaw>(
            detail::make_rod_law(rod_of(z), z.k, h, options.history, rule, n_steps + 2, options.history_tolerance));
      auto& w = weights[z.order];
      if (w.empty()) w = convolution_weights(rule, z.order, n_steps + 2);
      return std::make_unique<detail::RodLaw>(rod_of(z), z.k, h, options.history, w);
    };
    auto add_building = [&](const structure::Building& b, int offset) {
      const int nb = b.floors();
      mass.segment(offset, nb) = b.masses;
      c.block(offset, offset, nb, nb) = structure::inherent_damping_matrix(b) + structure::dashpot_matrix(b);
      for (int st = 0; st < nb; ++st) Pair{offset + st, st > 0 ? offset + st - 1 : -1}.add(a.k0_dense, b.springs[st]);
      for (const auto& d : b.devices)
        for (int st : d.storeys) {
          const Pair p{offset + st - 1, st > 1 ? offset + st - 2 : -1};
          if (d.type == DeviceType::spring) p.add(a.k0_dense, d.k);
          if (d.type == DeviceType::zener) zener.push_back({p, offset + st - 1, zener_law(d.zener), 0.0});
        }
    };
    add_building(s.a, 0);
    if (s.b) add_building(*s.b, s.a.floors());
    a.coupled = false;       // a link other than friction enters A = M + h/2 C + h^2/4 K
    for (std::size_t l = 0; l < s.links.size(); ++l) {
      const auto& link = s.links[l];
      const Pair p{s.dof('A', link.floor_a), s.dof('B', link.floor_b)};
      link_pair.push_back(p);
      if (link.type == LinkType::spring) p.add(a.k0_dense, link.k);
      if (link.type == LinkType::dashpot) p.add(c, link.c);
      if (link.type == LinkType::zener) zener.push_back({p, -1, zener_law(link.zener), 0.0});
      if (link.type == LinkType::friction) friction.push_back(static_cast<int>(l));
      else a.coupled = true;
    }
    // Zener links come after the storey devices in `zener`; remember where each link's is.
    link_zener.assign(s.links.size(), -1);
    {
      int z = static_cast<int>(zener.size());
      for (int l = static_cast<int>(s.links.size()) - 1; l >= 0; --l)
        if (s.links[l].type == LinkType::zener) link_zener[l] = --z;
    }
    a.k_eff_dense = a.k0_dense;
    for (const auto& e : zener) e.pair.add(a.k_eff_dense, e.law->stiffness());
    // A shear building's stiffness is tridiagonal and a link adds four entries: O(n) products.
    k0 = Banded(a.k0_dense);
    k_eff = Banded(a.k_eff_dense);

  }

  // The friction dampers: B_f and their slip forces.
  void assemble_dampers(Assembly& a) {
    nf = static_cast<int>(friction.size());
    a.bf = Eigen::MatrixXd::Zero(nf, n);
    limit.resize(nf);
    for (int f = 0; f < nf; ++f) {
      const Pair& p = link_pair[friction[f]];
      a.bf(f, p.i) = 1.0;
      a.bf(f, p.j) = -1.0;
      limit[f] = s.links[friction[f]].slip_force;
    }
  }

  void assemble_contacts(Assembly& a) {
    // Contact pairs (SPEC §6). Each with a law is a step force like a damper's, its impulse found
    // by integrating the pair's own relative motion through the step (solver/contact_step.hpp);
    // it needs A^-1 B_c' (and C A^-1 B_c'), its inverse effective mass kappa = B_c A^-1 B_c' and
    // B_c A^-1 B_f' (how the dampers' step forces move it).
    for (std::size_t k = 0; k < s.contacts.size(); ++k)
      if (s.contacts[k].law.model != structure::ContactModel::none) active.push_back(static_cast<int>(k));
    nc = static_cast<int>(active.size());
    for (const auto& ct : s.contacts) contact_pair.push_back({s.dof('A', ct.floor_a), s.dof('B', ct.floor_b)});
    contact_memory.resize(static_cast<std::size_t>(nc));
    a.bc = Eigen::MatrixXd::Zero(nc, n);
    for (int ci = 0; ci < nc; ++ci) {
      const Pair& p = contact_pair[active[ci]];
      a.bc(ci, p.i) = 1.0;
      a.bc(ci, p.j) = -1.0;
      const double m_eff = mass[p.i] * mass[p.j] / (mass[p.i] + mass[p.j]);
      contact_stepper.emplace_back(s.contacts[active[ci]].law, m_eff, active[ci]);
    }

  }

  // The step's matrices for the mechanics' weight theta (the constructor says which).
  std::unique_ptr<StepMatrices> step_matrices(double theta, const Assembly& a) const {
    auto m = std::make_unique<StepMatrices>();
    m->theta = theta;
    const Eigen::MatrixXd a_step = Eigen::MatrixXd(mass.asDiagonal()) + theta * h * c + theta * theta * h * h * a.k_eff_dense;
    for (const auto& [offset, size] : a.ranges) {
      Block b;
      b.offset = offset;
      b.size = size;
      b.a.compute(a_step.block(offset, offset, size, size));
      if (b.a.info() != Eigen::Success)
        throw NumericalError("the step matrix M + theta h C + theta^2 h^2 K is not positive definite", 0.0);
      b.c = c.block(offset, offset, size, size);
      Eigen::MatrixXd step(2 * size, size);
      step.topRows(size) = b.a.solve(Eigen::MatrixXd::Identity(size, size));
      step.bottomRows(size) = b.c * step.topRows(size);
      b.step = detail::DenseProduct(std::move(step));
      m->blocks.push_back(std::move(b));
    }
    // No friction link (a building alone): nothing to solve, and Eigen's triangular solve must
    // not see a matrix with no columns (it binds a reference to its null data).
    m->a_inv_bt = Eigen::MatrixXd::Zero(n, nf);
    if (nf > 0)
      for (const Block& b : m->blocks)
        m->a_inv_bt.middleRows(b.offset, b.size) = b.a.solve(a.bf.transpose().middleRows(b.offset, b.size));
    m->c_a_inv_bt = nf > 0 ? Eigen::MatrixXd(c * m->a_inv_bt) : Eigen::MatrixXd(n, 0);
    Eigen::MatrixXd stacked(2 * n, nf);
    stacked << m->a_inv_bt, m->c_a_inv_bt;
    m->damper_response = detail::DenseProduct(std::move(stacked));
    m->delassus = nf > 0 ? Eigen::MatrixXd(h * a.bf * m->a_inv_bt) : Eigen::MatrixXd(0, 0);
    m->box_qp = std::make_unique<detail::BoxQp>(m->delassus);
    m->a_inv_bc = Eigen::MatrixXd::Zero(n, nc);
    m->kappa.resize(nc);
    if (nc > 0) {
      for (const Block& b : m->blocks)
        m->a_inv_bc.middleRows(b.offset, b.size) = b.a.solve(a.bc.transpose().middleRows(b.offset, b.size));
      for (int ci = 0; ci < nc; ++ci) m->kappa[ci] = a.bc.row(ci).dot(m->a_inv_bc.col(ci));
    }
    m->c_a_inv_bc = nc > 0 ? Eigen::MatrixXd(c * m->a_inv_bc) : Eigen::MatrixXd(n, 0);
    m->contact_friction = Eigen::MatrixXd::Zero(nc, nf);
    for (int ci = 0; ci < nc; ++ci)
      for (int f = 0; f < nf; ++f) {
        const Pair& p = contact_pair[active[ci]];
        m->contact_friction(ci, f) = m->a_inv_bt(p.i, f) - m->a_inv_bt(p.j, f);
      }
    return m;
  }

  // The backward-Euler steps after a switch: 1 when the restart applies, else 0.
  int restart_rule(const Assembly& a) const {
    // The backward-Euler restart (the `implicit` schemes' rule; the two-block scenes' implicit
    // schemes are this stepper: solver/two_block_structure.cpp). Trapezoidal mechanics does not
    // damp the modes the step does not resolve (its amplification tends to -1 as omega h grows): a damper's switch (a jump of
    // its force) excites the stiffest mode, which rings on and can drive a damper's relative
    // velocity through zero again and again (spurious switches). The step after a switch is
    // therefore taken with backward-Euler mechanics, which damps a mode by
    // 1/sqrt(1 + (omega h)^2): automatically when the stiffest mode of the structure (with the
    // Zener elements at their effective stiffness, the dampers free: locking them only lowers
    // it) is unresolved, h omega_max > 1; after every switch with Restart::always (the
    // implicit-damped rule). One first-order step per switch keeps the step second order.
    double omega_max = 0.0;
    if (nf > 0 && options.restart == StructureSolverOptions::Restart::automatic) {
      // Per block (K_eff is block diagonal with the blocks of A), and from the tridiagonal
      // matrix directly where a block is one (a shear building: O(n^2), not the dense O(n^3)).
      for (const auto& [offset, size] : a.ranges) {
        const Eigen::VectorXd inv_sqrt_m = mass.segment(offset, size).cwiseSqrt().cwiseInverse();
        const Eigen::MatrixXd scaled = inv_sqrt_m.asDiagonal() * a.k_eff_dense.block(offset, offset, size, size) * inv_sqrt_m.asDiagonal();
        bool tridiagonal = size > 1;
        for (int j = 0; j < size && tridiagonal; ++j)
          for (int i = 0; i < size; ++i)
            if (std::abs(i - j) > 1 && scaled(i, j) != 0.0) tridiagonal = false;
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes;
        if (tridiagonal) modes.computeFromTridiagonal(scaled.diagonal(), scaled.diagonal(-1), Eigen::EigenvaluesOnly);
        else modes.compute(scaled, Eigen::EigenvaluesOnly);
        omega_max = std::max(omega_max, std::sqrt(std::max(0.0, modes.eigenvalues().maxCoeff())));
      }
    }
    return
        nf > 0 && (options.restart == StructureSolverOptions::Restart::always ||
                   (options.restart == StructureSolverOptions::Restart::automatic && h * omega_max > kResolvedOmegaH))
            ? 1
            : 0;
  }

  // Each dof's block, the contact pairs' vectors, B M^-1 B' and the dampers' floors.
  void index_blocks_and_dampers(const Assembly& a) {
    const std::vector<Block>& blocks = trapezoidal->blocks;
    block_of.resize(n);
    for (std::size_t bi = 0; bi < blocks.size(); ++bi)
      std::fill_n(block_of.begin() + blocks[bi].offset, blocks[bi].size, static_cast<int>(bi));
    contact_impulse = contact_moment = contact_end_force = Eigen::VectorXd::Zero(nc);
    contact_bt_now = contact_bt = total_now = Eigen::VectorXd::Zero(n);
    total_next.resize(n);
    contact_work.assign(static_cast<std::size_t>(nc), 0.0);
    step_work.assign(static_cast<std::size_t>(nc), 0.0);
    v_free0.resize(n);
    cv_free0.resize(n);
    step_impacts.reserve(16);
    inv_mass = mass.cwiseInverse();
    // B M^-1 B': for the grid-point forces of stuck dampers and the kinks of ended slips.
    g_all.resize(nf, nf);
    for (int i = 0; i < nf; ++i)
      for (int j = 0; j < nf; ++j) g_all(i, j) = (a.bf.row(i).cwiseProduct(inv_mass.transpose())).dot(a.bf.row(j));
    fi.resize(nf);
    fj.resize(nf);
    for (int f = 0; f < nf; ++f) {
      fi[f] = link_pair[friction[f]].i;
      fj[f] = link_pair[friction[f]].j;
    }
  }

  void prepare_trial() {
    // The trial step (the dampers' decisions) is read at the dampers' floors only: there its
    // velocities, damping forces and P, for which x at those floors' stiffness columns and at
    // the other ends of their Zener elements.
    for (int f = 0; f < nf; ++f) damper_dofs.insert(damper_dofs.end(), {fi[f], fj[f]});
    std::sort(damper_dofs.begin(), damper_dofs.end());
    damper_dofs.erase(std::unique(damper_dofs.begin(), damper_dofs.end()), damper_dofs.end());
    for (int k : damper_dofs) {
      const std::vector<int> cols = k0.columns(k);
      trial_dofs.insert(trial_dofs.end(), cols.begin(), cols.end());
      std::vector<std::pair<int, double>> touching;
      for (std::size_t e = 0; e < zener.size(); ++e) {
        const Pair& pr = zener[e].pair;
        if (pr.i != k && pr.j != k) continue;
        touching.emplace_back(static_cast<int>(e), pr.i == k ? 1.0 : -1.0);
        for (int d : {pr.i, pr.j})
          if (d >= 0) trial_dofs.push_back(d);
      }
      damper_zener.push_back(std::move(touching));
    }
    std::sort(trial_dofs.begin(), trial_dofs.end());
    trial_dofs.erase(std::unique(trial_dofs.begin(), trial_dofs.end()), trial_dofs.end());
    // The rows of A^-1 B' at the trial's floors and below them those of C A^-1 B' at the dampers'.
    // Their products with q are summed column after column (vectorised across the rows), so each
    // row's sum is formed in the order of its columns, as Eigen sums a row of the full matrices.
    nt = static_cast<Eigen::Index>(trial_dofs.size());
    nd = static_cast<Eigen::Index>(damper_dofs.size());
    for (StepMatrices* m : {trapezoidal.get(), backward.get()}) {
      if (m == nullptr) continue;
      m->trial_rows.resize(nt + nd, nf);
      for (Eigen::Index t = 0; t < nt; ++t) m->trial_rows.row(t) = m->a_inv_bt.row(trial_dofs[t]);
      for (Eigen::Index d = 0; d < nd; ++d) m->trial_rows.row(nt + d) = m->c_a_inv_bt.row(damper_dofs[d]);
    }
    trial_change.resize(nt + nd);

    // The stuck dampers' systems (B_s M^-1 B_s'), inverted per stuck set (a product with the
    // inverse of this small, well conditioned matrix is as accurate as a solve and much faster
    // than a dynamic-size LDLT solve).
    stuck_systems = detail::SubsetInverses(g_all);
    btq_dampers.resize(static_cast<Eigen::Index>(damper_dofs.size()));
    pi.resize(nf);
    pj.resize(nf);
    for (int f = 0; f < nf; ++f) {
      pi[f] = static_cast<int>(std::lower_bound(damper_dofs.begin(), damper_dofs.end(), fi[f]) - damper_dofs.begin());
      pj[f] = static_cast<int>(std::lower_bound(damper_dofs.begin(), damper_dofs.end(), fj[f]) - damper_dofs.begin());
    }
  }

  void allocate_workspace() {
    // The step's work vectors and the state carried from step to step.
    offsets.resize(static_cast<Eigen::Index>(zener.size()));
    response_q.resize(2 * n);
    off_dof = Eigen::VectorXd::Zero(n);
    for (Eigen::VectorXd* v : {&rhs, &v_free, &cv_free, &v1, &x1, &p1, &cv1, &p_next, &cv_next, &v_pre, &bq}) v->resize(n);
    for (Eigen::VectorXd* v : {&w_free, &w_end, &q_step, &q_trial, &q1, &stick1, &w1, &fixed, &fixed2, &q_grid, &stick_grid, &others})
      v->resize(nf);
    for (std::vector<double>* v : {&onset, &crossing, &kink_theta, &kink_jump}) v->resize(nf);
    decided.resize(nf);
    hold.resize(nf);
    hold2.resize(nf);
    touched.reserve(2 * static_cast<std::size_t>(nf));
    touched_flag.assign(damper_dofs.size(), 0);
    states.assign(nf, detail::DamperState::stick);
    internal = Eigen::VectorXd::Zero(n);
    friction_now = stick_force_now = stick_force_prev = Eigen::VectorXd::Zero(nf);
    prev_stuck.assign(nf, false);
    prev_same_slip.assign(nf, false);
    w_prev.assign(nf, 0.0);
    stick_start_t.assign(nf, -INFINITY);
    stick_start_q.assign(nf, 0.0);

  }

  void assemble_storeys() {
    // Storey forces: the storey springs, spring and dashpot devices, Zener devices.
    storey_spring.assign(n, 0.0);
    storey_dashpot.assign(n, 0.0);
    auto storeys_of = [&](const structure::Building& b, int offset) {
      for (int st = 0; st < b.floors(); ++st) storey_spring[offset + st] += b.springs[st];
      for (const auto& d : b.devices)
        for (int st : d.storeys) {
          if (d.type == DeviceType::spring) storey_spring[offset + st - 1] += d.k;
          if (d.type == DeviceType::dashpot) storey_dashpot[offset + st - 1] += d.c;
        }
    };
    storeys_of(s.a, 0);
    if (s.b) storeys_of(*s.b, s.a.floors());
    const Eigen::Map<const Eigen::VectorXd> dashpot_of(storey_dashpot.data(), n);
    dashpots_a = !dashpot_of.head(s.a.floors()).isZero(0.0);
    dashpots_b = !dashpot_of.tail(n - s.a.floors()).isZero(0.0);
  }

  void trial_product(const Eigen::VectorXd& q) {
    detail::step_kernels().columns(nt + nd, nf, sm->trial_rows.data(), q.data(), trial_change.data());
  }
  // B' q, where each damper acts -q on A's floor and +q on B's (as bf' q, without the zeros).
  void add_bt(const Eigen::VectorXd& q, Eigen::VectorXd* out) const {
    out->setZero();
    for (int f = 0; f < nf; ++f) {
      (*out)[fi[f]] += q[f];
      (*out)[fj[f]] -= q[f];
    }
  }
  void damper_bt(const Eigen::VectorXd& q) {
    double* out = btq_dampers.data();
    std::fill_n(out, btq_dampers.size(), 0.0);
    for (int f = 0; f < nf; ++f) {
      out[pi[f]] += q[f];
      out[pj[f]] -= q[f];
    }
  }
  // Damper f's relative acceleration without the ground, b_f M^-1 (-C v - P - B' q), B' q from
  // damper_bt.
  double relative_accel(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, int f) const {
    const int i = fi[f], j = fj[f];
    return (-cv[i] - p[i] - btq_dampers[pi[f]]) * inv_mass[i] - (-cv[j] - p[j] - btq_dampers[pj[f]]) * inv_mass[j];
  }
  // Grid-point forces: slipping dampers at +-F; the stuck ones carry what keeps their relative
  // acceleration zero, (B_s M^-1 B_s') q_s = B_s M^-1 (M 1 a_g - C v - P - B_l' q_l) (the ground
  // term cancels: B 1 = 0). Also returns each damper's stick force (unclamped) for onsets.
  // `cv` is C v. Only the dampers' floors are needed: O(nf^2).
  void grid_forces(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, const std::vector<Phase>& phase, Eigen::VectorXd* q,
                   Eigen::VectorXd* stick) {
    double* qd = q->data();
    double* sd = stick->data();
    stuck.clear();
    for (int f = 0; f < nf; ++f) {
      const Phase ph = phase[friction[f]];
      sd[f] = 0.0;
      if (ph == Phase::stick) {
        stuck.push_back(f);
        qd[f] = 0.0;
      } else {
        qd[f] = ph == Phase::slip_right ? limit[f] : -limit[f];
      }
    }
    if (stuck.empty()) return;
    damper_bt(*q);
    const int m = static_cast<int>(stuck.size());
    detail::SubsetInverses::System& sys = stuck_systems.of(stuck);
    double* b = sys.b.data();
    for (int i = 0; i < m; ++i) b[i] = relative_accel(cv, p, stuck[i]);
    sys.solve();
    const double* x = sys.x.data();
    for (int i = 0; i < m; ++i) {
      const int f = stuck[i];
      sd[f] = x[i];
      qd[f] = std::clamp(x[i], -limit[f], limit[f]);
    }
  }
  // The force that would keep slipping damper f stuck at this instant, the others at their
  // forces q: b_f M^-1 (-C v - P - sum_{g != f} b_g q_g) / (b_f M^-1 b_f').
  double would_stick(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, const Eigen::VectorXd& q, int f) {
    others = q;
    others[f] = 0.0;
    damper_bt(others);
    return relative_accel(cv, p, f) / g_all(f, f);
  }

  void fill_storeys(StructureState& st) const {
    st.storey_force.resize(n);
    // Storey i's drift is x_i - x_(i-1), the first storey's x_1 (the ground is at rest).
    auto building = [&](const structure::Building& b, int offset) {
      const int nb = b.floors();
      const bool dashpots = offset == 0 ? dashpots_a : dashpots_b;
      st.storey_force[offset] = storey_spring[offset] * st.x[offset] + (dashpots ? storey_dashpot[offset] * st.v[offset] : 0.0);
      if (nb < 2) return;
      kernels.drifts(nb, storey_spring.data() + offset, dashpots ? storey_dashpot.data() + offset : nullptr, st.x.data() + offset,
                     st.v.data() + offset, st.storey_force.data() + offset);
    };
    building(s.a, 0);
    if (s.b) building(*s.b, s.a.floors());
    for (const auto& e : zener)
      if (e.storey >= 0) st.storey_force[e.storey] += e.force;
  }
  void fill_links(StructureState& st, const Eigen::VectorXd& q_friction) const {
    fill_storeys(st);
    for (std::size_t l = 0; l < s.links.size(); ++l) {
      const Pair& p = link_pair[l];
      st.link_stroke[l] = p.of(st.x);
      st.link_velocity[l] = p.of(st.v);
      const auto& link = s.links[l];
      if (link.type == LinkType::spring) st.link_force[l] = link.k * st.link_stroke[l];
      if (link.type == LinkType::dashpot) st.link_force[l] = link.c * st.link_velocity[l];
      if (link.type == LinkType::zener) st.link_force[l] = zener[link_zener[l]].force;
    }
    for (int f = 0; f < nf; ++f) st.link_force[friction[f]] = q_friction[f];
  }
  // Where a damper's slip ends inside a step (it sticks, or turns), its force jumps by dq at
  // the located fraction theta, so the floors' velocities have a kink there, which the
  // trapezoidal rule integrates as if they were smooth: an O(h^2) local error,
  // -(jump of x'') h^2 theta (1 - theta) / 2, whose size depends on where in the step the
  // slip ended. Into a stick the stroke is then frozen and the stuck force that decides the
  // next onset carries the error on (near a grazing onset, amplified): the instants' errors
  // were irregular in h, which defeats an error estimate from two steps. The kink's part is
  // integrated exactly: x'' jumps by -M^-1 B' dQ, where dQ holds dq and the jumps of the
  // dampers that stay stuck (which keep their relative accelerations: their stuck forces
  // jump too). One damper: exactly the two-block scheme's correction. Onsets need nothing:
  // the stuck force reaches the limit continuously, no kink. (Rare: it may allocate.)
  void integrate_kinks(const std::vector<detail::DamperState>& after, const std::vector<double>& kink_theta_,
                       const std::vector<double>& kink_jump_, Eigen::VectorXd* x) {
    std::vector<int> held;
    for (int f = 0; f < nf; ++f)
      if (after[f] == detail::DamperState::stick && std::isnan(kink_theta_[f])) held.push_back(f);
    const int m = static_cast<int>(held.size());
    Eigen::MatrixXd g_held(m, m);
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) g_held(a, b) = g_all(held[a], held[b]);
    Eigen::LDLT<Eigen::MatrixXd> held_solver;
    if (m > 0) held_solver.compute(g_held);  // (never on an empty matrix: see a_inv_bt in step_matrices)
    Eigen::VectorXd dq(nf);
    for (int f = 0; f < nf; ++f) {
      if (std::isnan(kink_theta_[f])) continue;
      dq.setZero();
      dq[f] = kink_jump_[f];
      if (m > 0) {
        Eigen::VectorXd r(m);
        for (int a = 0; a < m; ++a) r[a] = -g_all(held[a], f) * kink_jump_[f];
        const Eigen::VectorXd response = held_solver.solve(r);
        for (int a = 0; a < m; ++a) dq[held[a]] = response[a];
      }
      const double theta = kink_theta_[f];
      add_bt(dq, &bq);
      *x += (0.5 * h * h * theta * (1.0 - theta)) * inv_mass.cwiseProduct(bq);
    }
  }

  // ---- the run's inputs (the caller's, alive through the run) ----
  const StructureSolverOptions& options;
  const structure::Structure& s;
  const GroundMotion& ground;
  const detail::StepKernels& kernels;
  static constexpr double g = kStandardGravity;
  double h = 0.0;
  std::size_t n_steps = 0;
  int n = 0;

  // ---- the structure, assembled ----
  Eigen::VectorXd mass, inv_mass;
  Eigen::MatrixXd c;  // C, the inherent damping and the dashpots
  std::vector<ZenerElement> zener;
  std::vector<Pair> link_pair;
  std::vector<int> friction;    // link indices
  std::vector<int> link_zener;  // per link, its Zener element (or -1)
  Banded k0, k_eff;             // K0 and K_eff (with the Zener elements' effective stiffness)
  int nf = 0;                   // friction dampers
  Eigen::VectorXd limit;        // their slip forces
  std::vector<int> active;      // contacts with a law
  int nc = 0;
  std::vector<Pair> contact_pair;
  std::vector<detail::ContactStepper> contact_stepper;
  std::vector<detail::ContactMemory> contact_memory;
  std::unique_ptr<StepMatrices> trapezoidal, backward;  // theta = 1/2, and 1 for the restart
  StepMatrices* sm = nullptr;                           // this step's
  int restart_steps = 0;                                // backward-Euler steps after a switch
  int restart_left = 0;                                 // ... still to take
  std::vector<int> block_of;                            // each dof's block
  Eigen::VectorXd contact_impulse, contact_moment, contact_end_force;
  Eigen::VectorXd contact_bt_now, contact_bt;  // B_c' p at t_n, t_n+1
  Eigen::VectorXd total_now, total_next;       // storey, link and contact forces
  std::vector<double> contact_work, step_work;
  std::vector<detail::ContactMemory> memory_before;
  Eigen::VectorXd v_free0, cv_free0;
  std::vector<Impact> step_impacts;
  Eigen::MatrixXd g_all;  // B M^-1 B'
  std::vector<int> fi, fj;  // each damper's two floors
  std::vector<int> damper_dofs, trial_dofs;
  std::vector<std::vector<std::pair<int, double>>> damper_zener;  // per damper dof: (element, sign), in order
  Eigen::Index nt = 0, nd = 0;
  Eigen::VectorXd trial_change;  // A^-1 B' q at trial_dofs, then C A^-1 B' q at damper_dofs
  detail::SubsetInverses stuck_systems;  // B_s M^-1 B_s' per stuck set
  std::vector<int> stuck;
  // B' q at the dampers' floors (damper_dofs), in btq_dampers: only there is it read by the
  // dampers' forces (each damper acts -q on A's floor and +q on B's).
  Eigen::VectorXd btq_dampers;
  std::vector<int> pi, pj;  // each damper's floors' places in damper_dofs
  std::vector<double> storey_spring, storey_dashpot;  // per storey: springs and spring devices; dashpots
  bool dashpots_a = false, dashpots_b = false;        // a building has dashpot devices

  // ---- the state carried from step to step ----
  std::vector<detail::DamperState> states;
  Eigen::VectorXd internal;  // storey and link forces (not friction) at t_n
  Eigen::VectorXd cv_now;    // C v at t_n
  Eigen::VectorXd friction_now;
  Eigen::VectorXd stick_force_now;  // the force that keeps each damper stuck
  Eigen::VectorXd stick_force_prev;
  std::vector<char> prev_stuck;      // the grid point before `now` was stuck
  std::vector<char> prev_same_slip;  // ... slipped as `now` does, with velocity:
  std::vector<double> w_prev;
  std::vector<double> stick_start_t, stick_start_q;  // the last stick's start

  // The step's work vectors, sized once: a step allocates nothing (but the box QP's small
  // systems). (char, not the bit-packed vector<bool>: read in every step.)
  Eigen::VectorXd offsets;  // each Zener element's f - k_eff d
  Eigen::VectorXd response_q, off_dof, rhs, v_free, cv_free, v1, x1, p1, cv1, p_next, cv_next, v_pre;
  Eigen::VectorXd bq, w_free, w_end, q_step, q_trial, q1, stick1, w1;
  Eigen::VectorXd fixed, fixed2, q_grid, stick_grid, others;
  std::vector<double> onset, crossing, kink_theta, kink_jump;
  std::vector<detail::DamperState> decided;
  std::vector<char> hold, hold2;
  std::vector<int> touched;
  std::vector<char> touched_flag;  // per damper_dofs entry

  // The grid points t_n (`now`) and t_n+1 (`next`): two states whose vectors every step reuses,
  // their roles swapped after each step.
  StructureState first, second;
  StructureState* now_p = nullptr;
  StructureState* next_p = nullptr;
};

}  // namespace

bool takes_restarts(const StructureSolverOptions& options, const structure::Structure& s, const GroundMotion& ground) {
  if (options.restart == StructureSolverOptions::Restart::never) return false;
  // The stepper's set-up decides (the stiffest mode of the step's own stiffness).
  return StructureStepper(options, s, ground).restarts();
}

StructureRunSummary simulate_structure(const StructureSolverOptions& options, const structure::Structure& s,
                                       const GroundMotion& ground, StructureObserver& observer) {
  const detail::LoopResult r = detail::integrate<StructureStepper>(observer, options, s, ground);
  StructureRunSummary summary;
  summary.steps = r.steps;
  summary.wall_seconds = r.wall_seconds;
  summary.history_bytes = r.history_bytes;
  summary.history_error = r.history_error;
  summary.history_modes = r.history_modes;
  return summary;
}

}  // namespace adjoin
