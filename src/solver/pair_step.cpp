#include "pair_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "adjoin/core/units.hpp"
#include "onset.hpp"

namespace adjoin::detail {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Whether the pair's slots are PairSlots<true>'s (decide(), the rare path, reads pc's own).
bool plain_pair(const PairConstants& c) {
  if (c.fi != 0 || c.fj != 1 || c.pi != 0 || c.pj != 1 || c.dashpots_a || c.dashpots_b) return false;
  if (c.n_contacts != 1 || c.contact_i[0] != 0 || c.contact_j[0] != 1) return false;
  if (c.n_zener != 0 && c.n_zener != 2) return false;
  for (int e = 0; e < c.n_zener; ++e)
    if (c.zener[e].i != e || c.zener[e].j != 2 || c.zener[e].storey != e) return false;
  return true;
}
}  // namespace

PairStepper::PairStepper(const StructureModel& model, StepWorkspace& workspace, const GroundMotion& ground_motion, Fallbacks& general)
    : m(model), ws(workspace), ground(ground_motion), fallbacks(general) {}

// The general step's floating-point operations in their order for two floors and one damper
// between them (f = 0, its floors i and j, damper_dofs = trial_dofs = {0, 1}, no contact law,
// viscous, bilinear or Bouc-Wen element), on scalars: the constants read once (PairConstants),
// the state carried between steps in PairCarry and the step's own values in locals, the state
// reported written straight into `next`. Each phase is named by the general step's function it
// repeats (structure_solver.cpp). Rare branches (the first step's QP, an onset's check, a
// kink) go through the general code and its work vectors.
template <int kZener, bool kPlain>
const StructureState& PairStepper::advance_with(std::size_t step) {
  const StructureState& now = *ws.now_p;
  StructureState& next = *ws.next_p;
  const PairConstants& c = pc;
  const PairSlots<kPlain> sl{c};
  const int n_zener = kZener >= 0 ? kZener : c.n_zener;
  PairCarry& cr = carry;
  // begin_step: t_n+1, a_g, the Zener elements' offsets (each reads its own law only).
  next.t = static_cast<double>(step + 1) * c.h;
  next.ag = kStandardGravity * ground.ag(next.t);
  double offsets[PairConstants::kMaxZener] = {};
  double off[3] = {0.0, 0.0, 0.0};
  const double* lag = ws.histories.lag_sums();
  for (int e = 0; e < n_zener; ++e) {
    offsets[e] = c.zener[e].scale * (lag[e] + 0.0);
    off[sl.zi(e)] += offsets[e];
    off[sl.zj(e)] -= offsets[e];
  }
  const bool restart = ws.restart_left > 0;
  if (restart) --ws.restart_left;
  const PairTheta& th = restart ? c.backward : c.trapezoidal;
  const double* x0 = now.x.data();
  const double* v0 = now.v.data();
  // predict: the free step.
  double rhs[2];
  if (restart) {
    const double p1_0 = (0.0 + c.ke_di0 * x0[0]) + c.ke_up0 * x0[1], p1_1 = (0.0 + c.ke_lo0 * x0[0]) + c.ke_di1 * x0[1];
    rhs[0] = c.mass[0] * v0[0] + c.h * ((c.mass[0] * next.ag - p1_0) - off[0]);
    rhs[1] = c.mass[1] * v0[1] + c.h * ((c.mass[1] * next.ag - p1_1) - off[1]);
  } else {
    const double s_ag = now.ag + next.ag, hh = c.half_h;
    const double x1_0 = x0[0] + hh * v0[0], x1_1 = x0[1] + hh * v0[1];
    const double p1_0 = (0.0 + c.ke_di0 * x1_0) + c.ke_up0 * x1_1, p1_1 = (0.0 + c.ke_lo0 * x1_0) + c.ke_di1 * x1_1;
    rhs[0] = c.mass[0] * v0[0] + hh * ((((c.mass[0] * s_ag - cr.cv_now[0]) - cr.internal[0]) - p1_0) - off[0]);
    rhs[1] = c.mass[1] * v0[1] + hh * ((((c.mass[1] * s_ag - cr.cv_now[1]) - cr.internal[1]) - p1_1) - off[1]);
  }
  Step s;
  for (int k = 0; k < 2; ++k) {
    s.vf[k] = 0.0 + th.block[k][0] * rhs[k];
    s.cvf[k] = 0.0 + th.block[k][1] * rhs[k];
  }
  // local_solve: the damper's step force, and correct: the step's end under it.
  s.w_free = s.vf[sl.fi()] - s.vf[sl.fj()];
  DamperState decided = DamperState::stick;
  End end;
  end.stick_known = false;
  if (step == 0) {
    ws.w_free[0] = s.w_free;
    ws.box_qp = restart ? ws.box_qp_backward.get() : ws.box_qp_trapezoidal.get();
    const BoxQpResult& r = ws.box_qp->solve(ws.w_free, m.limit, ws.states);
    decided = r.state[0];
    end_state<kZener, kPlain>(now, th, restart, step, s, r.q[0], decided, offsets, end);
  } else if (!decide_at_end<kZener, kPlain>(now, th, restart, step, offsets, s, decided, end)) {
    const double q_step = decide(now, th, restart, offsets, s, decided);
    end_state<kZener, kPlain>(now, th, restart, step, s, q_step, decided, offsets, end);
  }
  cr.state = decided;
  const double* x = end.x;
  const double* v = end.v;
  const double* xs = end.xs;
  double* p = end.p;
  const double* cv = end.cv;
  const double* zener_force = end.zener_force;
  // locate_switches
  const Phase before = now.link_phase[0];
  const Phase after = decided == DamperState::stick ? Phase::stick
                      : (decided == DamperState::slip_positive ? Phase::slip_right : Phase::slip_left);
  next.link_phase[0] = after;
  next.link_switch[0] = kNaN;
  if (after != before && step != 0) {
    const double theta = before == Phase::stick ? s.onset : s.crossing;
    next.link_switch[0] = now.t + (std::isnan(theta) ? 1.0 : theta) * c.h;
    ws.restart_left = m.restart_steps;  // the next step restarts (when the restart applies)
  }
  // report: the grid point's damper force, accelerations, storey and link forces; the Zener
  // histories committed.
  double stick_grid = 0.0;
  const double q = end.stick_known ? std::clamp(end.stick, -c.limit, c.limit) : grid_force(cv, p, after, &stick_grid);
  if (end.stick_known) stick_grid = end.stick;
  {
    const double ag = next.ag;
    double btq[2];
    btq[sl.pi()] = 0.0 + q;  // (damper_bt's sums)
    btq[sl.pj()] = 0.0 - q;
    double* a_abs = next.a_abs.data();
    for (int k = 0; k < 2; ++k) a_abs[k] = (c.mass[k] * ag - cv[k] - p[k] - btq[k]) * c.inv_mass[k] - ag;
    double* force = next.storey_force.data();
    force[0] = c.storey_spring[0] * x[0] + (sl.dashpots_a() ? c.storey_dashpot[0] * v[0] : 0.0);
    force[1] = c.storey_spring[1] * x[1] + (sl.dashpots_b() ? c.storey_dashpot[1] * v[1] : 0.0);
    for (int e = 0; e < n_zener; ++e)
      if (sl.storey(e) >= 0) force[sl.storey(e)] += zener_force[e];
    next.link_stroke[0] = x[sl.fi()] - x[sl.fj()];
    next.link_velocity[0] = v[sl.fi()] - v[sl.fj()];
    next.link_force[0] = q;
  }
  // (check_range's test, inline: |x| <= 1e6 false for NaN, v - v not 0 for an infinite v)
  const int bad = int{!(std::abs(x[0]) <= 1e6)} | int{!(std::abs(x[1]) <= 1e6)} | int{!(v[0] - v[0] == 0.0)} | int{!(v[1] - v[1] == 0.0)};
  if (bad) [[unlikely]] fallbacks.out_of_range(next);
  if (n_zener > 0) {  // (RodLaw::commit's values, all pushed at once)
    for (int e = 0; e < n_zener; ++e) {
      const PairZener& z = c.zener[e];
      ws.zener_value[static_cast<std::size_t>(e)] = z.value_of_x * (xs[sl.zi(e)] - xs[sl.zj(e)]) - z.value_of_f * zener_force[e];
    }
    ws.histories.push(ws.zener_value.data());
  }
  for (int k = 0; k < sl.contacts(); ++k) next.contact_gap[k] = c.contact_gap[k] - (xs[sl.ci(k)] - xs[sl.cj(k)]);
  // carry_over
  cr.internal[0] = p[0];
  cr.internal[1] = p[1];
  cr.cv_now[0] = cv[0];
  cr.cv_now[1] = cv[1];
  cr.stick_prev = cr.stick_now;
  cr.stick_now = stick_grid;
  cr.prev_stuck = before == Phase::stick && step > 0;
  cr.prev_same_slip = step > 0 && before != Phase::stick && after == before;
  cr.w_prev = now.link_velocity[0];
  std::swap(ws.now_p, ws.next_p);
  return *ws.now_p;
}

// correct: the step's end under the damper's step force q_step and its state `decided`: the
// end velocities from the damper's column, the stuck floors joined (their mass-weighted mean,
// twice; C v follows), x (with a slip's kink, the general code's), P with the Zener forces.
template <int kZener, bool kPlain>
void PairStepper::end_state(const StructureState& now, const PairTheta& th, bool restart, std::size_t step, const Step& s,
                            double q_step, DamperState decided, const double* offsets, End& e) {
  const PairConstants& c = pc;
  const PairSlots<kPlain> sl{c};
  const int n_zener = kZener >= 0 ? kZener : c.n_zener;
  StructureState& next = *ws.next_p;
  double* v = next.v.data();
  double* cv = e.cv;
  {
    double r[4];
    for (int k = 0; k < 4; ++k) r[k] = 0.0 + th.response[k] * q_step;
    for (int k = 0; k < 2; ++k) {
      v[k] = s.vf[k] - c.h * r[k];
      cv[k] = s.cvf[k] - c.h * r[2 + k];
    }
  }
  e.dv[0] = e.dv[1] = 0.0;
  if (decided == DamperState::stick) {  // stick_exact
    const double before[2] = {v[0], v[1]};
    const int fi = sl.fi(), fj = sl.fj();
    const double mi = c.mass[fi], mj = c.mass[fj];
    for (int pass = 0; pass < 2; ++pass) {
      const double mean = (mi * v[fi] + mj * v[fj]) / (mi + mj);
      v[fi] = v[fj] = mean;
    }
    for (int k = 0; k < 2; ++k) {
      const double dv = v[k] - before[k];
      e.dv[k] = dv;
      if (dv != 0.0) cv[k] += c.c_diag[k] * dv;
    }
  }
  const double* x0 = now.x.data();
  const double* v0 = now.v.data();
  double* x = next.x.data();
  if (restart) {
    for (int k = 0; k < 2; ++k) x[k] = x0[k] + c.h * v[k];
  } else {
    for (int k = 0; k < 2; ++k) x[k] = x0[k] + c.half_h * (v0[k] + v[k]);
    if (step > 0 && !std::isnan(s.kink_theta)) [[unlikely]] {
      ws.states[0] = decided;
      ws.kink_theta[0] = s.kink_theta;
      ws.kink_jump[0] = s.kink_jump;
      fallbacks.kinks(&next.x);
    }
  }
  e.x = x;
  e.v = v;
  double* p = e.p;
  p[0] = (0.0 + c.k0_di0 * x[0]) + c.k0_up0 * x[1];
  p[1] = (0.0 + c.k0_lo0 * x[0]) + c.k0_di1 * x[1];
  e.xs[0] = x[0];
  e.xs[1] = x[1];
  e.xs[2] = 0.0;
  double p3[3] = {p[0], p[1], 0.0};
  for (int k = 0; k < n_zener; ++k) {
    const PairZener& z = c.zener[k];
    e.zener_force[k] = z.stiffness * (e.xs[sl.zi(k)] - e.xs[sl.zj(k)]) + offsets[k];
    p3[sl.zi(k)] += e.zener_force[k];
    p3[sl.zj(k)] -= e.zener_force[k];
  }
  p[0] = p3[0];
  p[1] = p3[1];
}

// The usual steps decided at the step's end itself, without decide()'s trial:
//  - a slipping damper that slips on: the trial's force is the step force, so the trial's end
//    is the step's end (the same operations, the same numbers), and its relative velocity
//    decides;
//  - a stuck damper (inside the cone at t_n) whose stuck force at the step's end lies inside
//    the cone by more than stuck_margin: the trial's end differs from the step's only by the
//    stick's mean velocity (a few roundings), so the trial's stuck force lies inside the cone
//    too, and decide() would keep the damper stuck with the trial's force.
// Each decides as decide() would and leaves the step's end in e; false (nothing decided: a
// switch, or too close to one to tell) leaves the step to decide() and end_state.
template <int kZener, bool kPlain>
bool PairStepper::decide_at_end(const StructureState& now, const PairTheta& th, bool restart, std::size_t step,
                                const double* offsets, const Step& s, DamperState& decided, End& e) {
  const PairConstants& c = pc;
  const Phase ph = now.link_phase[0];
  if (ph == Phase::stick) {
    if (std::abs(carry.stick_now) > c.limit) return false;
    end_state<kZener, kPlain>(now, th, restart, step, s, th.single * s.w_free, DamperState::stick, offsets, e);
    const double stick = c.stuck_single * relative_accel(e.cv, e.p, 0.0);
    if (!(std::abs(stick) + stuck_margin<kZener, kPlain>(now, e) <= c.limit)) return false;  // (false for NaN)
    e.stick_known = true;
    e.stick = stick;
    decided = DamperState::stick;
    return true;
  }
  const double d = ph == Phase::slip_right ? 1.0 : -1.0;
  end_state<kZener, kPlain>(now, th, restart, step, s, d * c.limit, carry.state, offsets, e);
  const PairSlots<kPlain> sl{c};
  if (!((e.v[sl.fi()] - e.v[sl.fj()]) * d > 0.0)) return false;
  decided = carry.state;
  return true;
}

// A bound on |stick1 - stick| for decide_at_end: the trial's end (x1, C v1, P1) against the
// step's end (x, C v, P) of a stuck step. Their velocities differ by e.dv (the mean), which
// moves C v by C dv and x by up to h dv, hence P by up to |K| h dv (K: K0's row and the Zener
// stiffnesses); the trial's P also holds the contacts' B' f (zero without a contact law). Each
// end is formed with roundings of its terms (relative 1.1e-16 each), bounded here by 1e-12 of
// the terms' sizes: a bound generous by about four orders of magnitude.
template <int kZener, bool kPlain>
double PairStepper::stuck_margin(const StructureState& now, const End& e) const {
  const PairConstants& c = pc;
  const int n_zener = kZener >= 0 ? kZener : c.n_zener;
  const double dv = std::max(std::abs(e.dv[0]), std::abs(e.dv[1]));
  const double* x0 = now.x.data();
  const double* v0 = now.v.data();
  const double size_x = std::abs(x0[0]) + std::abs(x0[1]) + std::abs(e.x[0]) + std::abs(e.x[1]) +
                        c.h * (std::abs(v0[0]) + std::abs(v0[1]) + std::abs(e.v[0]) + std::abs(e.v[1]));
  double terms = std::abs(e.cv[0]) + std::abs(e.cv[1]) + std::abs(e.p[0]) + std::abs(e.p[1]);
  for (int k = 0; k < n_zener; ++k) terms += std::abs(e.zener_force[k]);
  return c.stuck_scale * ((c.c_abs + c.k_abs * c.h) * dv + c.contact_abs + 1e-12 * (terms + c.k_abs * size_x));
}

// The constants (PairConstants) and the carried state (PairCarry) from the model and from
// the state start() left in the workspace; at the first step of a run.
void PairStepper::begin_run() {
  PairConstants& c = pc;
  c.h = m.h;
  c.half_h = 0.5 * m.h;
  c.minus_h = -m.h;
  const Tridiagonal ke = m.k_eff.diagonals(), k0 = m.k0.diagonals();
  c.ke_di0 = ke.di[0], c.ke_di1 = ke.di[1], c.ke_up0 = ke.up[0], c.ke_lo0 = ke.lo[0];
  c.k0_di0 = k0.di[0], c.k0_di1 = k0.di[1], c.k0_up0 = k0.up[0], c.k0_lo0 = k0.lo[0];
  auto theta = [&](const StepMatrices* sm, BoxQp* qp, PairTheta& t) {
    if (!sm) return;
    t.single = qp->single();
    for (int r = 0; r < 4; ++r) {
      t.trial[r] = sm->trial_rows.data()[r];
      t.response[r] = sm->damper_response.matrix().data()[r];
    }
    for (const StepBlock& b : sm->blocks) {
      t.block[b.offset][0] = b.step.matrix()(0, 0);
      t.block[b.offset][1] = b.step.matrix()(1, 0);
    }
  };
  theta(m.trapezoidal.get(), ws.box_qp_trapezoidal.get(), c.trapezoidal);
  theta(m.backward.get(), ws.box_qp_backward.get(), c.backward);
  for (int k = 0; k < 2; ++k) {
    c.mass[k] = m.mass[k];
    c.inv_mass[k] = m.inv_mass[k];
    c.c_diag[k] = m.trapezoidal->blocks[m.block_of[k]].c(0, 0);
    c.contact_bt[k] = ws.contact_bt[k];
    c.storey_spring[k] = m.storey_spring[static_cast<std::size_t>(k)];
    c.storey_dashpot[k] = m.storey_dashpot.empty() ? 0.0 : m.storey_dashpot[static_cast<std::size_t>(k)];
  }
  c.dashpots_a = m.dashpots_a;
  c.dashpots_b = m.dashpots_b;
  c.limit = m.limit[0];
  c.stuck_single = ws.stuck_systems.single();
  // (stuck_margin's constants)
  c.stuck_scale = std::abs(c.stuck_single) * (c.inv_mass[0] + c.inv_mass[1]);
  c.c_abs = std::max(std::abs(c.c_diag[0]), std::abs(c.c_diag[1]));
  c.k_abs = std::max(std::abs(c.k0_di0) + std::abs(c.k0_up0), std::abs(c.k0_lo0) + std::abs(c.k0_di1));
  for (const auto& el : m.zener) c.k_abs += 2.0 * std::abs(el.stiffness);
  c.contact_abs = std::abs(c.contact_bt[0]) + std::abs(c.contact_bt[1]);
  c.g00 = m.g_all(0, 0);
  c.fi = m.fi[0];
  c.fj = m.fj[0];
  c.pi = m.pi[0];
  c.pj = m.pj[0];
  c.n_zener = static_cast<int>(m.zener.size());
  for (int e = 0; e < c.n_zener; ++e) {
    const auto& el = m.zener[static_cast<std::size_t>(e)];
    const auto u = static_cast<std::size_t>(e);
    c.zener[e] = {el.pair.i >= 0 ? el.pair.i : 2, el.pair.j >= 0 ? el.pair.j : 2, el.storey, el.stiffness, ws.zener_scale[u],
                  ws.zener_kx[u],                  ws.zener_tf[u]};
  }
  c.n_contacts = static_cast<int>(m.s.contacts.size());
  for (int k = 0; k < c.n_contacts; ++k) {
    const Pair& pair_k = m.contact_pair[static_cast<std::size_t>(k)];
    c.contact_gap[k] = m.s.contacts[static_cast<std::size_t>(k)].gap;
    c.contact_i[k] = pair_k.i >= 0 ? pair_k.i : 2;
    c.contact_j[k] = pair_k.j >= 0 ? pair_k.j : 2;
  }
  for (int k = 0; k < 2; ++k) {
    const auto& list = m.damper_zener[static_cast<std::size_t>(k)];
    c.n_trial_zener[k] = static_cast<int>(list.size());
    for (std::size_t a = 0; a < list.size(); ++a) {
      c.trial_zener[k][a] = list[a].first;
      c.trial_sign[k][a] = list[a].second;
    }
  }
  c.plain = plain_pair(c);
  switch (c.n_zener) {  // (the loops over the Zener elements unrolled for the usual counts)
    case 0: advance_ = c.plain ? &PairStepper::advance_with<0, true> : &PairStepper::advance_with<0, false>; break;
    case 1: advance_ = &PairStepper::advance_with<1, false>; break;
    case 2: advance_ = c.plain ? &PairStepper::advance_with<2, true> : &PairStepper::advance_with<2, false>; break;
    default: advance_ = &PairStepper::advance_with<-1, false>;
  }
  PairCarry& cr = carry;
  for (int k = 0; k < 2; ++k) {
    cr.internal[k] = ws.internal[k];
    cr.cv_now[k] = ws.cv_now[k];
  }
  cr.stick_prev = cr.stick_now = 0.0;
  cr.w_prev = 0.0;
  cr.stick_start_t = ws.stick_start_t[0];
  cr.stick_start_q = ws.stick_start_q[0];
  cr.prev_stuck = cr.prev_same_slip = false;
  cr.state = ws.states[0];
  // (The states' hyst, hyst_yield and storey_force have their two entries from start(): the
  // storeys' z stays 0 and is not written per step.)
}

// decide_dampers for the one damper: the trial, its grid force, decide_stuck or
// decide_slipping, the step force; returns it, the damper's state in `decided`.
double PairStepper::decide(const StructureState& now, const PairTheta& th, bool restart, const double* offsets, Step& s,
                           DamperState& decided) {
  const PairConstants& c = pc;
  const Phase ph = now.link_phase[0];
  const double lim = c.limit, single = th.single;
  const bool hold = ph == Phase::stick;
  const double fixed = hold ? 0.0 : (ph == Phase::slip_right ? lim : -lim);
  const double q_trial = hold ? single * s.w_free : fixed;
  // trial_state: both floors' v, x, C v and P under q_trial.
  double tc[4];
  for (int r = 0; r < 4; ++r) tc[r] = th.trial[r] * q_trial;
  const double *x0 = now.x.data(), *v0 = now.v.data();
  double v1[2], x1[3], cv1[2], p1[2];
  if (!restart) {
    for (int k = 0; k < 2; ++k) v1[k] = s.vf[k] + tc[k] * c.minus_h;
    for (int k = 0; k < 2; ++k) x1[k] = x0[k] + c.half_h * (v0[k] + v1[k]);
  } else {
    for (int k = 0; k < 2; ++k) {
      v1[k] = s.vf[k] - c.h * tc[k];
      x1[k] = x0[k] + c.h * v1[k];
    }
  }
  x1[2] = 0.0;
  const double p_rows[2] = {(0.0 + c.k0_di0 * x1[0]) + c.k0_up0 * x1[1], (0.0 + c.k0_lo0 * x1[0]) + c.k0_di1 * x1[1]};
  for (int k = 0; k < 2; ++k) {
    cv1[k] = s.cvf[k] - c.h * tc[2 + k];
    p1[k] = p_rows[k] + c.contact_bt[k];
    for (int a = 0; a < c.n_trial_zener[k]; ++a) {
      const int e = c.trial_zener[k][a];
      const PairZener& z = c.zener[e];
      p1[k] += c.trial_sign[k][a] * (z.stiffness * (x1[z.i] - x1[z.j]) + offsets[e]);
    }
  }
  // grid_force_single at the trial's end: only the stuck force is read (a slipping damper's
  // would_stick sets its own force aside).
  double stick1 = 0.0;
  grid_force(cv1, p1, ph, &stick1);
  const double w1 = v1[c.fi] - v1[c.fj];
  bool hold2 = true;
  double fixed2 = 0.0;
  if (hold) decide_stuck(now, stick1, s, hold2, fixed2, decided);
  else decide_slipping(now, fixed, w1, cv1, p1, s, hold2, fixed2, decided);
  double q_step = hold2 == hold && fixed2 == fixed ? q_trial : (hold2 ? single * s.w_free : fixed2);
  if (std::isnan(s.onset)) return q_step;
  // A starting damper that the others leave no room to slip stays stuck this step (the
  // general step's Eigen product, through its work vectors).
  ws.w_free[0] = s.w_free;
  ws.q_step[0] = q_step;
  ws.w_end.noalias() = ws.w_free - (restart ? m.backward : m.trapezoidal)->delassus * ws.q_step;
  if (ws.w_end[0] * fixed2 <= 0.0) {
    s.onset = kNaN;
    decided = DamperState::stick;
    q_step = single * s.w_free;
  }
  return q_step;
}
// decide_stuck for the one damper (stick1: its stuck force at the trial's end).
void PairStepper::decide_stuck(const StructureState& now, double stick1, Step& s, bool& hold2, double& fixed2, DamperState& decided) {
  const PairCarry& cr = carry;
  const double lim = pc.limit, h = pc.h;
  const double q_now = cr.stick_now;
  if (std::abs(q_now) > lim) {  // beyond the cone at t_n already: slipping since before t_n
    const double d = q_now > 0.0 ? 1.0 : -1.0;
    if (cr.stick_start_t > now.t - h) {
      const double r = (d * lim - cr.stick_start_q) / (q_now - cr.stick_start_q);
      s.onset = (cr.stick_start_t + std::clamp(r, 0.0, 1.0) * (now.t - cr.stick_start_t) - now.t) / h;
    } else {
      s.onset = std::min(locate_onset(d * lim, cr.prev_stuck, cr.stick_prev, q_now, stick1, -1.0), 0.0);
    }
    hold2 = false;
    fixed2 = d * lim;
    decided = d > 0.0 ? DamperState::slip_positive : DamperState::slip_negative;
  } else if (std::abs(stick1) > lim) {
    const double d = stick1 > 0.0 ? 1.0 : -1.0;
    const double theta = locate_onset(d * lim, cr.prev_stuck, cr.stick_prev, q_now, stick1, 0.0);
    s.onset = theta;
    hold2 = false;
    fixed2 = theta * 0.5 * (q_now + d * lim) + (1.0 - theta) * d * lim;
    decided = d > 0.0 ? DamperState::slip_positive : DamperState::slip_negative;
  } else {
    hold2 = true;
    fixed2 = 0.0;
    decided = DamperState::stick;
  }
}
// decide_slipping for the one damper (fixed: its force +-F; w1, cv1, p1: the trial's end).
void PairStepper::decide_slipping(const StructureState& now, double fixed, double w1, const double* cv1, const double* p1, Step& s,
                                  bool& hold2, double& fixed2, DamperState& decided) {
  PairCarry& cr = carry;
  const double lim = pc.limit;
  const double d = fixed > 0.0 ? 1.0 : -1.0;
  const double w_now = now.link_velocity[0];
  if (w1 * d > 0.0) {  // slips on
    hold2 = false;
    fixed2 = d * lim;
    decided = cr.state;
    return;
  }
  const double theta = cr.prev_same_slip ? locate_onset(0.0, true, cr.w_prev, w_now, w1, 0.0)
                       : (w_now != w1 ? std::clamp(w_now / (w_now - w1), 0.0, 1.0) : 1.0);
  s.crossing = theta;
  // would_stick: the others' forces are none (one damper), so B' q = 0 in relative_accel.
  const double s0 = relative_accel(cr.cv_now, cr.internal, 0.0) / pc.g00;
  const double s1 = relative_accel(cv1, p1, 0.0) / pc.g00;
  const double at = s0 + theta * (s1 - s0);
  s.kink_theta = theta;
  if (std::abs(at) <= lim) {
    hold2 = true;
    fixed2 = 0.0;
    decided = DamperState::stick;
    cr.stick_start_t = now.t + theta * pc.h;
    cr.stick_start_q = at;
    s.kink_jump = at - d * lim;
  } else {
    hold2 = false;
    fixed2 = lim * d * (2.0 * theta - 1.0);
    decided = d > 0.0 ? DamperState::slip_negative : DamperState::slip_positive;
    s.kink_jump = -2.0 * d * lim;
  }
}
// relative_accel for the one damper with B' q's entries btq (the same at both floors' rows
// here: 0 in every call but report's, which writes its own).
double PairStepper::relative_accel(const double* cv, const double* p, double btq) const {
  const int i = pc.fi, j = pc.fj;
  const double at_i = (-cv[i] - p[i] - btq) * pc.inv_mass[i];
  return at_i - (-cv[j] - p[j] - btq) * pc.inv_mass[j];
}
// grid_force_single: the damper's grid force in phase ph (and its stuck force, 0 unless stuck).
double PairStepper::grid_force(const double* cv, const double* p, Phase ph, double* stick) const {
  *stick = 0.0;
  if (ph != Phase::stick) return ph == Phase::slip_right ? pc.limit : -pc.limit;
  const double x = pc.stuck_single * relative_accel(cv, p, 0.0);
  *stick = x;
  return std::clamp(x, -pc.limit, pc.limit);
}

}  // namespace adjoin::detail
