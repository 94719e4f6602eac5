#pragma once
// Which structures the structure stepper steps by its pair step (structure_solver.cpp,
// advance_pair): two buildings of one floor each, joined by one friction damper between their
// floors and nothing else that the step must solve for (no contact law, no nonlinear viscous,
// bilinear or Bouc-Wen element, no isolated base, no other link). The two-block scenes' 1 + 1
// structure is one, and so is a building pair of one storey each with one friction link.
//
// Why a step of its own: on two floors the general step's loops over its device lists, its
// work vectors' dynamic sizes and its calls cost several times the arithmetic. The pair step
// (PairStepper, pair_step.cpp) repeats the general step's floating-point operations in their
// order on scalars, its constants read once per run, so a run gives the same numbers bit for
// bit either way (tests/test_pair_step.cpp checks it); the paper's strong scene's step costs
// about 0.43k instructions besides the ground's sample and the rods' histories (1.1k when the
// pair step ran on the general step's work vectors, 1.9k for the general step; the dedicated
// two-block stepper it replaced, 0.49k). Most steps are decided at the step's end without the
// trial (PairStepper::decide_at_end says when that is the trial's decision).
#include "box_qp.hpp"
#include "structure_model.hpp"

namespace adjoin::detail {

inline bool takes_pair_step(const StructureModel& m) {
  if (!m.options.pair_step) return false;
  if (m.n != 2 || m.nf != 1 || m.nc != 0 || m.nv != 0 || m.nh != 0 || m.nw != 0) return false;
  if (!m.s.b || m.s.a.floors() != 1 || m.s.b->floors() != 1) return false;
  if (m.s.base_dof('A') >= 0 || m.s.base_dof('B') >= 0) return false;
  // The damper is the only link, between the two floors.
  if (m.s.links.size() != 1 || m.link_pair.size() != 1 || m.friction[0] != 0 || m.link_zener[0] >= 0) return false;
  if (!m.linear_links.empty() || m.fi[0] < 0 || m.fj[0] < 0 || m.fi[0] == m.fj[0]) return false;
  // The trial reads both floors (the dampers' floors are 0 and 1, sorted).
  if (!(m.trial_every_floor && m.nt == 2 && m.nd == 2)) return false;
  // Each building its own block of A (one floor each, no element between them but the damper),
  // and a few Zener elements and contacts (PairConstants' arrays).
  for (const StepMatrices* sm : {m.trapezoidal.get(), m.backward.get()})
    if (sm && (sm->blocks.size() != 2 || sm->blocks[0].size != 1 || sm->blocks[1].size != 1)) return false;
  if (m.zener.size() > 4 || m.damper_zener.size() != 2 || m.damper_zener[0].size() > 4 || m.damper_zener[1].size() > 4 || m.s.contacts.size() > 4) return false;
  return true;
}

}  // namespace adjoin::detail

namespace adjoin::detail {

// The pair step's constants, read once from the model (and the QPs' S_00^-1 at the first
// step): per step weight (trapezoidal, backward Euler) the damper's closed-form solve and
// columns, and each building's block of [A^-1; C A^-1]; the bands of K_eff and K0; the
// masses; the Zener elements' floors as slots of a three-entry array {x_0, x_1, 0}, so that
// Pair::of's (i >= 0 ? x_i : 0) - (j >= 0 ? x_j : 0) is one subtraction of two loads.
struct PairTheta {
  double single = 0.0;             // the QP's S_00^-1
  double trial[4] = {};            // trial_rows' column
  double response[4] = {};         // damper_response's column
  double block[2][2] = {};         // floor k's block: v_free = 0 + block[k][0] rhs, C v_free = 0 + block[k][1] rhs
};
struct PairZener {
  int i = 2, j = 2;  // floor slots (2: the ground's zero)
  int storey = -1;
  double stiffness = 0.0;
  double scale = 0.0, value_of_x = 0.0, value_of_f = 0.0;  // the workspace's zener_scale, zener_kx, zener_tf
};
struct PairConstants {
  static constexpr int kMaxZener = 4;
  PairTheta trapezoidal, backward;
  double h = 0.0, half_h = 0.0, minus_h = 0.0;
  double ke_di0 = 0.0, ke_di1 = 0.0, ke_up0 = 0.0, ke_lo0 = 0.0;  // K_eff's bands
  double k0_di0 = 0.0, k0_di1 = 0.0, k0_up0 = 0.0, k0_lo0 = 0.0;  // K0's
  double mass[2] = {}, inv_mass[2] = {}, c_diag[2] = {};          // M, M^-1, C's diagonal (trapezoidal blocks)
  double limit = 0.0, stuck_single = 0.0, g00 = 0.0;              // F, (B M^-1 B')^-1, B M^-1 B'
  // PairStepper::stuck_margin's: |stuck_single| (1/m_0 + 1/m_1), max |C_kk|, the largest row
  // sum of |K0| plus twice the Zener stiffnesses, sum |contact_bt|.
  double stuck_scale = 0.0, c_abs = 0.0, k_abs = 0.0, contact_abs = 0.0;
  double contact_bt[2] = {};
  double storey_spring[2] = {}, storey_dashpot[2] = {};
  bool dashpots_a = false, dashpots_b = false;
  int fi = 0, fj = 1;  // the damper's floors
  int pi = 0, pj = 1;  // ... as damper dofs (B' q's rows)
  int n_zener = 0;
  PairZener zener[kMaxZener];
  bool plain = false;  // the slots are PairSlots<true>'s
  // The contacts without a law (the only ones here): their gaps reported, gap - x_i + x_j.
  int n_contacts = 0;
  double contact_gap[kMaxZener] = {};
  int contact_i[kMaxZener] = {}, contact_j[kMaxZener] = {};
  // Per floor k, the Zener elements acting on it in the trial (model.damper_zener[k]).
  int n_trial_zener[2] = {};
  int trial_zener[2][kMaxZener] = {};
  double trial_sign[2][kMaxZener] = {};
};

// The slots the pair step reads: constants for the plain pair (PairConstants::plain, the
// two-block scenes' 1 + 1 structure: the damper from floor 0 to floor 1, Zener element e the
// storey of floor e, one contact pair between the floors, no dashpot), from pc otherwise. The
// same operations either way, on registers instead of indexed loads for the plain pair.
template <bool kPlain>
struct PairSlots {
  const PairConstants& c;
  int fi() const { return kPlain ? 0 : c.fi; }
  int fj() const { return kPlain ? 1 : c.fj; }
  int pi() const { return kPlain ? 0 : c.pi; }
  int pj() const { return kPlain ? 1 : c.pj; }
  int zi(int e) const { return kPlain ? e : c.zener[e].i; }
  int zj(int e) const { return kPlain ? 2 : c.zener[e].j; }
  int storey(int e) const { return kPlain ? e : c.zener[e].storey; }
  int contacts() const { return kPlain ? 1 : c.n_contacts; }
  int ci(int k) const { return kPlain ? 0 : c.contact_i[k]; }
  int cj(int k) const { return kPlain ? 1 : c.contact_j[k]; }
  bool dashpots_a() const { return kPlain ? false : c.dashpots_a; }
  bool dashpots_b() const { return kPlain ? false : c.dashpots_b; }
};

// The pair step's state carried from t_n to t_n+1 in scalars (the general step's work vectors
// of one or two entries: internal, cv_now, stick_force_prev/now, w_prev, ...).
struct PairCarry {
  double internal[2] = {}, cv_now[2] = {};
  double stick_prev = 0.0, stick_now = 0.0, w_prev = 0.0;
  double stick_start_t = 0.0, stick_start_q = 0.0;
  bool prev_stuck = false, prev_same_slip = false;
  DamperState state = DamperState::stick;  // the damper's after the last step
};

}  // namespace adjoin::detail

#include <cstddef>
#include <limits>

#include "adjoin/ground/ground_motion.hpp"
#include "structure_workspace.hpp"

namespace adjoin::detail {

// The pair step itself (pair_step.cpp): one grid step of the structure stepper for a structure
// that takes_pair_step, on the stepper's model and workspace. The same numbers bit for bit as
// the general step (tests/test_pair_step.cpp).
class PairStepper {
 public:
  // The general step's code for the pair step's rare branches (the structure stepper's).
  class Fallbacks {
   public:
    // The kinks of a slip that ended inside the step, into x (integrate_kinks on ws.states,
    // ws.kink_theta and ws.kink_jump, which the pair step has set).
    virtual void kinks(Eigen::VectorXd* x) = 0;
    // The error of a response out of range (check_range's).
    [[noreturn]] virtual void out_of_range(const StructureState& next) = 0;

   protected:
    ~Fallbacks() = default;
  };

  PairStepper(const StructureModel& model, StepWorkspace& workspace, const GroundMotion& ground_motion, Fallbacks& general);
  // The step from t_n to t_n+1 (n = step) from ws.now_p into ws.next_p, as the structure
  // stepper's advance(); swaps them and returns the state at t_n+1.
  const StructureState& advance(std::size_t step) {
    if (step == 0) begin_run();
    return (this->*advance_)(step);
  }

 private:
  // advance() for a structure of kZener Zener elements (-1: any number, read from pc).
  template <int kZener, bool kPlain>
  const StructureState& advance_with(std::size_t step);
  // The run's advance_with (begin_run's choice: once a run, not a switch at every step).
  const StructureState& (PairStepper::*advance_)(std::size_t) = nullptr;
  // The step's values the decisions pass on (the general step's ws.onset, crossing, ...).
  struct Step {
    static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    double vf[2] = {}, cvf[2] = {}, w_free = 0.0;
    double onset = kNaN, crossing = kNaN, kink_theta = kNaN, kink_jump = 0.0;
  };
  // The step's end (correct's): written into the next state (x, v) and here.
  // (No initialisers: end_state writes every field a step reads, and zeroing them cost about
  // 20 instructions a step.)
  struct End {
    const double* x;  // next.x's, next.v's entries
    const double* v;
    double cv[2], p[2], xs[3], dv[2];
    double zener_force[PairConstants::kMaxZener];
    bool stick_known;  // the damper's stuck force at the end is `stick` (decide_at_end's)
    double stick;
  };
  // The constants (PairConstants) and the carried state (PairCarry) from the model and from
  // the state start() left in the workspace; at the first step of a run.
  void begin_run();
  template <int kZener, bool kPlain>
  [[gnu::always_inline]] inline void end_state(const StructureState& now, const PairTheta& th, bool restart, std::size_t step,
                                               const Step& s, double q_step, DamperState decided, const double* offsets, End& e);
  template <int kZener, bool kPlain>
  [[gnu::always_inline]] inline bool decide_at_end(const StructureState& now, const PairTheta& th, bool restart, std::size_t step,
                                                   const double* offsets, const Step& s, DamperState& decided, End& e);
  template <int kZener, bool kPlain>
  [[gnu::always_inline]] inline double stuck_margin(const StructureState& now, const End& e) const;
  // decide_dampers for the one damper; returns its step force, its state in `decided`.
  // (These are inlined into advance(), which alone calls them (pair_step.cpp): as calls
  // they cost about 200 instructions a step of a two-block run; there is no FMA contraction in
  // this file's baseline build, so inlining leaves every result bit for bit.)
  [[gnu::always_inline]] inline double decide(const StructureState& now, const PairTheta& th, bool restart, const double* offsets,
                                              Step& s, DamperState& decided);
  [[gnu::always_inline]] inline void decide_stuck(const StructureState& now, double stick1, Step& s, bool& hold2, double& fixed2,
                                                  DamperState& decided);
  [[gnu::always_inline]] inline void decide_slipping(const StructureState& now, double fixed, double w1, const double* cv1,
                                                     const double* p1, Step& s, bool& hold2, double& fixed2, DamperState& decided);
  [[gnu::always_inline]] inline double relative_accel(const double* cv, const double* p, double btq) const;
  [[gnu::always_inline]] inline double grid_force(const double* cv, const double* p, Phase ph, double* stick) const;

  const StructureModel& m;
  StepWorkspace& ws;
  const GroundMotion& ground;
  Fallbacks& fallbacks;
  PairConstants pc;
  PairCarry carry;
};

}  // namespace adjoin::detail
