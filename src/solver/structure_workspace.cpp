#include "structure_workspace.hpp"

#include <cmath>

namespace adjoin::detail {
namespace {

// The Zener elements' histories (with soe, the elements of one order share a SoeBank: stepped
// together, four elements per vector operation) and their laws' numbers.
void make_zener_laws(const StructureModel& m, StepWorkspace& ws) {
  std::vector<double> orders;
  for (const ZenerElement& e : m.zener) {
    const double w0 = e.rod.elastic ? 1.0 : convolution_weights(m.weight_rule(), e.rod.order, 1)[0];
    const RodLaw law(e.rod, e.k, m.h, w0, nullptr);
    ws.zener_scale.push_back(law.history_scale());
    ws.zener_kx.push_back(law.value_of_x());
    ws.zener_tf.push_back(law.value_of_f());
    orders.push_back(e.rod.elastic ? std::nan("") : e.rod.order);
  }
  ws.histories = HistorySet(m.options.history, m.weight_rule(), orders, m.n_steps + 2, m.options.history_tolerance);
  ws.zener_value.assign(m.zener.size(), 0.0);
}

}  // namespace

StepWorkspace::StepWorkspace(const StructureModel& m) {
  const int n = m.n, nf = m.nf, nc = m.nc;
  make_zener_laws(m, *this);
  zener_force.assign(m.zener.size(), 0.0);
  contact_memory.resize(static_cast<std::size_t>(nc));
  box_qp_trapezoidal = std::make_unique<BoxQp>(m.trapezoidal->qp_matrix);
  if (m.backward) box_qp_backward = std::make_unique<BoxQp>(m.backward->qp_matrix);
  bilinear_layout = BilinearLayout(m.bilinear);
  bilinear = BilinearStates(bilinear_layout);
  bilinear_plastic.reserve(static_cast<std::size_t>(m.nh));
  bilinear_active.reserve(static_cast<std::size_t>(m.nh));
  if (m.nh > 0 && nf > 0) {
    box_qp_friction = std::make_unique<BoxQp>(m.trapezoidal->delassus.topLeftCorner(nf, nf));
    states_friction.assign(nf, DamperState::stick);
    w_friction.resize(nf);
  }
  sm = m.trapezoidal.get();
  box_qp = box_qp_trapezoidal.get();
  // The stuck dampers' systems (B_s M^-1 B_s'), inverted per stuck set (a product with the
  // inverse of this small, well conditioned matrix is as accurate as a solve and much faster
  // than a dynamic-size LDLT solve).
  stuck_systems = SubsetInverses(m.g_all);

  // The contact pairs' vectors.
  contact_impulse = contact_moment = contact_end_force = Eigen::VectorXd::Zero(nc);
  contact_bt_now = contact_bt = total_now = Eigen::VectorXd::Zero(n);
  total_next.resize(n);
  contact_work.assign(static_cast<std::size_t>(nc), 0.0);
  step_work.assign(static_cast<std::size_t>(nc), 0.0);
  v_free0.resize(n);
  cv_free0.resize(n);
  step_impacts.reserve(16);

  // The step's work vectors and the state carried from step to step.
  trial_change.resize(m.nt + m.nd);
  btq_dampers.resize(m.nd);
  offsets.resize(static_cast<Eigen::Index>(m.zener.size()));
  response_q.resize(2 * n);
  off_dof = Eigen::VectorXd::Zero(n);
  for (Eigen::VectorXd* v : {&rhs, &v_free, &cv_free, &v1, &x1, &p1, &cv1, &p_next, &cv_next, &v_pre, &bq}) v->resize(n);
  for (Eigen::VectorXd* v : {&q1, &stick1, &w1, &q_grid, &stick_grid, &others}) v->resize(nf);
  // (the QP's: the dampers' entries, then the bilinear elements')
  for (Eigen::VectorXd* v : {&w_free, &w_end, &q_step, &q_trial, &fixed, &fixed2}) v->setZero(m.nq);
  for (std::vector<double>* v : {&onset, &crossing, &kink_theta, &kink_jump}) v->resize(nf);
  decided.assign(m.nq, DamperState::stick);
  hold.assign(m.nq, 0);
  nonzero.assign(static_cast<std::size_t>(m.nq), 0);
  candidates.reserve(static_cast<std::size_t>(m.nq));
  hold2.assign(m.nq, 0);
  touched.reserve(2 * static_cast<std::size_t>(nf));
  touched_flag.assign(m.damper_dofs.size(), 0);
  states.assign(m.nq, DamperState::stick);
  internal = Eigen::VectorXd::Zero(n);
  for (Eigen::VectorXd* v : {&viscous_q, &viscous_w_pass, &viscous_w0, &viscous_w1, &viscous_wt, &viscous_force, &viscous_q_new})
    *v = Eigen::VectorXd::Zero(m.nv);
  viscous_bt = Eigen::VectorXd::Zero(n);
  if (m.nv > 0) {
    viscous_solver = std::make_unique<ViscousSolver>(m.viscous_laws);
    v_base.resize(n);
    cv_base.resize(n);
    states_before.resize(static_cast<std::size_t>(nf));
    memory_saved.resize(static_cast<std::size_t>(nc));
    contact_work_saved.resize(static_cast<std::size_t>(nc));
    bilinear_saved = BilinearStates(bilinear_layout);
  }
  bouc_wen.assign(static_cast<std::size_t>(m.nw), BoucWenState{});
  for (Eigen::VectorXd* v : {&bouc_wen_q, &bouc_wen_q_new, &bouc_wen_w1, &bouc_wen_w_pass, &bouc_wen_wt}) *v = Eigen::VectorXd::Zero(m.nw);
  if (m.nw > 0) {
    bouc_wen_solver = std::make_unique<BoucWenSolver>(m.nw);
    bouc_wen_v_base.resize(n);
    bouc_wen_cv_base.resize(n);
  }
  friction_now = stick_force_now = stick_force_prev = Eigen::VectorXd::Zero(nf);
  prev_stuck.assign(nf, false);
  prev_same_slip.assign(nf, false);
  w_prev.assign(nf, 0.0);
  stick_start_t.assign(nf, -INFINITY);
  stick_start_q.assign(nf, 0.0);
}

}  // namespace adjoin::detail
