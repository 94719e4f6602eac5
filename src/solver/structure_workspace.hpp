#pragma once
// The structure stepper's per-run part (internal to the solver; the Data of Pinocchio's
// Model/Data split): what changes from step to step — the Zener elements' laws with their
// histories, the dampers' and contact pairs' states, the forces carried from t_n to t_n+1,
// the two grid states — and the step's work vectors, all sized once from the model, so that a
// step allocates nothing (but the box QP's small systems when a stuck set is first met).
#include <Eigen/Dense>
#include <deque>
#include <memory>
#include <vector>

#include "adjoin/fractional/history_set.hpp"
#include "adjoin/structure/state.hpp"
#include "bilinear_lanes.hpp"
#include "box_qp.hpp"
#include "contact_step.hpp"
#include "rod_law.hpp"
#include "structure_model.hpp"

namespace adjoin::detail {

struct StepWorkspace {
  explicit StepWorkspace(const StructureModel& m);

  // ---- the elements' and dampers' memory ----
  // The Zener elements' histories, stepped together (fractional/history_set.hpp), and their laws
  // (rod_law.hpp) side by side: element e's force is its stiffness x + zener_scale[e] (its lag
  // sum + 0), and it pushes zener_kx[e] x - zener_tf[e] f, as RodLaw's offset() and commit().
  HistorySet histories;
  std::vector<double> zener_scale, zener_kx, zener_tf;
  std::vector<double> zener_value;  // the step's values pushed
  std::vector<double> zener_force;  // per Zener element, its force at t_n+1 (then t_n)
  std::vector<ContactMemory> contact_memory, memory_before;  // per contact pair with a law; before the step
  std::unique_ptr<BoxQp> box_qp_trapezoidal, box_qp_backward;  // the dampers' QP of each step matrix
  SubsetInverses stuck_systems;  // B_s M^-1 B_s' per stuck set, inverted when first met
  BilinearLayout bilinear_layout;  // the model's bilinear elements as arrays (bilinear_lanes.hpp)
  BilinearStates bilinear;         // ... and their states
  int bilinear_trial_failed = 0;   // how many failed the first test at the trial's end (decide_bilinear)
  bool bilinear_slipped = true;         // some element's slip u_p changed in the last step (its offsets with it)
  std::vector<int> bilinear_plastic;    // the elements slipping at t_n, ascending
  bool bilinear_event = false;          // an element yielded or unloaded in this step's decisions
  std::vector<int> bilinear_active;     // ... and those this step decided on (slipping, or leaving the elastic range), ascending
  // With bilinear elements, the dampers' own QP for the first step (from rest the elements are
  // elastic: no unknowns).
  std::unique_ptr<BoxQp> box_qp_friction;
  std::vector<DamperState> states_friction;
  Eigen::VectorXd w_friction;

  // ---- this step ----
  bool restart = false;            // backward Euler
  int restart_left = 0;            // backward-Euler steps still to take
  const StepMatrices* sm = nullptr;  // this step's matrices
  BoxQp* box_qp = nullptr;         // ... and their QP
  bool any_contact = false;        // a contact pair touched in the step

  // ---- the state carried from step to step ----
  std::vector<DamperState> states;
  Eigen::VectorXd internal;  // storey and link forces (not friction) at t_n
  Eigen::VectorXd cv_now;    // C v at t_n
  Eigen::VectorXd friction_now;
  Eigen::VectorXd stick_force_now;  // the force that keeps each damper stuck
  Eigen::VectorXd stick_force_prev;
  std::vector<char> prev_stuck;      // the grid point before `now` was stuck
  std::vector<char> prev_same_slip;  // ... slipped as `now` does, with velocity:
  std::vector<double> w_prev;
  std::vector<double> stick_start_t, stick_start_q;  // the last stick's start
  std::vector<double> contact_work;                  // per contact pair with a law: its work so far
  Eigen::VectorXd contact_bt_now, total_now;         // B_c' p and all forces at t_n (with contacts)

  // ---- the step's work vectors (char, not the bit-packed vector<bool>: read in every step) ----
  Eigen::VectorXd offsets;  // each Zener element's f - k_eff d
  Eigen::VectorXd response_q, off_dof, rhs, v_free, cv_free, v1, x1, p1, cv1, p_next, cv_next, v_pre;
  Eigen::VectorXd bq, w_free, w_end, q_step, q_trial, q1, stick1, w1;
  Eigen::VectorXd fixed, fixed2, q_grid, stick_grid, others;
  std::vector<double> onset, crossing, kink_theta, kink_jump;
  std::vector<DamperState> decided;
  std::vector<char> hold, hold2;
  std::vector<int> touched;
  std::vector<char> touched_flag;  // per damper_dofs entry
  std::vector<int> stuck;
  std::vector<int> nonzero;     // the QP's unknowns with a nonzero step force (sparse_columns)
  std::vector<int> candidates;  // ... that may be held or fixed (solve_held)
  Eigen::VectorXd trial_change;  // A^-1 B' q at trial_dofs, then C A^-1 B' q at damper_dofs
  // B' q at the dampers' floors (damper_dofs), in btq_dampers: only there is it read by the
  // dampers' forces (each damper acts -q on A's floor and +q on B's).
  Eigen::VectorXd btq_dampers;
  Eigen::VectorXd contact_impulse, contact_moment, contact_end_force;
  Eigen::VectorXd contact_bt, total_next;  // B_c' p and all forces at t_n+1
  std::vector<double> step_work;
  Eigen::VectorXd v_free0, cv_free0;  // the free step before the contact impulses
  std::vector<Impact> step_impacts;

  // The nonlinear viscous dampers: their step forces Q, relative velocities at t_n and t_n+1,
  // their velocities without their own step forces, their forces at t_n+1 (then t_n) and those
  // forces at the floors (B_v' F); the free step before their step forces; what the local
  // solve changes, kept to take it again (viscous_step in structure_solver.cpp).
  Eigen::VectorXd viscous_q, viscous_w_pass, viscous_w0, viscous_w1, viscous_wt, viscous_force, viscous_q_new, viscous_bt;
  Eigen::VectorXd v_base, cv_base;
  std::unique_ptr<ViscousSolver> viscous_solver;
  std::size_t viscous_split_steps = 0;  // steps whose passes flipped (viscous_step): SolverSummary
  std::vector<char> held_key;  // (restart, stuck per damper): viscous_g_held's cache
  std::deque<std::pair<std::vector<char>, Eigen::MatrixXd>> held_g;
  std::vector<DamperState> states_before;
  std::vector<ContactMemory> memory_saved;
  BilinearStates bilinear_saved;
  std::vector<double> contact_work_saved;

  // The Bouc-Wen elements (bouc_wen_step.hpp): their states, step forces Q, end velocities (of
  // this pass and the last), velocities without their own Q; the free step before their Q; what
  // the local solve changes, kept to take it again (bouc_wen_step in structure_solver.cpp).
  std::vector<BoucWenState> bouc_wen;
  Eigen::VectorXd bouc_wen_q, bouc_wen_q_new, bouc_wen_w1, bouc_wen_w_pass, bouc_wen_wt;
  Eigen::VectorXd bouc_wen_v_base, bouc_wen_cv_base;
  std::unique_ptr<BoucWenSolver> bouc_wen_solver;
  std::size_t bouc_wen_unsettled = 0;  // steps whose passes did not settle
  std::vector<DamperState> bouc_wen_states_saved;
  std::vector<ContactMemory> bouc_wen_memory_saved;
  BilinearStates bouc_wen_bilinear_saved;
  std::vector<double> bouc_wen_work_saved;

  // The grid points t_n (`now`) and t_n+1 (`next`): two states whose vectors every step reuses,
  // their roles swapped after each step.
  StructureState first, second;
  StructureState* now_p = nullptr;
  StructureState* next_p = nullptr;
};

}  // namespace adjoin::detail
