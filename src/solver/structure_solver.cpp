#include "adjoin/solver/structure_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/solver/options.hpp"
#include "onset.hpp"
#include "pair_step.hpp"
#include "step_kernels.hpp"
#include "structure_model.hpp"
#include "structure_workspace.hpp"
#include "time_loop.hpp"

namespace adjoin {

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

using detail::DamperState;
using detail::Pair;
using detail::StepBlock;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// body(i) for i = 0..n-1; written out for two and four entries (the two-block scene's two
// floors, and its [v; C v] columns), where the compiler's loop with its vector set-up and
// remainder costs more than the arithmetic. Each entry's operations are the loop's, so the
// same bits.
template <class Body>
[[gnu::always_inline]] inline void small_loop(Eigen::Index n, Body&& body) {
  if (n == 2) {
    body(0);
    body(1);
  } else if (n == 4) {
    body(0);
    body(1);
    body(2);
    body(3);
  } else {
    for (Eigen::Index i = 0; i < n; ++i) body(i);
  }
}

// One column's product for one damper, inline: out = 0 + a q, as DenseProduct sums each row
// from 0 (damper_response), ...
void one_column(Eigen::Index rows, const double* __restrict a, double q, double* __restrict out) {
  small_loop(rows, [&](Eigen::Index r) { out[r] = 0.0 + a[r] * q; });
}
// ... and out = a q, as the columns kernel's first column (trial_rows).
void trial_column(Eigen::Index rows, const double* __restrict a, double q, double* __restrict out) {
  small_loop(rows, [&](Eigen::Index r) { out[r] = a[r] * q; });
}

// The free step's predictor x1 = x + c v and right-hand side (the banded kernel's free_rhs
// without K), for the dense K_eff's small structures: the pointers do not alias (no run-time
// checks before the compiler's vector loop).
void predictor(Eigen::Index n, const double* __restrict x, const double* __restrict v, double c, double* __restrict x1) {
  for (Eigen::Index i = 0; i < n; ++i) x1[i] = x[i] + c * v[i];
}
void free_rhs_rows(Eigen::Index n, const double* __restrict m, const double* __restrict v, const double* __restrict cv,
                   const double* __restrict p0, const double* __restrict p, const double* __restrict off, double c, double s,
                   double* __restrict rhs) {
  for (Eigen::Index i = 0; i < n; ++i) rhs[i] = m[i] * v[i] + c * ((((m[i] * s - cv[i]) - p0[i]) - p[i]) - off[i]);
}

// The step kernels (step_kernels.hpp) with their passes over a few entries inline: below
// kInline entries a call through the kernel table and its vector loop's set-up cost more than
// the arithmetic (the two-block scene's structure has two floors and one damper). Each entry
// by the kernel's own operations in its order (step_kernels.cpp), so the same bits either way;
// the pointers do not alias, as the kernels' do (__restrict: no run-time overlap checks).
class SmallPasses {
 public:
  using Index = Eigen::Index;
  static constexpr Index kInline = 4;
  explicit SmallPasses(const detail::StepKernels& k) : k_(k) {}

  template <class... A>
  void free_rhs(A... a) const { k_.free_rhs(a...); }
  template <class... A>
  void some_columns(A... a) const { k_.some_columns(a...); }
  template <class... A>
  void drifts(A... a) const { k_.drifts(a...); }
  void end_velocities(Index n, const double* __restrict vf, const double* __restrict cvf, const double* __restrict rv,
                      const double* __restrict rc, double h, double* __restrict v, double* __restrict cv) const {
    if (n >= kInline) return k_.end_velocities(n, vf, cvf, rv, rc, h, v, cv);
    small_loop(n, [&](Index i) {
      v[i] = vf[i] - h * rv[i];
      cv[i] = cvf[i] - h * rc[i];
    });
  }
  void trapezoid(Index n, const double* __restrict x0, const double* __restrict v0, const double* __restrict v1, double c,
                 double* __restrict x1) const {
    if (n >= kInline) return k_.trapezoid(n, x0, v0, v1, c, x1);
    small_loop(n, [&](Index i) { x1[i] = x0[i] + c * (v0[i] + v1[i]); });
  }
  void accelerations(Index n, const double* __restrict m, const double* __restrict inv_m, const double* __restrict cv,
                     const double* __restrict p, double ag, double* __restrict a) const {
    if (n >= kInline) return k_.accelerations(n, m, inv_m, cv, p, ag, a);
    small_loop(n, [&](Index i) { a[i] = ((m[i] * ag - cv[i]) - p[i]) * inv_m[i] - ag; });
  }
  void axpy(Index n, double a, const double* __restrict x, double* __restrict y) const {
    if (n >= kInline) return k_.axpy(n, a, x, y);
    small_loop(n, [&](Index i) { y[i] += x[i] * a; });
  }
  bool out_of_range(Index n, const double* x, const double* v, double limit) const {
    if (n >= kInline) return k_.out_of_range(n, x, v, limit);
    int bad = 0;
    small_loop(n, [&](Index i) { bad |= static_cast<int>(!(std::abs(x[i]) <= limit)) | static_cast<int>(!(v[i] - v[i] == 0.0)); });
    return bad != 0;
  }
  void columns(Index rows, Index cols, const double* __restrict m, const double* __restrict q, double* __restrict out) const {
    if (rows >= kInline) return k_.columns(rows, cols, m, q, out);
    for (Index r = 0; r < rows; ++r) out[r] = m[r] * q[0];
    for (Index j = 1; j < cols; ++j)
      for (Index r = 0; r < rows; ++r) out[r] += m[j * rows + r] * q[j];
  }

 private:
  const detail::StepKernels& k_;
};

// The structure step as a stepper of the one time loop (solver/time_loop.hpp): the constant
// model (structure_model.hpp: the assembly, the step's matrices, the restart rule) and the
// per-run workspace (structure_workspace.hpp: the state and the work vectors) built in the
// constructor; one grid step in advance(), in phases: the free step (predict), the dampers'
// and contact pairs' local solve, the step's end (correct), the switches, the grid point's
// report, and the carry-over to the next step.
class StructureStepper final : private detail::PairStepper::Fallbacks {
 public:
  StructureStepper(const StructureSolverOptions& options, const structure::Structure& s, const GroundMotion& ground_)
      : m(options, s), ws(m), ground(ground_), kernels(detail::step_kernels()), bilinear_kernels(detail::bilinear_kernels()) {}

  std::tuple<const structure::Structure&, const StructureSolverOptions&> info() const { return {m.s, m.options}; }
  std::size_t steps() const { return m.n_steps; }
  std::size_t history_bytes() const { return ws.histories.bytes(); }
  double history_error() const { return ws.histories.weight_error(); }
  std::size_t history_modes() const { return ws.histories.modes(); }
  std::size_t viscous_split_steps() const { return ws.viscous_split_steps; }
  // The impacts to report before the state advance() returned (time_loop.hpp's impacts()).
  const std::vector<Impact>& impacts() const { return ws.step_impacts; }

  // The state at t = 0.
  const StructureState& start() {
    StructureState& first = ws.first;
    first.t = 0.0;
    first.x = m.options.x0.size() == m.n ? m.options.x0 : Eigen::VectorXd::Zero(m.n);
    first.v = m.options.v0.size() == m.n ? m.options.v0 : Eigen::VectorXd::Zero(m.n);
    first.ag = g * ground.ag(0.0);
    // (per link, then per isolated base its slider: structure_model.hpp's link_pair)
    const auto n_links = static_cast<Eigen::Index>(m.link_pair.size());
    first.link_force = first.link_stroke = first.link_velocity = Eigen::VectorXd::Zero(n_links);
    first.link_phase.assign(m.link_pair.size(), Phase::stick);
    const auto n_contacts = static_cast<Eigen::Index>(m.s.contacts.size());
    first.contact_force = first.contact_work = first.contact_dissipated = Eigen::VectorXd::Zero(n_contacts);
    first.contact_gap.resize(n_contacts);
    for (std::size_t k = 0; k < m.s.contacts.size(); ++k) first.contact_gap[static_cast<Eigen::Index>(k)] = m.s.contacts[k].gap;
    first.link_switch.assign(m.link_pair.size(), kNaN);
    // The Zener elements' histories take their values at rest (RodLaw::commit(0, 0)'s).
    for (std::size_t e = 0; e < m.zener.size(); ++e) ws.zener_value[e] = ws.zener_kx[e] * 0.0 - ws.zener_tf[e] * 0.0;
    if (!m.zener.empty()) ws.histories.push(ws.zener_value.data());
    ws.cv_now = m.c * first.v;  // C v at t_n

    first.a_abs = Eigen::VectorXd::Zero(m.n);
    m.k0.apply(first.x, ws.internal);
    if (m.nv > 0) {
      viscous_end_forces(first);
      ws.total_now = ws.internal + ws.viscous_bt;
    }
    fill_links(first, ws.friction_now);
    // At rest no storey, damper or link force acts yet, so no floor accelerates absolutely
    // (its relative acceleration is the ground's, a_g): exactly 0, as the formula gives it.
    if (!(first.x.isZero() && first.v.isZero()))
      first.a_abs = (m.mass * first.ag - ws.cv_now - ws.internal - ws.viscous_bt).cwiseProduct(m.inv_mass) - Eigen::VectorXd::Constant(m.n, first.ag);
    ws.second = first;
    ws.now_p = &ws.first;
    ws.next_p = &ws.second;
    return first;
  }

  // The step from t_n to t_n+1 (n = step): the state at t_n+1.
  const StructureState& advance(std::size_t step) {
    if (pair) return pair_stepper.advance(step);
    const StructureState& now = *ws.now_p;
    StructureState& next = *ws.next_p;
    // (next's phases and switches are set below for the friction links; the other links' stay
    // as both states began.)
    begin_step(step, next);
    predict(now, next);
    if (m.nw > 0) bouc_wen_step(step, now);
    else if (m.nv > 0) viscous_step(step, now);
    else local_solve(step, now);
    correct(step, now, next);
    locate_switches(step, now, next);
    report(step, next);
    carry_over(step, now, next);
    std::swap(ws.now_p, ws.next_p);
    return *ws.now_p;
  }

 private:
  // The grid point t_n+1, the Zener elements' history terms, and which step this is.
  void begin_step(std::size_t step, StructureState& next) {
    next.t = static_cast<double>(step + 1) * m.h;
    next.ag = g * ground.ag(next.t);
    ag_next = next.ag;
    // The Zener elements' history terms: constant through the step (until commit).
    const double* lag = ws.histories.lag_sums();
    for (std::size_t e = 0; e < m.zener.size(); ++e) ws.offsets[static_cast<Eigen::Index>(e)] = ws.zener_scale[e] * (lag[e] + 0.0);
    // (Else it stays zero; with bilinear elements alone it changes only when a slip u_p did.)
    if (!m.zener.empty() || m.nw > 0 || (m.nh > 0 && ws.bilinear_slipped)) {
      ws.bilinear_slipped = false;
      if (m.n <= 2) {  // (one or two floors: two stores, not a call to memset)
        ws.off_dof[0] = 0.0;
        ws.off_dof[m.n - 1] = 0.0;
      } else {
        ws.off_dof.setZero();
      }
      for (std::size_t e = 0; e < m.zener.size(); ++e) m.zener[e].pair.add(ws.off_dof, ws.offsets[static_cast<Eigen::Index>(e)]);
      // The bilinear elements' slips: -k_h u_p (bilinear_step.hpp).
      if (m.nh > 0) detail::bilinear_scatter(bilinear_kernels, ws.bilinear_layout, ws.bilinear.offset.data(), ws.off_dof.data());
      // The Bouc-Wen elements' k_h (z - d) at t_n (bouc_wen_step.hpp).
      for (int e = 0; e < m.nw; ++e) Pair{m.bouc_wen[e].i, m.bouc_wen[e].j}.add(ws.off_dof, ws.bouc_wen[e].offset(m.bouc_wen[e]));
    }
    // The step after a switch, where the restart applies, is backward Euler.
    ws.restart = ws.restart_left > 0;
    if (ws.restart) --ws.restart_left;
    ws.sm = ws.restart ? m.backward.get() : m.trapezoidal.get();
    ws.box_qp = ws.restart ? ws.box_qp_backward.get() : ws.box_qp_trapezoidal.get();
  }

  // The free step: the velocities at t_n+1 without the dampers' and contacts' step forces.
  void predict(const StructureState& now, const StructureState& next) {
    // Trapezoidal: rhs = M v + h/2 (M 1 (ag_n + ag_n+1) - C v - P - K_eff (x + h/2 v) - offsets);
    // backward Euler: rhs = M v + h (M 1 ag_n+1 - K_eff x - offsets). (x1: the predictor, in
    // x1's storage; p1 = K_eff x1.)
    if (ws.restart) {
      m.k_eff.apply(now.x, ws.p1);
      ws.rhs = m.mass.cwiseProduct(now.v) + m.h * (m.mass * next.ag - ws.p1 - ws.off_dof);
    } else if (m.k_eff.banded()) {
      kernels.free_rhs(m.n, m.mass.data(), now.x.data(), now.v.data(), ws.cv_now.data(), ws.internal.data(), ws.off_dof.data(),
                       m.k_eff.diagonals(), 0.5 * m.h, now.ag + next.ag, ws.x1.data(), ws.p1.data(), ws.rhs.data());
      if (!m.k_eff.after_rows().empty()) {  // (the links' entries, then their rows' right-hand side again)
        m.k_eff.add_after(ws.x1, ws.p1);
        const double s_ag = now.ag + next.ag;
        for (int i : m.k_eff.after_rows())
          ws.rhs[i] = m.mass[i] * now.v[i] + 0.5 * m.h * ((((m.mass[i] * s_ag - ws.cv_now[i]) - ws.internal[i]) - ws.p1[i]) - ws.off_dof[i]);
      }
    } else {  // (plain loops, not Eigen expressions, whose dynamic-size set-up outweighs two floors' sums)
      const double c = 0.5 * m.h, s_ag = now.ag + next.ag;
      predictor(m.n, now.x.data(), now.v.data(), c, ws.x1.data());
      m.k_eff.apply(ws.x1, ws.p1);
      free_rhs_rows(m.n, m.mass.data(), now.v.data(), ws.cv_now.data(), ws.internal.data(), ws.p1.data(), ws.off_dof.data(), c, s_ag,
                    ws.rhs.data());
    }
    // v_free = A^-1 rhs and its damping forces C v_free: the step's only O(n^2) work (with
    // dense C).
    for (const StepBlock& b : ws.sm->blocks)
      b.step.apply_halves(ws.rhs.data() + b.offset, ws.v_free.data() + b.offset, ws.cv_free.data() + b.offset);
  }

  // The non-smooth part of the step: the contact pairs' impulses and the dampers' step forces.
  //
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
  //
  // The contact pairs' step: each pair's relative motion through the step under its free
  // relative acceleration (the structure's free step with the dampers as they were), its
  // impulse then applied to the free step as a step force before the dampers decide.
  void local_solve(std::size_t step, const StructureState& now) {
    for (int f = 0; f < m.nf; ++f) {
      ws.q_step[f] = 0.0;
      ws.onset[f] = ws.crossing[f] = ws.kink_theta[f] = kNaN;  // (kink_theta: slips ended in the step)
      ws.kink_jump[f] = 0.0;
      ws.decided[f] = DamperState::stick;
      ws.w_free[f] = across(ws.v_free, f);
    }
    ws.any_contact = false;
    if (m.nc > 0) {
      ws.v_free0 = ws.v_free;
      ws.cv_free0 = ws.cv_free;
      ws.memory_before = ws.contact_memory;
      std::fill(ws.step_work.begin(), ws.step_work.end(), 0.0);
      ws.q_trial.setZero();
      if (m.nq > 0 && step > 0) {
        hold_as_phased(now);
        solve_held(ws.hold, ws.fixed, &ws.q_trial, ws.bilinear_plastic);
      }
      contact_pass(now, ws.q_trial);
    }
    if (m.nf > 0 && step == 0 && m.nh > 0) {  // (the bilinear elements elastic from rest: not unknowns)
      ws.w_friction = ws.w_free.head(m.nf);
      const detail::BoxQpResult& r = ws.box_qp_friction->solve(ws.w_friction, m.limit, ws.states_friction);
      ws.q_step.setZero();
      ws.q_step.head(m.nf) = r.q;
      std::copy(r.state.begin(), r.state.end(), ws.decided.begin());
    } else if (m.nf > 0 && step == 0) {  // from rest: the closed-form relay of the box QP
      const detail::BoxQpResult& r = ws.box_qp->solve(ws.w_free, m.limit, ws.states);
      ws.q_step = r.q;
      ws.decided = r.state;
    } else if (m.nq > 0 && step > 0) {
      decide_dampers(now);
    }
    ws.states.swap(ws.decided);  // (decided is filled again at the next step)
    // The dampers' decided step forces move the pairs too: the contact step is taken again
    // with them, so that each pair's end of step is its own (no penetration for the Newton
    // law, the compliant force consistent with the floors' motion); the dampers keep their
    // decisions.
    if (ws.any_contact && m.nq > 0) contact_pass(now, ws.q_step);
    for (int ci = 0; ci < m.nc; ++ci) ws.contact_work[ci] += ws.step_work[ci];
  }

  // The nonlinear viscous dampers' step forces (viscous_step.hpp) with the local solve's. Alone
  // (no friction damper, no contact pair) their equation is solved once; with them, the two
  // are solved in turn until the viscous forces settle (Gauss-Seidel: the local solve with the
  // viscous forces fixed, then the viscous forces with the dampers' and pairs' fixed). (The
  // step taken is the last pass's: the next forces differ from its by less than the tolerance.)
  void viscous_step(std::size_t step, const StructureState& now) {
    constexpr int kMaxPasses = 30;
    const bool end_force = ws.restart;  // backward Euler: the end force
    ws.v_base = ws.v_free;
    ws.cv_base = ws.cv_free;
    ws.viscous_w1 = ws.viscous_w0;
    if (m.nq == 0 && m.nc == 0) {
      for (int k = 0; k < m.nv; ++k) ws.viscous_wt[k] = m.viscous[static_cast<std::size_t>(k)].pair.of(ws.v_base);
      if (!ws.viscous_solver->solve(ws.sm->viscous_g, ws.viscous_wt, ws.viscous_w0, end_force, ws.viscous_w1, ws.viscous_q))
        viscous_failed(now.t);
      fold_viscous();
      local_solve(step, now);
      return;
    }
    save_local_state();
    double last_change = std::numeric_limits<double>::infinity();
    for (int pass = 0;; ++pass) {
      if (pass > 0) restore_local_state();
      fold_viscous();
      local_solve(step, now);
      ws.viscous_w_pass = ws.viscous_w1;
      solve_viscous_beside(now.t, end_force);
      // Settled when the dampers' velocities are, to 1e-10 of the floors' velocities or where
      // rounding stops their changes falling (below 1e-8). (Not the forces: near w = 0 the law
      // magnifies a rounding change of w, 1e-16 m/s giving 1e-6 of c.)
      const double change = pass == 0 ? INFINITY : (ws.viscous_w1 - ws.viscous_w_pass).cwiseAbs().maxCoeff();
      const double scale = ws.v_base.cwiseAbs().maxCoeff() + ws.viscous_w1.cwiseAbs().maxCoeff();
      if (change <= 1e-10 * scale || (change <= 1e-8 * scale && change >= 0.5 * last_change)) return;
      last_change = change;
      if (pass == kMaxPasses) {
        // A friction damper beside a viscous one on the same floors, at its onset, can flip
        // between two passes: stuck, the viscous force vanishes and it must slip; slipping at
        // its free rate, the viscous force holds it. The joint answer (slipping slowly, the
        // viscous force taking the excess) lies between: the step is taken with the mean of
        // the two passes' viscous forces and the decision that gives (its error is that of
        // the viscous force over one step, a few per onset; docs/explanation/numerics.md).
        ws.viscous_q = 0.5 * (ws.viscous_q + ws.viscous_q_new);
        restore_local_state();
        fold_viscous();
        local_solve(step, now);
        ++ws.viscous_split_steps;
        return;
      }
      ws.viscous_q.swap(ws.viscous_q_new);
    }
  }
  // G_eff = G - G_vs S_ss^-1 G_sv for the friction dampers stuck now (s): their forces keep
  // their velocities zero, q_s = S_ss^-1 (... - G_sv Q), and so answer the viscous dampers' Q,
  // which then see the structure through G_eff (a Schur complement: positive semidefinite,
  // singular where a viscous damper is locked by a stuck one). Formed when a stuck set is first
  // met, then kept (a run meets few).
  const Eigen::MatrixXd& viscous_g_held() {
    ws.held_key.assign(static_cast<std::size_t>(m.nf) + 1, 0);
    ws.held_key[0] = ws.restart ? 1 : 0;
    bool any = false;
    for (int f = 0; f < m.nf; ++f) any |= (ws.held_key[static_cast<std::size_t>(f) + 1] = ws.states[f] == DamperState::stick);
    if (!any) return ws.sm->viscous_g;
    for (const auto& [key, cached] : ws.held_g)
      if (key == ws.held_key) return cached;
    std::vector<int> held;
    for (int f = 0; f < m.nf; ++f)
      if (ws.held_key[static_cast<std::size_t>(f) + 1]) held.push_back(f);
    const auto nh = static_cast<Eigen::Index>(held.size());
    Eigen::MatrixXd s_hh(nh, nh), g_vh(m.nv, nh);
    for (Eigen::Index a = 0; a < nh; ++a) {
      for (Eigen::Index b = 0; b < nh; ++b) s_hh(a, b) = ws.sm->delassus(held[a], held[b]);
      g_vh.col(a) = m.h * ws.sm->viscous_friction.col(held[a]);
    }
    Eigen::MatrixXd g_eff = ws.sm->viscous_g - g_vh * s_hh.ldlt().solve(g_vh.transpose());
    g_eff = 0.5 * (g_eff + g_eff.transpose()).eval();
    ws.held_g.emplace_back(ws.held_key, std::move(g_eff));
    return ws.held_g.back().second;
  }

  // The viscous dampers' forces with the last pass's dampers, bilinear elements and contact
  // pairs fixed: their end velocities less their own step forces' part, the stuck friction
  // dampers' answer to them included (w_1 = w~ - G_eff Q with the set stuck), solved.
  void solve_viscous_beside(double t, bool end_force) {
    const Eigen::MatrixXd& g_eff = viscous_g_held();
    ws.viscous_wt.noalias() = g_eff * ws.viscous_q;
    for (int k = 0; k < m.nv; ++k) {
      ws.viscous_wt[k] += m.viscous[static_cast<std::size_t>(k)].pair.of(ws.v_free);
      if (m.nq > 0) ws.viscous_wt[k] -= m.h * ws.sm->viscous_friction.row(k).dot(ws.q_step);
    }
    if (!ws.viscous_solver->solve(g_eff, ws.viscous_wt, ws.viscous_w0, end_force, ws.viscous_w1, ws.viscous_q_new))
      viscous_failed(t);
  }
  // What the local solve changes (to take it again in the next pass).
  void save_local_state() {
    ws.states_before = ws.states;
    ws.memory_saved = ws.contact_memory;
    ws.contact_work_saved = ws.contact_work;
    ws.bilinear_saved = ws.bilinear;
  }
  void restore_local_state() {
    ws.states = ws.states_before;
    ws.contact_memory = ws.memory_saved;
    ws.contact_work = ws.contact_work_saved;
    ws.bilinear = ws.bilinear_saved;
  }

  // The free step with the viscous dampers' step forces Q: v_base - h A^-1 B_v' Q (and C v).
  void fold_viscous() {
    ws.v_free = ws.v_base;
    ws.cv_free = ws.cv_base;
    ws.v_free.noalias() -= m.h * (ws.sm->a_inv_bv * ws.viscous_q);
    ws.cv_free.noalias() -= m.h * (ws.sm->c_a_inv_bv * ws.viscous_q);
  }
  [[noreturn]] void viscous_failed(double t) const {
    std::ostringstream message;
    message << "the nonlinear viscous dampers' step equation did not converge in the step from t = " << t
            << " s; reduce solver.h (now " << m.h << " s)";
    throw NumericalError(message.str(), t);
  }
  // The viscous dampers' forces at a grid point, F = c |w|^alpha sign w, and B_v' F; whether a
  // damper's velocity turned since the last grid point.
  bool viscous_end_forces(const StructureState& st) {
    ws.viscous_bt.setZero();
    bool turned = false;
    for (int k = 0; k < m.nv; ++k) {
      const auto& e = m.viscous[static_cast<std::size_t>(k)];
      const double w = e.pair.of(st.v);
      turned = turned || (w > 0.0 && ws.viscous_w0[k] < 0.0) || (w < 0.0 && ws.viscous_w0[k] > 0.0);
      ws.viscous_w0[k] = w;  // (t_n of the next step)
      ws.viscous_force[k] = m.viscous_laws[static_cast<std::size_t>(k)].force(ws.viscous_w0[k]);
      e.pair.add(ws.viscous_bt, ws.viscous_force[k]);
    }
    return turned;
  }

  // The Bouc-Wen elements' step forces (bouc_wen_step.hpp) with the local solve's (and the
  // viscous dampers'): solved in turn until the elements' end velocities settle (Gauss-Seidel,
  // as viscous_step; a contraction of rate ~ (omega h)^2 / 4, the elements' forces changing by
  // O(h) over a step). Alone, their equation is solved once.
  void bouc_wen_step(std::size_t step, const StructureState& now) {
    constexpr int kMaxPasses = 30;
    ws.bouc_wen_v_base = ws.v_free;
    ws.bouc_wen_cv_base = ws.cv_free;
    auto inner = [&] {
      ws.v_free = ws.bouc_wen_v_base;
      ws.cv_free = ws.bouc_wen_cv_base;
      ws.v_free.noalias() -= m.h * (ws.sm->a_inv_bw * ws.bouc_wen_q);
      ws.cv_free.noalias() -= m.h * (ws.sm->c_a_inv_bw * ws.bouc_wen_q);
      if (m.nv > 0) viscous_step(step, now);
      else local_solve(step, now);
    };
    const bool alone = m.nq == 0 && m.nc == 0 && m.nv == 0;
    if (!alone) {
      ws.bouc_wen_states_saved = ws.states;
      ws.bouc_wen_memory_saved = ws.contact_memory;
      ws.bouc_wen_work_saved = ws.contact_work;
      ws.bouc_wen_bilinear_saved = ws.bilinear;
    }
    for (int pass = 0;; ++pass) {
      if (pass > 0) {
        ws.states = ws.bouc_wen_states_saved;
        ws.contact_memory = ws.bouc_wen_memory_saved;
        ws.contact_work = ws.bouc_wen_work_saved;
        ws.bilinear = ws.bouc_wen_bilinear_saved;
      }
      if (!alone) inner();
      // The elements' end velocities with the others' forces as they are, less their own Q's part.
      const auto& v = alone ? ws.bouc_wen_v_base : ws.v_free;
      if (alone) ws.bouc_wen_wt.setZero();
      else ws.bouc_wen_wt.noalias() = ws.sm->bouc_wen_g * ws.bouc_wen_q;
      for (int k = 0; k < m.nw; ++k) {
        const detail::BoucWenElement& el = m.bouc_wen[k];
        ws.bouc_wen_wt[k] += v[el.i] - (el.j >= 0 ? v[el.j] : 0.0);
        if (!alone && m.nq > 0) ws.bouc_wen_wt[k] -= m.h * ws.sm->bouc_wen_qp.row(k).dot(ws.q_step);
      }
      ws.bouc_wen_w_pass = ws.bouc_wen_w1;
      const int bad = ws.bouc_wen_solver->solve(m.bouc_wen, ws.bouc_wen, ws.sm->theta, m.h, ws.sm->bouc_wen_g, ws.bouc_wen_wt,
                                                ws.bouc_wen_w1, ws.bouc_wen_q_new);
      if (bad >= 0) bouc_wen_failed(now.t, bad);
      if (alone) {
        ws.bouc_wen_q.swap(ws.bouc_wen_q_new);
        inner();
        return;
      }
      const double change = pass == 0 ? INFINITY : (ws.bouc_wen_w1 - ws.bouc_wen_w_pass).cwiseAbs().maxCoeff();
      const double scale = ws.bouc_wen_v_base.cwiseAbs().maxCoeff() + ws.bouc_wen_w1.cwiseAbs().maxCoeff();
      if (change <= 1e-10 * scale) return;
      // (Not settled: a friction damper flipping between passes at its onset; the last pass's
      // step is taken, its error that of the element's force over one step.)
      if (pass == kMaxPasses) {
        ++ws.bouc_wen_unsettled;
        return;
      }
      ws.bouc_wen_q.swap(ws.bouc_wen_q_new);
    }
  }
  [[noreturn]] void bouc_wen_failed(double t, int e) const {
    const detail::BoucWenElement& el = m.bouc_wen[static_cast<std::size_t>(e)];
    const int na = m.s.a.floors();
    std::ostringstream message;
    message << "the Bouc-Wen " << (el.storey_law ? "law of" : "device on") << " building " << (el.storey < na ? m.s.a.name : m.s.b->name)
            << "'s storey " << (el.storey < na ? el.storey + 1 : el.storey - na + 1)
            << ": its implicit step (Newton's method on z) did not converge in the step from t = " << t << " s; reduce solver.h (now "
            << m.h << " s), and check the law's beta and gamma (beta >= |gamma| keeps z bounded)";
    throw NumericalError(message.str(), t);
  }
  // The Bouc-Wen elements at t_n+1 from the step's end velocities and displacements (z_n+1 on
  // them, bouc_wen_step.hpp), in P; a storey law's yield (|z| reaching 0.9 of its saturation)
  // located in the step (linear in z).
  void end_bouc_wen(const StructureState& now, StructureState& next) {
    for (int e = 0; e < m.nw; ++e) {
      const detail::BoucWenElement& el = m.bouc_wen[e];
      detail::BoucWenState& st = ws.bouc_wen[e];
      const double w1 = next.v[el.i] - (el.j >= 0 ? next.v[el.j] : 0.0);
      const double d1 = next.x[el.i] - (el.j >= 0 ? next.x[el.j] : 0.0);
      double z1 = 0.0;
      if (!detail::bouc_wen_end_z(el, st, ws.sm->theta, m.h, w1, &z1, nullptr)) bouc_wen_failed(now.t, e);
      const double z0 = std::abs(st.z), threshold = detail::kBoucWenYield * el.z_limit;
      detail::bouc_wen_commit(el, st, d1, w1, z1);
      Pair{el.i, el.j}.add(ws.p_next, st.offset(el));  // (K0 holds k d1)
      if (!el.storey_law) continue;
      next.hyst_yield.resize(static_cast<std::size_t>(m.n), kNaN);
      next.hyst_yield[el.storey] = z0 < threshold && std::abs(z1) >= threshold
                                       ? now.t + (threshold - z0) / (std::abs(z1) - z0) * m.h
                                       : kNaN;
    }
  }

  // The dampers as they were: the stuck ones held, the slipping ones at their limits.
  // (Every entry is written here, none zeroed first: a call to memset costs more than the
  // few dampers' stores.)
  void hold_as_phased(const StructureState& now) {
    for (int f = 0; f < m.nf; ++f) {
      const Phase ph = now.link_phase[m.friction[f]];
      ws.hold[f] = ph == Phase::stick;
      ws.fixed[f] = ws.hold[f] ? 0.0 : (ph == Phase::slip_right ? m.limit[f] : -m.limit[f]);
    }
    if (m.nh > 0) hold_bilinear();
  }
  // The bilinear elements as phased at t_n (bilinear_step.hpp): elastic (no unknown: held 0,
  // fixed 0 as hold_as_phased zeroed it, its next phase and event as end_bilinear left them:
  // elastic, none), or slipping (the list ws.bilinear_plastic), held at their yield force;
  // their rows of the QP's right-hand side.
  void hold_bilinear() {
    std::fill(ws.hold.begin() + m.nf, ws.hold.end(), 0);
    ws.fixed.tail(m.nh).setZero();
    for (int e : ws.bilinear_plastic) {
      const detail::BilinearElement& el = m.bilinear[e];
      const int k = m.nf + e;
      const double w_free = ws.v_free[el.i] - (el.j >= 0 ? ws.v_free[el.j] : 0.0);
      detail::bilinear_as_phased(ws.bilinear[e], ws.sm->theta, w_free, &ws.hold[k], &ws.fixed[k], &ws.w_free[k]);
    }
  }
  // A product with columns of [A^-1 B'; C A^-1 B'] (rows `rows` of `columns`), skipping the
  // zero step forces: with bilinear elements most of the QP's unknowns are zero (elastic).
  // Only the dampers and the bilinear elements `elements` (ascending) can have a nonzero one.
  void sparse_columns(const Eigen::MatrixXd& columns, Eigen::Index rows, const Eigen::VectorXd& q, const std::vector<int>& elements,
                      double* out) {
    int* list = ws.nonzero.data();  // (listed without a branch: most steps differ in a few)
    Eigen::Index count = 0;
    auto consider = [&](int k) {
      list[count] = k;
      count += q[k] != 0.0 ? 1 : 0;
    };
    for (int k = 0; k < m.nf; ++k) consider(k);
    for (int e : elements) consider(m.nf + e);
    kernels.some_columns(rows, columns.rows(), count, list, columns.data(), q.data(), out);
  }
  // Solves for the held dampers (limit infinite) with the others' step forces fixed.
  // With bilinear elements, only the dampers and `elements` (ascending) may be held or fixed
  // nonzero.
  void solve_held(const std::vector<char>& hold, const Eigen::VectorXd& fixed, Eigen::VectorXd* q,
                  const std::vector<int>& elements) {
    if (m.nh == 0) {
      ws.box_qp->solve_held(ws.w_free, hold, fixed, q);
      return;
    }
    ws.candidates.clear();
    for (int f = 0; f < m.nf; ++f) ws.candidates.push_back(f);
    for (int e : elements) ws.candidates.push_back(m.nf + e);
    ws.box_qp->solve_held(ws.w_free, hold, fixed, q, &ws.candidates);
  }

  // One pass of the contact pairs with the dampers' step forces q_f (their impulses are
  // applied to the free step held in v_free0, cv_free0).
  void contact_pass(const StructureState& now, const Eigen::VectorXd& q_f) {
    ws.any_contact = false;
    ws.contact_bt.setZero();
    ws.step_impacts.clear();
    for (int ci = 0; ci < m.nc; ++ci) {
      const Pair& p = m.contact_pair[m.active[ci]];
      detail::ContactStepIn in;
      in.t0 = now.t;
      in.h = m.h;
      in.delta0 = p.of(now.x) - m.s.contacts[m.active[ci]].gap;
      in.w0 = p.of(now.v);
      in.a = (p.of(ws.v_free0) - (m.nq > 0 ? m.h * ws.sm->contact_friction.row(ci).dot(q_f) : 0.0) - in.w0) / m.h;
      in.kappa = ws.sm->kappa[ci];
      ws.contact_impulse[ci] = ws.contact_moment[ci] = ws.contact_end_force[ci] = 0.0;
      ws.contact_memory[ci] = ws.memory_before[ci];
      if (m.contact_stepper[ci].quiet(ws.contact_memory[ci], in)) continue;
      const detail::ContactStepOut out = m.contact_stepper[ci].step(ws.contact_memory[ci], in, ws.step_impacts);
      ws.contact_impulse[ci] = out.impulse;
      ws.contact_moment[ci] = out.moment;
      ws.contact_end_force[ci] = out.force;
      ws.step_work[ci] = out.work;
      p.add(ws.contact_bt, out.force);
      ws.any_contact = ws.any_contact || out.touched;
    }
    ws.v_free = ws.v_free0;
    ws.cv_free = ws.cv_free0;
    if (ws.any_contact) {
      ws.v_free.noalias() -= ws.sm->a_inv_bc * ws.contact_impulse;
      ws.cv_free.noalias() -= ws.sm->c_a_inv_bc * ws.contact_impulse;
    }
    for (int f = 0; f < m.nf; ++f) ws.w_free[f] = across(ws.v_free, f);
  }

  // The dampers' decisions after t_0: the trial step, each damper's switch (if any), the step
  // forces of the decided phases.
  void decide_dampers(const StructureState& now) {
    hold_as_phased(now);
    solve_held(ws.hold, ws.fixed, &ws.q_trial, ws.bilinear_plastic);
    trial_state(now, ws.q_trial);
    grid_forces(ws.cv1, ws.p1, ag_next, now.link_phase, &ws.q1, &ws.stick1);
    for (int f = 0; f < m.nf; ++f) ws.w1[f] = across(ws.v1, f);
    // (decide_stuck and decide_slipping write each damper's hold2 and fixed2, decide_bilinear
    // the elements')
    for (int f = 0; f < m.nf; ++f) {
      if (ws.hold[f]) decide_stuck(f, now);
      else decide_slipping(f, now);
    }
    if (m.nh > 0) decide_bilinear(now);
    // (Mostly the dampers go on as they were, and the trial's forces are the step's.)
    // (Swapped, not copied: q_trial is written whole by the next solve_held before it is read.)
    if (same_as_trial()) ws.q_step.swap(ws.q_trial);
    else solve_held(ws.hold2, ws.fixed2, &ws.q_step, ws.bilinear_active);
    // A starting damper that the others leave no room to slip stays stuck this step.
    if (std::any_of(ws.onset.begin(), ws.onset.end(), [](double t) { return !std::isnan(t); }))
      ws.w_end.noalias() = ws.w_free - ws.sm->delassus * ws.q_step;
    bool again = false;
    for (int f = 0; f < m.nf; ++f)
      if (!std::isnan(ws.onset[f]) && ws.w_end[f] * ws.fixed2[f] <= 0.0) {
        ws.hold2[f] = true;
        ws.onset[f] = kNaN;
        ws.decided[f] = DamperState::stick;
        again = true;
      }
    if (again) solve_held(ws.hold2, ws.fixed2, &ws.q_step, ws.bilinear_active);
  }

  // Whether the decided step keeps the trial's held set and fixed forces: the dampers', and
  // the bilinear elements' (changed only by an event located in the step).
  bool same_as_trial() const {
    for (int f = 0; f < m.nf; ++f)
      if (ws.hold2[f] != ws.hold[f] || ws.fixed2[f] != ws.fixed[f]) return false;
    return !ws.bilinear_event;
  }
  // The bilinear elements' decisions from the trial's end: yield or unloading located inside
  // the step (bilinear_step.hpp), or as phased.
  void decide_bilinear(const StructureState& now) {
    std::copy(ws.hold.begin() + m.nf, ws.hold.end(), ws.hold2.begin() + m.nf);
    ws.fixed2.tail(m.nh) = ws.fixed.tail(m.nh);
    ws.bilinear_active.clear();
    ws.bilinear_event = false;
    // (most stay elastic: bilinear_decide's first test, in one pass over all elements at the
    // trial's end, trial_state's; then the others, up to the last of them)
    detail::BilinearStates& b = ws.bilinear;
    for (int e = 0, left = ws.bilinear_trial_failed; left > 0; ++e) {
      if (b.flag[e] == 0.0) continue;
      --left;
      const detail::BilinearElement& el = m.bilinear[e];
      const int k = m.nf + e;
      ws.bilinear_active.push_back(e);
      b.bound[e] = -1.0;  // (decided here: its end is bilinear_end's)
      // (leaving the elastic range: its velocity at t_n, which the fast ends left)
      if (b[e].phase == detail::YieldPhase::elastic) b[e].w = now.v[el.i] - (el.j >= 0 ? now.v[el.j] : 0.0);
      const double w1 = ws.v1[el.i] - (el.j >= 0 ? ws.v1[el.j] : 0.0);
      detail::bilinear_decide(el, b[e], b.q[e], ws.sm->theta, m.h, b.d[e], w1, &ws.hold2[k], &ws.fixed2[k]);
      ws.bilinear_event = ws.bilinear_event || !std::isnan(b[e].event);
    }
  }

  // The end of the trial step for step forces q, at the dampers' floors: v and x (there and
  // where P there needs them), C v and P (Zener forces at their offsets), as the step's end
  // (correct) computes them everywhere.
  void trial_state(const StructureState& now, const Eigen::VectorXd& q) {
    // (q: the trial's, nonzero at the slipping elements only)
    if (m.nh > 0) sparse_columns(ws.sm->trial_rows, m.nt + m.nd, q, ws.bilinear_plastic, ws.trial_change.data());
    else if (m.nf == 1 && m.nt + m.nd <= SmallPasses::kInline) trial_column(m.nt + m.nd, ws.sm->trial_rows.data(), q[0], ws.trial_change.data());
    else kernels.columns(m.nt + m.nd, m.nf, ws.sm->trial_rows.data(), q.data(), ws.trial_change.data());
    if (m.trial_every_floor && !ws.restart) {  // (the same, in passes the compiler vectorises)
      // (v1 = v_free - h A^-1 B' q, as v_free + (A^-1 B' q)(-h): the same numbers)
      if (m.n < SmallPasses::kInline) {
        double* v1 = ws.v1.data();
        const double* vf = ws.v_free.data();
        const double* tc = ws.trial_change.data();
        const double minus_h = -m.h;
        small_loop(m.n, [&](Eigen::Index i) { v1[i] = vf[i] + tc[i] * minus_h; });  // (axpy's y + x a)
      } else {
        std::copy_n(ws.v_free.data(), m.n, ws.v1.data());
        kernels.axpy(m.n, -m.h, ws.trial_change.data(), ws.v1.data());
      }
      kernels.trapezoid(m.n, now.x.data(), now.v.data(), ws.v1.data(), 0.5 * m.h, ws.x1.data());
    } else {
      for (std::size_t t = 0; t < m.trial_dofs.size(); ++t) {
        const int k = m.trial_dofs[t];
        ws.v1[k] = ws.v_free[k] - m.h * ws.trial_change[t];
        ws.x1[k] = ws.restart ? now.x[k] + m.h * ws.v1[k] : now.x[k] + 0.5 * m.h * (now.v[k] + ws.v1[k]);
      }
    }
    // The bilinear elements' drifts at the trial's end and their first test (decide_bilinear).
    if (m.nh > 0) ws.bilinear_trial_failed = detail::bilinear_test(bilinear_kernels, ws.bilinear_layout, ws.x1.data(), ws.bilinear, false);
    for (std::size_t d = 0; d < m.damper_dofs.size(); ++d) {
      const int k = m.damper_dofs[d];
      ws.cv1[k] = ws.cv_free[k] - m.h * ws.trial_change[m.nt + d];
      ws.p1[k] = m.k0.row(k, ws.x1) + ws.contact_bt[k];
      for (const auto& [e, sign] : m.damper_zener[d]) {
        const auto& el = m.zener[static_cast<std::size_t>(e)];
        ws.p1[k] += sign * (el.stiffness * el.pair.of(ws.x1) + ws.offsets[e]);
      }
      // (the viscous dampers at their latest end velocities)
      if (m.nv > 0)
        for (const auto& [e, sign] : m.damper_viscous[d])
          ws.p1[k] += sign * m.viscous_laws[static_cast<std::size_t>(e)].force(ws.viscous_w1[e]);
      if (!m.damper_bilinear[d].empty()) {
        double pk = ws.p1[k];  // (summed in a register: the same sum, without a store per element)
        for (const auto& [e, sign] : m.damper_bilinear[d]) {
          const detail::BilinearElement& el = m.bilinear[static_cast<std::size_t>(e)];
          const double d1 = ws.bilinear.d[e];  // (K0 holds k_h d1)
          pk += sign * (detail::bilinear_trial_force(el, ws.bilinear[e], d1) - el.k * d1);
        }
        ws.p1[k] = pk;
      }
      if (m.nw > 0)
        for (const auto& [e, sign] : m.damper_bouc_wen[d]) {  // (at the latest z_n+1; K0 holds k d1)
          const detail::BoucWenElement& el = m.bouc_wen[static_cast<std::size_t>(e)];
          ws.p1[k] += sign * el.k * (ws.bouc_wen[e].z1 - (ws.x1[el.i] - (el.j >= 0 ? ws.x1[el.j] : 0.0)));
        }
    }
  }

  // Damper f, stuck at t_n: stays stuck, or starts to slip at the located onset.
  void decide_stuck(int f, const StructureState& now) {
    const double lim = m.limit[f];
    const double q_now = ws.stick_force_now[f];
    if (std::abs(q_now) > lim) {  // beyond the cone at t_n already: slipping since before t_n
      const double d = q_now > 0.0 ? 1.0 : -1.0;
      if (ws.stick_start_t[f] > now.t - m.h) {
        // A stick that began inside the last step (at a reversal): the onset lies on the
        // line between the stuck forces at its start and at t_n.
        const double r = (d * lim - ws.stick_start_q[f]) / (q_now - ws.stick_start_q[f]);
        ws.onset[f] = (ws.stick_start_t[f] + std::clamp(r, 0.0, 1.0) * (now.t - ws.stick_start_t[f]) - now.t) / m.h;
      } else {
        ws.onset[f] = std::min(detail::locate_onset(d * lim, ws.prev_stuck[f], ws.stick_force_prev[f], q_now, ws.stick1[f], -1.0), 0.0);
      }
      ws.hold2[f] = false;
      ws.fixed2[f] = d * lim;
      ws.decided[f] = d > 0.0 ? DamperState::slip_positive : DamperState::slip_negative;
    } else if (std::abs(ws.stick1[f]) > lim) {
      const double d = ws.stick1[f] > 0.0 ? 1.0 : -1.0;
      const double theta = detail::locate_onset(d * lim, ws.prev_stuck[f], ws.stick_force_prev[f], q_now, ws.stick1[f], 0.0);
      ws.onset[f] = theta;
      ws.hold2[f] = false;
      ws.fixed2[f] = theta * 0.5 * (q_now + d * lim) + (1.0 - theta) * d * lim;
      ws.decided[f] = d > 0.0 ? DamperState::slip_positive : DamperState::slip_negative;
    } else {
      ws.hold2[f] = true;
      ws.fixed2[f] = 0.0;
      ws.decided[f] = DamperState::stick;
    }
  }

  // Damper f, slipping at t_n: slips on, or at its velocity's located zero crossing sticks
  // or reverses.
  void decide_slipping(int f, const StructureState& now) {
    const double lim = m.limit[f];
    const double d = ws.fixed[f] > 0.0 ? 1.0 : -1.0;
    const double w_now = now.link_velocity[m.friction[f]];
    if (ws.w1[f] * d > 0.0) {  // slips on
      ws.hold2[f] = false;
      ws.fixed2[f] = d * lim;
      ws.decided[f] = ws.states[f];
      return;
    }
    // On the parabola through the damper's velocities at t_{n-1}, t_n and the end of
    // slipping on, when t_{n-1} was in this slip too (as the two-block scheme does: a
    // line's error depends on where in the step the crossing falls).
    const double theta = ws.prev_same_slip[f] ? detail::locate_onset(0.0, true, ws.w_prev[f], w_now, ws.w1[f], 0.0)
                         : (w_now != ws.w1[f] ? std::clamp(w_now / (w_now - ws.w1[f]), 0.0, 1.0) : 1.0);
    ws.crossing[f] = theta;
    // The force that would keep it stuck, at t_n and at the end of slipping on.
    const double s0 = would_stick(ws.cv_now, m.nc > 0 || m.nv > 0 ? ws.total_now : ws.internal, now.ag, ws.friction_now, f);
    const double s1 = would_stick(ws.cv1, ws.p1, ag_next, ws.q1, f);
    const double at = s0 + theta * (s1 - s0);
    ws.kink_theta[f] = theta;
    if (std::abs(at) <= lim) {
      ws.hold2[f] = true;
      ws.fixed2[f] = 0.0;
      ws.decided[f] = DamperState::stick;
      ws.stick_start_t[f] = now.t + theta * m.h;
      ws.stick_start_q[f] = at;
      ws.kink_jump[f] = at - d * lim;
    } else {
      ws.hold2[f] = false;
      ws.fixed2[f] = lim * d * (2.0 * theta - 1.0);
      ws.decided[f] = d > 0.0 ? DamperState::slip_negative : DamperState::slip_positive;
      ws.kink_jump[f] = -2.0 * d * lim;
    }
  }

  // The step's end from the decided step forces: velocities (stuck dampers exact),
  // displacements (with the kinks of ended slips and the contact impulses' timing), and the
  // storey and link forces P at t_n+1.
  void correct(std::size_t step, const StructureState& now, StructureState& next) {
    if (m.nh > 0) {
      sparse_columns(ws.sm->damper_response_columns, 2 * m.n, ws.q_step, ws.bilinear_active, ws.response_q.data());
      kernels.end_velocities(m.n, ws.v_free.data(), ws.cv_free.data(), ws.response_q.data(), ws.response_q.data() + m.n, m.h,
                             next.v.data(), ws.cv_next.data());
    } else if (m.nf == 1 && m.n <= SmallPasses::kInline) {  // (one damper: its column of the response, inline)
      one_column(2 * m.n, ws.sm->damper_response.matrix().data(), ws.q_step[0], ws.response_q.data());
      kernels.end_velocities(m.n, ws.v_free.data(), ws.cv_free.data(), ws.response_q.data(), ws.response_q.data() + m.n, m.h,
                             next.v.data(), ws.cv_next.data());
    } else if (m.nf > 0) {
      ws.sm->damper_response.apply(ws.q_step.data(), ws.response_q.data());
      kernels.end_velocities(m.n, ws.v_free.data(), ws.cv_free.data(), ws.response_q.data(), ws.response_q.data() + m.n, m.h,
                             next.v.data(), ws.cv_next.data());
    } else {
      next.v = ws.v_free;
      ws.cv_next = ws.cv_free;
    }
    stick_exact(next);
    if (ws.restart) {
      next.x = now.x + m.h * next.v;
    } else {
      kernels.trapezoid(m.n, now.x.data(), now.v.data(), next.v.data(), 0.5 * m.h, next.x.data());
      // (A backward-Euler step's own first-order error is larger than the kinks'.)
      if (step > 0 && std::any_of(ws.kink_theta.begin(), ws.kink_theta.end(), [](double t) { return !std::isnan(t); }))
        integrate_kinks(ws.states, ws.kink_theta, ws.kink_jump, &next.x);
    }
    // The contact impulses' timing inside the step: the step's displacement takes each as
    // spread over the step (h/2 of its velocity change for the trapezoidal rule, h for
    // backward Euler); A^-1 B_c' ((1 - theta) h I - J) makes the pair's penetration its own.
    if (ws.any_contact) {
      if (ws.restart) next.x.noalias() -= ws.sm->a_inv_bc * ws.contact_moment;
      else next.x.noalias() += ws.sm->a_inv_bc * (0.5 * m.h * ws.contact_impulse - ws.contact_moment);
    }
    m.k0.apply(next.x, ws.p_next);
    // The Zener elements' forces, and the values their histories take at report() (RodLaw::commit's).
    for (std::size_t e = 0; e < m.zener.size(); ++e) {
      const auto& el = m.zener[e];
      const double d = el.pair.of(next.x);
      ws.zener_force[e] = el.stiffness * d + ws.offsets[static_cast<Eigen::Index>(e)];
      ws.zener_value[e] = ws.zener_kx[e] * d - ws.zener_tf[e] * ws.zener_force[e];
      el.pair.add(ws.p_next, ws.zener_force[e]);
    }
    end_bilinear(now, next);
    end_bouc_wen(now, next);
  }

  // The bilinear elements' forces and phases at t_n+1 from the step's end velocities, in P,
  // and their storeys' yield instants located in the step.
  void end_bilinear(const StructureState& now, StructureState& next) {
    if (m.nh == 0) return;
    std::fill(next.hyst_yield.begin(), next.hyst_yield.end(), kNaN);
    ws.bilinear_plastic.clear();
    detail::BilinearStates& b = ws.bilinear;
    const detail::BilinearLayout& layout = ws.bilinear_layout;
    // The most: elastic through the step (no event), ending within the yield surface, where
    // only the force changes (u_p as it was), in one pass; then the others.
    for (int e = 0, left = detail::bilinear_test(bilinear_kernels, layout, next.x.data(), b, true); left > 0; ++e) {
      if (b.flag[e] == 0.0) continue;
      --left;
      const detail::BilinearElement& el = m.bilinear[e];
      detail::BilinearState& st = b[e];
      const double w1 = next.v[el.i] - (el.j >= 0 ? next.v[el.j] : 0.0);
      const double up = st.up;
      detail::bilinear_end(el, st, b.q[e], b.d[e], w1);
      ws.bilinear_slipped = ws.bilinear_slipped || st.up != up;
      if (el.storey_law && st.yielded && !std::isnan(st.event)) next.hyst_yield[el.storey] = now.t + st.event * m.h;
      st.event = kNaN;  // (read: hold_bilinear leaves an elastic element's as it is)
      if (st.phase != detail::YieldPhase::elastic) ws.bilinear_plastic.push_back(e);
      b.settled(e, layout);
    }
    // Their offsets -k_h u_p in P, in the elements' order (K0 holds k_h d1).
    detail::bilinear_scatter(bilinear_kernels, layout, b.offset.data(), ws.p_next.data());
  }

  // Stick exact: a stuck damper's two floors get one velocity, bit for bit (their
  // mass-weighted mean, which moves them by rounding only).
  void stick_exact(StructureState& next) {
    if (m.nf == 1) {  // (one damper: its floors are damper_dofs, all touched when it is stuck, none if not)
      if (ws.states[0] != DamperState::stick) return;
      for (int k : m.damper_dofs) ws.v_pre[k] = next.v[k];
      join_stuck_floors(next);
      follow_moves(next, m.damper_dofs);
      return;
    }
    // (touched: the stuck dampers' floors, ascending, from damper_dofs: sorted and unique.)
    // (every entry is some damper's floor: cleared there, without a call to memset)
    for (int f = 0; f < m.nf; ++f) {
      ws.touched_flag[m.pi[f]] = 0;
      if (m.pj[f] >= 0) ws.touched_flag[m.pj[f]] = 0;
    }
    for (int f = 0; f < m.nf; ++f)
      if (ws.states[f] == DamperState::stick) {
        ws.touched_flag[m.pi[f]] = 1;
        if (m.pj[f] >= 0) ws.touched_flag[m.pj[f]] = 1;
      }
    ws.touched.clear();
    for (std::size_t d = 0; d < m.damper_dofs.size(); ++d)
      if (ws.touched_flag[d]) ws.touched.push_back(m.damper_dofs[d]);
    for (int k : ws.touched) ws.v_pre[k] = next.v[k];
    join_stuck_floors(next);
    follow_moves(next, ws.touched);
  }
  // Each stuck damper's floors moved to their mass-weighted mean velocity (twice: a floor
  // shared by two dampers), a base's slider's base to the ground's.
  void join_stuck_floors(StructureState& next) const {
    for (int pass = 0; pass < 2; ++pass)
      for (int f = 0; f < m.nf; ++f)
        if (ws.states[f] == DamperState::stick) {
          const int i = m.fi[f], j = m.fj[f];
          if (j < 0) {  // a base's slider: the base moves with the ground (its relative velocity 0)
            next.v[i] = 0.0;
            continue;
          }
          const double v = (m.mass[i] * next.v[i] + m.mass[j] * next.v[j]) / (m.mass[i] + m.mass[j]);
          next.v[i] = next.v[j] = v;
        }
  }
  // ... and C v follows the moves of the floors `touched` (ascending) column by column (O(n)
  // each), not by a product with C.
  void follow_moves(const StructureState& next, const std::vector<int>& touched) {
    for (int k : touched) {
      const double dv = next.v[k] - ws.v_pre[k];
      if (dv == 0.0) continue;
      const StepBlock& b = m.trapezoidal->blocks[m.block_of[k]];  // (C's other rows are zero in column k; theta plays no part)
      kernels.axpy(b.size, dv, b.c.col(k - b.offset).data(), ws.cv_next.data() + b.offset);
    }
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
  void integrate_kinks(const std::vector<DamperState>& after, const std::vector<double>& kink_theta,
                       const std::vector<double>& kink_jump, Eigen::VectorXd* x) {
    std::vector<int> held;
    for (int f = 0; f < m.nf; ++f)
      if (after[f] == DamperState::stick && std::isnan(kink_theta[f])) held.push_back(f);
    const int n_held = static_cast<int>(held.size());
    Eigen::MatrixXd g_held(n_held, n_held);
    for (int a = 0; a < n_held; ++a)
      for (int b = 0; b < n_held; ++b) g_held(a, b) = m.g_all(held[a], held[b]);
    Eigen::LDLT<Eigen::MatrixXd> held_solver;
    if (n_held > 0) held_solver.compute(g_held);  // (never on an empty matrix: see a_inv_bt in step_matrices)
    Eigen::VectorXd dq(m.nf);
    for (int f = 0; f < m.nf; ++f) {
      if (std::isnan(kink_theta[f])) continue;
      dq.setZero();
      dq[f] = kink_jump[f];
      if (n_held > 0) {
        Eigen::VectorXd r(n_held);
        for (int a = 0; a < n_held; ++a) r[a] = -m.g_all(held[a], f) * kink_jump[f];
        const Eigen::VectorXd response = held_solver.solve(r);
        for (int a = 0; a < n_held; ++a) dq[held[a]] = response[a];
      }
      const double theta = kink_theta[f];
      add_bt(dq, &ws.bq);
      *x += (0.5 * m.h * m.h * theta * (1.0 - theta)) * m.inv_mass.cwiseProduct(ws.bq);
    }
  }

  // Phases from the step's dampers, with the switches located in the local solve.
  void locate_switches(std::size_t step, const StructureState& now, StructureState& next) {
    for (int f = 0; f < m.nf; ++f) {
      const int l = m.friction[f];
      const Phase before = now.link_phase[l];
      const Phase after = ws.states[f] == DamperState::stick ? Phase::stick
                          : (ws.states[f] == DamperState::slip_positive ? Phase::slip_right : Phase::slip_left);
      next.link_phase[l] = after;
      next.link_switch[l] = kNaN;
      if (after == before || step == 0) continue;
      const double theta = before == Phase::stick ? ws.onset[f] : ws.crossing[f];
      next.link_switch[l] = now.t + (std::isnan(theta) ? 1.0 : theta) * m.h;
      ws.restart_left = m.restart_steps;  // the next step restarts (when the restart applies)
    }
  }

  // The state reported at t_n+1: the grid point's damper forces and accelerations, the links'
  // and storeys' forces, the contact pairs'; the Zener elements' histories committed.
  void report(std::size_t step, StructureState& next) {
    // The grid point's forces with the contacts' (kept apart from `internal`: the trapezoidal
    // rule must not see the contact forces, whose impulse the contact step gives).
    // A viscous damper whose velocity turned in the step: the next step is backward Euler.
    // Trapezoidal mechanics would carry on a sawtooth of +-w about zero (its amplification of
    // a step of the law near w = 0 is -1, as for any mode it does not resolve), where the
    // damper and the structure are at rest; one backward-Euler step (first order, once per
    // turn: the run stays second order) damps it as the law does.
    if (m.nv > 0 && viscous_end_forces(next) && m.viscous_restarts) ws.restart_left = std::max(ws.restart_left, 1);
    if (m.nc > 0 || m.nv > 0) ws.total_next = ws.p_next + ws.contact_bt + ws.viscous_bt;
    const Eigen::VectorXd& p_grid = m.nc > 0 || m.nv > 0 ? ws.total_next : ws.p_next;
    grid_forces(ws.cv_next, p_grid, next.ag, next.link_phase, &ws.q_grid, &ws.stick_grid);
    // Absolute accelerations at the grid point: x'' - a_g.
    // The dampers' forces B' q are added at their floors only.
    if (!dampers_on_every_floor)  // (else the dampers' loop below writes them all)
      kernels.accelerations(m.n, m.mass.data(), m.inv_mass.data(), ws.cv_next.data(), p_grid.data(), next.ag, next.a_abs.data());
    if (m.nf > 0) {
      damper_bt(ws.q_grid);
      for (std::size_t d = 0; d < m.damper_dofs.size(); ++d) {
        const int k = m.damper_dofs[d];
        next.a_abs[k] = (m.mass[k] * next.ag - ws.cv_next[k] - p_grid[k] - ws.btq_dampers[d]) * m.inv_mass[k] - next.ag;
      }
    }
    fill_links(next, ws.q_grid);
    check_range(next);
    if (!m.zener.empty()) ws.histories.push(ws.zener_value.data());  // (the values correct() made)
    for (std::size_t k = 0; k < m.s.contacts.size(); ++k)
      next.contact_gap[static_cast<Eigen::Index>(k)] = m.s.contacts[k].gap - m.contact_pair[k].of(next.x);
    for (int ci = 0; ci < m.nc; ++ci) {
      const Eigen::Index k = m.active[ci];
      next.contact_force[k] = ws.contact_end_force[ci];
      next.contact_work[k] = ws.contact_work[ci];
      next.contact_dissipated[k] =
          ws.contact_work[ci] - (ws.contact_memory[ci].engaged ? m.contact_stepper[ci].stored(-next.contact_gap[k]) : 0.0);
    }
    // The impacts that ended in the step (impacts(), reported before the state) and, after the
    // last step, those still going on.
    if (step + 1 == m.n_steps)
      for (int ci = 0; ci < m.nc; ++ci)
        if (ws.contact_memory[ci].engaged) {
          Impact i = ws.contact_memory[ci].current;
          i.duration = next.t - i.start;
          i.complete = false;
          ws.step_impacts.push_back(i);
        }
  }

  // A runaway or non-finite response stops the run (NumericalError with the time).
  void check_range(const StructureState& next) const {
    if (kernels.out_of_range(m.n, next.x.data(), next.v.data(), 1e6)) range_error(next);
  }
  [[noreturn]] [[gnu::cold]] [[gnu::noinline]] void range_error(const StructureState& next) const {
    std::ostringstream message;
    message << "the response became " << (next.x.allFinite() ? "larger than 1e6 m" : "non-finite") << " at t = " << next.t
            << " s at solver.h = " << m.h << " s; check the ground motion's scale and the structure's units";
    throw NumericalError(message.str(), next.t);
  }

  // Ready for the next step (nothing here changes the state returned).
  void carry_over(std::size_t step, const StructureState& now, const StructureState& next) {
    ws.internal.swap(ws.p_next);
    if (m.nc > 0 || m.nv > 0) ws.total_now.swap(ws.total_next);
    if (m.nc > 0) {
      ws.contact_bt_now.swap(ws.contact_bt);
    }
    ws.cv_now.swap(ws.cv_next);
    // (q_grid and stick_grid are written whole by the next grid_forces.)
    ws.friction_now.swap(ws.q_grid);
    ws.stick_force_prev.swap(ws.stick_force_now);
    ws.stick_force_now.swap(ws.stick_grid);
    for (int f = 0; f < m.nf; ++f) {
      const Phase ph = now.link_phase[m.friction[f]];
      ws.prev_stuck[f] = ph == Phase::stick && step > 0;
      ws.prev_same_slip[f] = step > 0 && ph != Phase::stick && next.link_phase[m.friction[f]] == ph;
      ws.w_prev[f] = now.link_velocity[m.friction[f]];
    }
  }

  // ---- the dampers' forces ----
  // B' q, where each damper acts -q on A's floor and +q on B's (as bf' q, without the zeros).
  void add_bt(const Eigen::VectorXd& q, Eigen::VectorXd* out) const {
    out->setZero();
    for (int f = 0; f < m.nf; ++f) {
      (*out)[m.fi[f]] += q[f];
      if (m.fj[f] >= 0) (*out)[m.fj[f]] -= q[f];
    }
  }
  void damper_bt(const Eigen::VectorXd& q) {
    double* out = ws.btq_dampers.data();
    // (every entry is some damper's floor: zeroed there, without a call to memset)
    for (int f = 0; f < m.nf; ++f) {
      out[m.pi[f]] = 0.0;
      if (m.pj[f] >= 0) out[m.pj[f]] = 0.0;
    }
    for (int f = 0; f < m.nf; ++f) {
      out[m.pi[f]] += q[f];
      if (m.pj[f] >= 0) out[m.pj[f]] -= q[f];
    }
  }
  // Damper f's relative acceleration, b_f M^-1 (-C v - P - B' q) (+ a_g against the ground), B' q from
  // damper_bt.
  // Against the ground (a base's slider, j = -1) the ground term stays: + a_g.
  double relative_accel(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, double ag, int f) const {
    const int i = m.fi[f], j = m.fj[f];
    const double at_i = (-cv[i] - p[i] - ws.btq_dampers[m.pi[f]]) * m.inv_mass[i];
    return j < 0 ? at_i + ag : at_i - (-cv[j] - p[j] - ws.btq_dampers[m.pj[f]]) * m.inv_mass[j];
  }
  // Damper f's relative velocity (or any quantity across it) in `v`: v_i - v_j, v_j = 0 at the
  // ground (a base's slider).
  double across(const Eigen::VectorXd& v, int f) const { return v[m.fi[f]] - (m.fj[f] >= 0 ? v[m.fj[f]] : 0.0); }
  // Grid-point forces: slipping dampers at +-F; the stuck ones carry what keeps their relative
  // acceleration zero, (B_s M^-1 B_s') q_s = B_s M^-1 (M 1 a_g - C v - P - B_l' q_l) (the ground
  // term cancels: B 1 = 0, but for a damper against the ground, relative_accel). Also returns each damper's stick force (unclamped) for onsets.
  // `cv` is C v. Only the dampers' floors are needed: O(nf^2).
  void grid_forces(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, double ag, const std::vector<Phase>& phase, Eigen::VectorXd* q,
                   Eigen::VectorXd* stick) {
    if (m.nf == 1) grid_force_single(cv, p, ag, phase[m.friction[0]], q->data(), stick->data());
    else grid_forces_of_sets(cv, p, ag, phase, q, stick);
  }
  // (Out of line: its set-up is not paid by the one damper's path.)
  [[gnu::noinline]] void grid_forces_of_sets(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, double ag, const std::vector<Phase>& phase,
                                             Eigen::VectorXd* q, Eigen::VectorXd* stick) {
    double* qd = q->data();
    double* sd = stick->data();
    ws.stuck.clear();
    for (int f = 0; f < m.nf; ++f) {
      const Phase ph = phase[m.friction[f]];
      sd[f] = 0.0;
      if (ph == Phase::stick) {
        ws.stuck.push_back(f);
        qd[f] = 0.0;
      } else {
        qd[f] = ph == Phase::slip_right ? m.limit[f] : -m.limit[f];
      }
    }
    if (ws.stuck.empty()) return;
    damper_bt(*q);
    const int n_stuck = static_cast<int>(ws.stuck.size());
    detail::SubsetInverses::System& sys = ws.stuck_systems.of(ws.stuck);
    double* b = sys.b.data();
    for (int i = 0; i < n_stuck; ++i) b[i] = relative_accel(cv, p, ag, ws.stuck[i]);
    sys.solve();
    const double* x = sys.x.data();
    for (int i = 0; i < n_stuck; ++i) {
      const int f = ws.stuck[i];
      sd[f] = x[i];
      qd[f] = std::clamp(x[i], -m.limit[f], m.limit[f]);
    }
  }
  // grid_forces for one damper: the same numbers without the stuck set's lists and lookup.
  void grid_force_single(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, double ag, Phase ph, double* q, double* stick) {
    stick[0] = 0.0;
    if (ph != Phase::stick) {
      q[0] = ph == Phase::slip_right ? m.limit[0] : -m.limit[0];
      return;
    }
    ws.btq_dampers[m.pi[0]] = 0.0;  // (B' q with q = 0: damper_bt's)
    if (m.pj[0] >= 0) ws.btq_dampers[m.pj[0]] = 0.0;
    const double x = ws.stuck_systems.single() * relative_accel(cv, p, ag, 0);
    stick[0] = x;
    q[0] = std::clamp(x, -m.limit[0], m.limit[0]);
  }
  // The force that would keep slipping damper f stuck at this instant, the others at their
  // forces q: b_f M^-1 (-C v - P - sum_{g != f} b_g q_g) / (b_f M^-1 b_f').
  double would_stick(const Eigen::VectorXd& cv, const Eigen::VectorXd& p, double ag, const Eigen::VectorXd& q, int f) {
    ws.others = q;
    ws.others[f] = 0.0;
    damper_bt(ws.others);
    return relative_accel(cv, p, ag, f) / m.g_all(f, f);
  }

  void fill_storeys(StructureState& st) const {
    st.storey_force.resize(m.n);
    // Storey i's drift is x_i - x_(i-1), the first storey's x_1 (the ground is at rest).
    auto building = [&](const structure::Building& b, int offset) {
      const int nb = b.floors();
      const bool dashpots = offset == 0 ? m.dashpots_a : m.dashpots_b;
      st.storey_force[offset] = m.storey_spring[offset] * st.x[offset] + (dashpots ? m.storey_dashpot[offset] * st.v[offset] : 0.0);
      if (nb < 2) return;
      kernels.drifts(nb, m.storey_spring.data() + offset, dashpots ? m.storey_dashpot.data() + offset : nullptr, st.x.data() + offset,
                     st.v.data() + offset, st.storey_force.data() + offset);
    };
    building(m.s.a, 0);
    if (m.s.b) building(*m.s.b, m.s.a.floors());
    // An isolated building's storey 1 joins its base, not the ground (SPEC §7).
    for (char name : {'A', 'B'}) {
      const int base = m.s.base_dof(name);
      if (base < 0) continue;
      const int k = m.s.dof(name, 1);
      const bool dashpots = name == 'A' ? m.dashpots_a : m.dashpots_b;
      st.storey_force[k] -= m.storey_spring[k] * st.x[base] + (dashpots ? m.storey_dashpot[k] * st.v[base] : 0.0);
    }
    for (std::size_t e = 0; e < m.zener.size(); ++e)
      if (m.zener[e].storey >= 0) st.storey_force[m.zener[e].storey] += ws.zener_force[e];
    for (int k = 0; k < m.nv; ++k)
      if (m.viscous[static_cast<std::size_t>(k)].storey >= 0) st.storey_force[m.viscous[static_cast<std::size_t>(k)].storey] += ws.viscous_force[k];
    // The bilinear elements' forces, and the storeys' own laws' z (bilinear_step.hpp).
    // (Without bilinear or Bouc-Wen elements nothing writes z: zeroed once, not every step.)
    if (m.nh > 0 || m.nw > 0 || st.hyst.size() != m.n) st.hyst.setZero(m.n);
    st.hyst_yield.resize(static_cast<std::size_t>(m.n), kNaN);
    double* force = st.storey_force.data();
    double* hyst = st.hyst.data();
    const detail::BilinearStates& b = ws.bilinear;
    if (ws.bilinear_layout.chains) {
      bilinear_kernels.chain_storeys(m.nh, b.offset.data(), b.q.data(), ws.bilinear_layout.k.data(), force, hyst);
    } else {
      for (int e = 0; e < m.nh; ++e) {
        const detail::BilinearElement& el = m.bilinear[e];
        force[el.storey] += b.offset[e];  // (the storey's spring holds k_h d)
        if (el.storey_law) hyst[el.storey] = b.q[e] / el.k;
      }
    }
    for (int e = 0; e < m.nw; ++e) {  // (bouc_wen_step.hpp: the storey's spring holds k d)
      const detail::BoucWenElement& el = m.bouc_wen[e];
      st.storey_force[el.storey] += ws.bouc_wen[e].offset(el);
      if (el.storey_law) st.hyst[el.storey] = ws.bouc_wen[e].z;
    }
  }
  void fill_links(StructureState& st, const Eigen::VectorXd& q_friction) const {
    fill_storeys(st);
    for (std::size_t l = 0; l < m.link_pair.size(); ++l) {
      const Pair& p = m.link_pair[l];
      st.link_stroke[l] = p.of(st.x);
      st.link_velocity[l] = p.of(st.v);
      if (l >= m.s.links.size()) continue;  // a base's slider: a friction damper (below)
      if (m.link_zener[l] >= 0) st.link_force[l] = ws.zener_force[m.link_zener[l]];
    }
    // The linear family's (a spring's k s, a linear dashpot's c v: one term when the other is 0).
    for (const detail::StructureModel::LinearLink& e : m.linear_links) {
      const double s = st.link_stroke[e.link], v = st.link_velocity[e.link];
      st.link_force[e.link] = e.c == 0.0 ? e.k * s : e.k == 0.0 ? e.c * v : e.k * s + e.c * v;
    }
    for (int k = 0; k < m.nv; ++k)
      if (m.viscous[static_cast<std::size_t>(k)].link >= 0) st.link_force[m.viscous[static_cast<std::size_t>(k)].link] = ws.viscous_force[k];
    for (int f = 0; f < m.nf; ++f) st.link_force[m.friction[f]] = q_friction[f];
  }
  // ---- the pair step (pair_step.hpp): the general code for its rare branches ----
  void kinks(Eigen::VectorXd* x) override { integrate_kinks(ws.states, ws.kink_theta, ws.kink_jump, x); }
  [[noreturn]] void out_of_range(const StructureState& next) override { range_error(next); }

  // ---- the model (constant), the workspace (the run's state), the ground ----
  static constexpr double g = kStandardGravity;
  double ag_next = 0.0;  // a_g at t_n+1 (for the dampers against the ground, at the trial's end)
  const detail::StructureModel m;
  // Every floor is a damper's (the two-block scene): report() writes each acceleration once.
  const bool dampers_on_every_floor = m.nf > 0 && m.nd == m.n;
  detail::StepWorkspace ws;
  const GroundMotion& ground;
  const SmallPasses kernels;  // (the step kernels, a few entries' passes inline)
  const detail::BilinearKernels& bilinear_kernels;
  // The pair step (pair_step.hpp): whether it applies, and its stepper (on m and ws).
  const bool pair = detail::takes_pair_step(m);
  detail::PairStepper pair_stepper{m, ws, ground, *this};
};

}  // namespace

bool takes_restarts(const StructureSolverOptions& options, const structure::Structure& s, const GroundMotion& /*ground*/) {
  if (options.restart == StructureSolverOptions::Restart::never) return false;
  // The model's set-up decides (the stiffest mode of the step's own stiffness).
  return detail::StructureModel(options, s).restarts();
}

SolverSummary simulate_structure(const StructureSolverOptions& options, const structure::Structure& s,
                                 const GroundMotion& ground, StructureObserver& observer) {
  SolverSummary summary = detail::integrate<StructureStepper>(observer, options, s, ground);
  summary.scheme = scheme_name(options);
  summary.history = to_string(options.history);
  summary.h = options.h;
  return summary;
}

}  // namespace adjoin
