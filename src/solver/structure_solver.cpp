#include "adjoin/solver/structure_solver.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "adjoin/errors.hpp"
#include "adjoin/fractional/weights.hpp"
#include "adjoin/model/units.hpp"
#include "adjoin/structure/modal.hpp"
#include "box_qp.hpp"
#include "onset.hpp"
#include "rod_law.hpp"

namespace adjoin {
namespace {

using structure::DeviceType;
using structure::LinkType;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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
  if (t_end / h > 1e9) return fail("solver.t_end / solver.h exceeds 1e9 steps");
  return true;
}

StructureRunSummary simulate_structure(const StructureSolverOptions& options, const structure::Structure& s,
                                       const GroundMotion& ground, StructureObserver& observer) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  if (!s.IsValid(&error)) throw InputError(error);
  const auto start = std::chrono::steady_clock::now();
  const double h = options.h;
  const std::size_t n_steps = options.steps();
  const int n = s.dofs();

  // ---- assembly: M, C, elastic K0, Zener elements, friction links ----
  Eigen::VectorXd mass(n);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, n), k0 = Eigen::MatrixXd::Zero(n, n);
  std::vector<ZenerElement> zener;
  std::map<double, std::vector<double>> weights;  // per order
  auto zener_law = [&](const structure::Zener& z) {
    auto& w = weights[z.order];
    if (w.empty()) w = bdf2_weights(z.order, n_steps + 2);
    return std::make_unique<detail::RodLaw>(rod_of(z), z.k, h, options.history, w);
  };
  auto add_building = [&](const structure::Building& b, int offset) {
    const int nb = b.floors();
    mass.segment(offset, nb) = b.masses;
    c.block(offset, offset, nb, nb) = structure::inherent_damping_matrix(b) + structure::dashpot_matrix(b);
    for (int st = 0; st < nb; ++st) Pair{offset + st, st > 0 ? offset + st - 1 : -1}.add(k0, b.springs[st]);
    for (const auto& d : b.devices)
      for (int st : d.storeys) {
        const Pair p{offset + st - 1, st > 1 ? offset + st - 2 : -1};
        if (d.type == DeviceType::spring) p.add(k0, d.k);
        if (d.type == DeviceType::zener) zener.push_back({p, offset + st - 1, zener_law(d.zener), 0.0});
      }
  };
  add_building(s.a, 0);
  if (s.b) add_building(*s.b, s.a.floors());
  std::vector<Pair> link_pair;
  std::vector<int> friction;  // link indices
  for (std::size_t l = 0; l < s.links.size(); ++l) {
    const auto& link = s.links[l];
    const Pair p{s.dof('A', link.floor_a), s.dof('B', link.floor_b)};
    link_pair.push_back(p);
    if (link.type == LinkType::spring) p.add(k0, link.k);
    if (link.type == LinkType::dashpot) p.add(c, link.c);
    if (link.type == LinkType::zener) zener.push_back({p, -1, zener_law(link.zener), 0.0});
    if (link.type == LinkType::friction) friction.push_back(static_cast<int>(l));
  }
  // Zener links come after the storey devices in `zener`; remember where each link's is.
  std::vector<int> link_zener(s.links.size(), -1);
  {
    int z = static_cast<int>(zener.size());
    for (int l = static_cast<int>(s.links.size()) - 1; l >= 0; --l)
      if (s.links[l].type == LinkType::zener) link_zener[l] = --z;
  }
  Eigen::MatrixXd k_eff = k0;
  for (const auto& e : zener) e.pair.add(k_eff, e.law->stiffness());
  const Eigen::MatrixXd a_step = Eigen::MatrixXd(mass.asDiagonal()) + 0.5 * h * c + 0.25 * h * h * k_eff;
  const Eigen::LDLT<Eigen::MatrixXd> a_solver(a_step);
  if (a_solver.info() != Eigen::Success) throw NumericalError("the step matrix M + h/2 C + h^2/4 K is not positive definite", 0.0);
  const int nf = static_cast<int>(friction.size());
  Eigen::MatrixXd bf = Eigen::MatrixXd::Zero(nf, n);
  Eigen::VectorXd limit(nf);
  for (int f = 0; f < nf; ++f) {
    const Pair& p = link_pair[friction[f]];
    bf(f, p.i) = 1.0;
    bf(f, p.j) = -1.0;
    limit[f] = s.links[friction[f]].slip_force;
  }
  // No friction link (a building alone): nothing to solve, and Eigen's triangular solve must
  // not see a matrix with no columns (it binds a reference to its null data).
  const Eigen::MatrixXd a_inv_bt = nf > 0 ? Eigen::MatrixXd(a_solver.solve(bf.transpose())) : Eigen::MatrixXd(n, 0);
  const Eigen::MatrixXd delassus = nf > 0 ? Eigen::MatrixXd(h * bf * a_inv_bt) : Eigen::MatrixXd(0, 0);
  // For the grid-point forces of stuck dampers: B M^-1 B' restricted to the stuck ones.
  const Eigen::VectorXd inv_mass = mass.cwiseInverse();

  observer.begin(s, options);
  const double g = kStandardGravity;
  StructureState now;
  now.t = 0.0;
  now.x = now.v = Eigen::VectorXd::Zero(n);
  now.ag = g * ground.ag(0.0);
  now.link_force = now.link_stroke = now.link_velocity = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.links.size()));
  now.link_phase.assign(s.links.size(), Phase::stick);
  now.link_switch.assign(s.links.size(), kNaN);
  for (auto& e : zener) e.law->commit(0.0, 0.0);

  std::vector<detail::DamperState> states(nf, detail::DamperState::stick);
  Eigen::VectorXd internal = Eigen::VectorXd::Zero(n);  // storey and link forces (not friction) at t_n
  Eigen::VectorXd friction_now = Eigen::VectorXd::Zero(nf);
  Eigen::VectorXd stick_force_now = Eigen::VectorXd::Zero(nf);  // the force that keeps each damper stuck
  Eigen::VectorXd stick_force_prev = Eigen::VectorXd::Zero(nf);
  std::vector<bool> prev_stuck(nf, false);            // the grid point before `now` was stuck
  std::vector<bool> prev_same_slip(nf, false);        // ... slipped as `now` does, with velocity:
  std::vector<double> w_prev(nf, 0.0);
  std::vector<double> stick_start_t(nf, -INFINITY), stick_start_q(nf, 0.0);  // the last stick's start

  // Grid-point forces: slipping dampers at +-F; the stuck ones carry what keeps their relative
  // acceleration zero, (B_s M^-1 B_s') q_s = B_s M^-1 (M 1 a_g - C v - P - B_l' q_l) (the ground
  // term cancels: B 1 = 0). Also returns each damper's stick force (unclamped) for onsets.
  auto grid_forces = [&](const Eigen::VectorXd& v, const Eigen::VectorXd& p, const std::vector<Phase>& phase,
                         Eigen::VectorXd* q, Eigen::VectorXd* stick) {
    q->setZero(nf);
    std::vector<int> stuck;
    for (int f = 0; f < nf; ++f) {
      if (phase[friction[f]] == Phase::stick) stuck.push_back(f);
      else (*q)[f] = phase[friction[f]] == Phase::slip_right ? limit[f] : -limit[f];
    }
    Eigen::VectorXd rhs = -(c * v) - p - bf.transpose() * (*q);
    rhs = rhs.cwiseProduct(inv_mass);
    stick->setZero(nf);
    if (stuck.empty()) return;
    const int m = static_cast<int>(stuck.size());
    Eigen::MatrixXd a(m, m);
    Eigen::VectorXd b(m);
    for (int i = 0; i < m; ++i) {
      b[i] = bf.row(stuck[i]).dot(rhs);
      for (int j = 0; j < m; ++j) a(i, j) = (bf.row(stuck[i]).cwiseProduct(inv_mass.transpose())).dot(bf.row(stuck[j]));
    }
    const Eigen::VectorXd qs = a.ldlt().solve(b);
    for (int i = 0; i < m; ++i) {
      (*stick)[stuck[i]] = qs[i];
      (*q)[stuck[i]] = std::clamp(qs[i], -limit[stuck[i]], limit[stuck[i]]);
    }
  };
  // The force that would keep slipping damper f stuck at this instant, the others at their
  // forces q: b_f M^-1 (-C v - P - sum_{g != f} b_g q_g) / (b_f M^-1 b_f').
  auto would_stick = [&](const Eigen::VectorXd& v, const Eigen::VectorXd& p, const Eigen::VectorXd& q, int f) {
    Eigen::VectorXd others = q;
    others[f] = 0.0;
    const Eigen::VectorXd rhs = (-(c * v) - p - bf.transpose() * others).cwiseProduct(inv_mass);
    return bf.row(f).dot(rhs) / bf.row(f).cwiseProduct(inv_mass.transpose()).dot(bf.row(f));
  };

  // Storey forces: the storey springs, spring and dashpot devices, Zener devices.
  std::vector<double> storey_spring(n, 0.0), storey_dashpot(n, 0.0);
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
  auto fill_storeys = [&](StructureState& st) {
    st.storey_force.resize(n);
    auto building = [&](const structure::Building& b, int offset) {
      for (int i = 0; i < b.floors(); ++i) {
        const Pair p{offset + i, i > 0 ? offset + i - 1 : -1};
        st.storey_force[offset + i] = storey_spring[offset + i] * p.of(st.x) + storey_dashpot[offset + i] * p.of(st.v);
      }
    };
    building(s.a, 0);
    if (s.b) building(*s.b, s.a.floors());
    for (const auto& e : zener)
      if (e.storey >= 0) st.storey_force[e.storey] += e.force;
  };
  auto fill_links = [&](StructureState& st, const Eigen::VectorXd& q_friction) {
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
  };
  now.a_abs = Eigen::VectorXd::Zero(n);
  fill_links(now, friction_now);
  now.a_abs.setConstant(-now.ag);  // at rest: the floors move with the ground
  observer.observe(now);

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
  // the stuck force reaches the limit continuously, no kink.
  const auto integrate_kinks = [&](const std::vector<detail::DamperState>& after, const std::vector<double>& kink_theta,
                                   const std::vector<double>& kink_jump, Eigen::VectorXd* x) {
    std::vector<int> held;
    for (int f = 0; f < nf; ++f)
      if (after[f] == detail::DamperState::stick && std::isnan(kink_theta[f])) held.push_back(f);
    const Eigen::MatrixXd g_all = bf * inv_mass.asDiagonal() * bf.transpose();
    const int m = static_cast<int>(held.size());
    Eigen::MatrixXd g_held(m, m);
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) g_held(a, b) = g_all(held[a], held[b]);
    Eigen::LDLT<Eigen::MatrixXd> held_solver;
    if (m > 0) held_solver.compute(g_held);  // (never on an empty matrix: see a_inv_bt above)
    for (int f = 0; f < nf; ++f) {
      if (std::isnan(kink_theta[f])) continue;
      Eigen::VectorXd dq = Eigen::VectorXd::Zero(nf);
      dq[f] = kink_jump[f];
      if (m > 0) {
        Eigen::VectorXd rhs(m);
        for (int a = 0; a < m; ++a) rhs[a] = -g_all(held[a], f) * kink_jump[f];
        const Eigen::VectorXd response = held_solver.solve(rhs);
        for (int a = 0; a < m; ++a) dq[held[a]] = response[a];
      }
      const double theta = kink_theta[f];
      *x += (0.5 * h * h * theta * (1.0 - theta)) * inv_mass.cwiseProduct(bf.transpose() * dq);
    }
  };

  for (std::size_t step = 0; step < n_steps; ++step) {
    StructureState next = now;
    next.t = static_cast<double>(step + 1) * h;
    next.ag = g * ground.ag(next.t);
    Eigen::VectorXd offsets = Eigen::VectorXd::Zero(n);
    for (const auto& e : zener) e.pair.add(offsets, e.law->offset());
    const Eigen::VectorXd predicted = now.x + 0.5 * h * now.v;
    const Eigen::VectorXd rhs = mass.cwiseProduct(now.v) +
                                0.5 * h * (mass * (now.ag + next.ag) - c * now.v - internal - k_eff * predicted - offsets);
    const Eigen::VectorXd v_free = a_solver.solve(rhs);
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
    Eigen::VectorXd q_step = Eigen::VectorXd::Zero(nf);
    std::vector<double> onset(nf, kNaN), crossing(nf, kNaN);
    std::vector<double> kink_theta(nf, kNaN), kink_jump(nf, 0.0);  // slips ended in the step
    const Eigen::VectorXd w_free = bf * v_free;
    auto end_state = [&](const Eigen::VectorXd& q, Eigen::VectorXd* v, Eigen::VectorXd* x, Eigen::VectorXd* p) {
      *v = v_free - h * a_inv_bt * q;
      *x = now.x + 0.5 * h * (now.v + *v);
      *p = k0 * *x;
      for (const auto& e : zener) e.pair.add(*p, e.law->force(e.pair.of(*x)));
    };
    // Solves for the held dampers (limit infinite) with the others' step forces fixed.
    auto solve_held = [&](const std::vector<bool>& hold, const Eigen::VectorXd& fixed) {
      Eigen::VectorXd w0 = w_free, lim = Eigen::VectorXd::Zero(nf);
      for (int f = 0; f < nf; ++f) {
        if (hold[f]) lim[f] = std::numeric_limits<double>::infinity();
        else w0 -= delassus.col(f) * fixed[f];
      }
      Eigen::VectorXd q = detail::solve_box_qp(delassus, w0, lim, states).q;
      for (int f = 0; f < nf; ++f)
        if (!hold[f]) q[f] = fixed[f];
      return q;
    };
    std::vector<detail::DamperState> decided(nf, detail::DamperState::stick);
    if (nf > 0 && step == 0) {  // from rest: the closed-form relay of the box QP
      const detail::BoxQpResult r = detail::solve_box_qp(delassus, w_free, limit, states);
      q_step = r.q;
      decided = r.state;
    } else if (nf > 0) {
      std::vector<bool> hold(nf, false);
      Eigen::VectorXd fixed = Eigen::VectorXd::Zero(nf);
      for (int f = 0; f < nf; ++f) {
        const Phase ph = now.link_phase[friction[f]];
        hold[f] = ph == Phase::stick;
        if (!hold[f]) fixed[f] = ph == Phase::slip_right ? limit[f] : -limit[f];
      }
      const Eigen::VectorXd q_trial = solve_held(hold, fixed);
      Eigen::VectorXd v1, x1, p1, q1(nf), stick1(nf);
      end_state(q_trial, &v1, &x1, &p1);
      std::vector<Phase> phase1 = now.link_phase;
      grid_forces(v1, p1, phase1, &q1, &stick1);
      const Eigen::VectorXd w1 = bf * v1;
      std::vector<bool> hold2(nf, false);
      Eigen::VectorXd fixed2 = Eigen::VectorXd::Zero(nf);
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
          const double s0 = would_stick(now.v, internal, friction_now, f);
          const double s1 = would_stick(v1, p1, q1, f);
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
      q_step = solve_held(hold2, fixed2);
      // A starting damper that the others leave no room to slip stays stuck this step.
      const Eigen::VectorXd w_end = w_free - delassus * q_step;
      bool again = false;
      for (int f = 0; f < nf; ++f)
        if (!std::isnan(onset[f]) && w_end[f] * fixed2[f] <= 0.0) {
          hold2[f] = true;
          onset[f] = kNaN;
          decided[f] = detail::DamperState::stick;
          again = true;
        }
      if (again) q_step = solve_held(hold2, fixed2);
    }
    states = decided;
    next.v = v_free - h * a_inv_bt * q_step;
    // Stick exact: a stuck damper's two floors get one velocity, bit for bit (their
    // mass-weighted mean, which moves them by rounding only).
    for (int pass = 0; pass < 2; ++pass)
      for (int f = 0; f < nf; ++f)
        if (states[f] == detail::DamperState::stick) {
          const Pair& p = link_pair[friction[f]];
          const double v = (mass[p.i] * next.v[p.i] + mass[p.j] * next.v[p.j]) / (mass[p.i] + mass[p.j]);
          next.v[p.i] = next.v[p.j] = v;
        }
    next.x = now.x + 0.5 * h * (now.v + next.v);
    if (step > 0 && std::any_of(kink_theta.begin(), kink_theta.end(), [](double t) { return !std::isnan(t); }))
      integrate_kinks(states, kink_theta, kink_jump, &next.x);
    Eigen::VectorXd p_next = k0 * next.x;
    for (auto& e : zener) {
      const double d = e.pair.of(next.x);
      e.force = e.law->force(d);
      e.pair.add(p_next, e.force);
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
    }
    Eigen::VectorXd q_grid(nf), stick_grid(nf);
    grid_forces(next.v, p_next, next.link_phase, &q_grid, &stick_grid);
    // Absolute accelerations at the grid point: x'' - a_g.
    const Eigen::VectorXd force = mass * next.ag - c * next.v - p_next - bf.transpose() * q_grid;
    next.a_abs = force.cwiseProduct(inv_mass) - Eigen::VectorXd::Constant(n, next.ag);
    fill_links(next, q_grid);
    if (!(next.x.allFinite() && next.v.allFinite()) || next.x.cwiseAbs().maxCoeff() > 1e6) {
      std::ostringstream m;
      m << "the response became " << (next.x.allFinite() ? "larger than 1e6 m" : "non-finite") << " at t = " << next.t
        << " s at solver.h = " << h << " s; check the ground motion's scale and the structure's units";
      throw NumericalError(m.str(), next.t);
    }
    for (auto& e : zener) e.law->commit(e.pair.of(next.x), e.force);
    observer.observe(next);
    internal = p_next;
    friction_now = q_grid;
    stick_force_prev = stick_force_now;
    stick_force_now = stick_grid;
    for (int f = 0; f < nf; ++f) {
      const Phase ph = now.link_phase[friction[f]];
      prev_stuck[f] = ph == Phase::stick && step > 0;
      prev_same_slip[f] = step > 0 && ph != Phase::stick && next.link_phase[friction[f]] == ph;
      w_prev[f] = now.link_velocity[friction[f]];
    }
    now = std::move(next);
  }
  observer.end();
  StructureRunSummary summary;
  summary.steps = n_steps;
  for (const auto& e : zener) summary.history_bytes += e.law->bytes();
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace adjoin
