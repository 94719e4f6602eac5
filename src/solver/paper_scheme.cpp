// The paper's scheme, (3.1)/(3.2) of the seed paper with the misprint in (3.1) fixed
// (the factor before f2's brace is 1/(1 + tau_f2 h^{-beta})).
//
// At each grid point t_m:
//   1. rod forces f_m from x_m and the Grünwald–Letnikov history (3.1)_{1,2};
//   2. the damper phase for the step from t_m to t_{m+1}, decided on the grid:
//        stick : stays while |q_stick| < mu, q = q_stick; otherwise slip towards sign(q_stick);
//        slip  : continues while the relative velocity keeps its sign; when it reaches zero or
//                changes sign, sticks if |q_stick| <= mu (c = x1 - x2 frozen), otherwise slips
//                towards sign(q_stick);
//   3. explicit central differences: (3.1)_{3,4} in slip, (3.2) in stick.
// The history runs from t = 0 across every phase change.
//
// Start: x_0 = 0 and x_1 = h^2 a_0 / 2 (central differences from rest). For the decaying sine
// a_0 = 0, so x_1 = 0 as in the paper.
//
// Its states are the 1 + 1 structure's (structure/two_block.hpp; StructureState, so that the
// observers of any structure watch it): block 1 and rod 1 as building A's floor and storey,
// block 2 and rod 2 as B's, the damper as link 1 (its phase decided on the grid, no located
// switch), contact pair 1 at gap0 (no contact law: its force and work are 0). The observers are
// told locate_switches = false: without a damper, the phase (the sign of the relative
// velocity) changes at a grid point.
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include "adjoin/core/errors.hpp"
#include "adjoin/fractional/weights.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/two_block.hpp"
#include "rod_law.hpp"
#include "schemes.hpp"
#include "time_loop.hpp"

namespace adjoin::detail {
namespace {

// Dimensionless displacements beyond this are taken as a blow-up (physical ones are O(1) to
// O(1e3) even for extreme excitations).
constexpr double kRunaway = 1e12;

// Largest squared natural frequency the explicit step sees, at step h: each block on its own
// rod (slip) and the two blocks together (stick). The fastest grid mode alternates in sign,
// z_m = (-1)^m, where the Grünwald–Letnikov sum is (1 - (-1))^g = 2^g times the mode, so a
// rod's stiffness for it is k (1 + tau_x (2/h)^g) / (1 + tau_f (2/h)^g).
double max_omega_squared(const Model& model, double h) {
  auto stiffness = [&](const Rod& rod, double k) {
    if (rod.elastic) return k;
    const double s = std::pow(2.0 / h, rod.order);
    return k * (1.0 + rod.tau_x * s) / (1.0 + rod.tau_f * s);
  };
  const double k1 = stiffness(model.rod1, 1.0);
  const double k2 = stiffness(model.rod2, model.eps);
  double w2 = std::max(k1, model.rho * k2);
  if (model.mu > 0.0) w2 = std::max(w2, model.rho / (model.rho + 1.0) * (k1 + k2));
  return w2;
}

// Central differences are stable for h^2 omega^2 < 4; the rods stiffen as h shrinks, so the
// bound is found by bisection on h.
void check_stability(const SolverOptions& options, const Model& model) {
  auto stable = [&](double h) { return h * h * max_omega_squared(model, h) < 4.0; };
  if (stable(options.h)) return;
  double lo = options.h, hi = options.h;
  while (!stable(lo) && lo > 1e-300) lo *= 0.5;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  std::ostringstream s;
  s.precision(4);
  s << "the paper scheme is unstable at solver.h = " << options.h
    << ": explicit central differences need h < " << lo
    << " for these rods and masses (h^2 omega_max^2 < 4); set solver.h below " << 0.9 * lo;
  throw NumericalError(s.str(), 0.0);
}

// The scheme as a stepper of the time loop (time_loop.hpp). The state at t_m needs x_{m+1}
// (central-difference velocity), so grid point m is computed with the step to t_{m+1}:
// start() takes the first step from rest and reports t_0, advance(n) takes the step from
// t_{n+1} and reports t_{n+1}.
class PaperStepper {
 public:
  PaperStepper(const SolverOptions& options, const Model& model, const GroundMotion& ground)
      : options_(options), model_(stable(options, model)), ground_(ground), h_(options.h), h2_(h_ * h_), n_(options.steps()),
        rho_(model.rho), mu_(model.mu), damper_(mu_ > 0.0),
        rod1_(make_rod_law(model.rod1, 1.0, h_, options.history, WeightRule::grunwald_letnikov, n_ + 2,
                           options.history_tolerance)),
        rod2_(make_rod_law(model.rod2, model.eps, h_, options.history, WeightRule::grunwald_letnikov, n_ + 2,
                           options.history_tolerance)),
        structure_(structure::two_block_structure(model)) {
    observed_.h = options.h;
    observed_.t_end = options.t_end;
    observed_.history = options.history;
    observed_.history_tolerance = options.history_tolerance;
    observed_.scheme = Scheme::paper;
    observed_.locate_switches = false;  // the phases are decided on the grid
    StructureState& s = state_;
    for (auto* v : {&s.x, &s.v, &s.a_abs, &s.storey_force}) v->setZero(2);
    const Eigen::Index links = damper_ ? 1 : 0;
    for (auto* v : {&s.link_force, &s.link_stroke, &s.link_velocity}) v->setZero(links);
    s.link_phase.assign(static_cast<std::size_t>(links), Phase::stick);
    s.link_switch.assign(static_cast<std::size_t>(links), std::numeric_limits<double>::quiet_NaN());
    for (auto* v : {&s.contact_gap, &s.contact_force, &s.contact_work, &s.contact_dissipated}) v->setZero(1);
  }

  std::tuple<const structure::Structure&, const StructureSolverOptions&> info() const { return {structure_, observed_}; }
  std::size_t steps() const { return n_; }
  std::size_t history_bytes() const { return rod1_.bytes() + rod2_.bytes(); }
  double history_error() const { return std::max(rod1_.weight_error(), rod2_.weight_error()); }
  std::size_t history_modes() const { return std::max(rod1_.modes(), rod2_.modes()); }
  const StructureState& start() { return grid_point(0); }
  const StructureState& advance(std::size_t n) { return grid_point(n + 1); }

 private:
  // The model, checked against the stability bound first: model_ is initialised before the
  // rods, so an unstable step is refused before their weights are computed.
  static const Model& stable(const SolverOptions& options, const Model& model) {
    if (options.stability_check) check_stability(options, model);
    return model;
  }

  // Grid point m: the rod forces and the damper's phase at t_m, the step to x_{m+1}, and the
  // state at t_m. Inlined into advance() (and start()): called from two places, the compiler
  // kept it out of line, a call per step that cost about 1 % on the strong scene with fft.
  [[gnu::always_inline]] const StructureState& grid_point(std::size_t m) {
    const double h = h_, h2 = h2_, rho = rho_, mu = mu_;
    const bool damper = damper_;
    const double t = static_cast<double>(m) * h;
    const double ag = ground_.ag(t);
    const double f1 = rod1_.force(x1_);
    const double f2 = rod2_.force(x2_);
    rod1_.commit(x1_, f1);
    rod2_.commit(x2_, f2);

    // The damper: decide the phase of the step t_m -> t_{m+1} and its force q_m.
    double q = 0.0;
    if (damper) {
      const double q_stick = stick_force(model_, f1, f2);
      const Phase towards = q_stick > 0.0 ? Phase::slip_right : Phase::slip_left;
      if (phase_ == Phase::stick) {
        if (std::abs(q_stick) >= mu) phase_ = towards;
      } else {
        const double w = (x1_ - x1_prev_) - (x2_ - x2_prev_);  // relative velocity times h
        const bool still_sliding = phase_ == Phase::slip_right ? w > 0.0 : w < 0.0;
        if (!still_sliding && !first_) {
          if (std::abs(q_stick) <= mu) {
            phase_ = Phase::stick;
            c_ = x1_ - x2_;
          } else {
            phase_ = towards;
          }
        }
      }
      q = phase_ == Phase::stick ? q_stick : (phase_ == Phase::slip_right ? mu : -mu);
    }

    // Explicit central differences.
    double a1, a2;  // absolute accelerations x'' - a_g
    double x1_next, x2_next;
    if (damper && phase_ == Phase::stick) {
      a1 = a2 = -rho / (rho + 1.0) * (f1 + f2);
      x1_next = (first_ ? x1_ + 0.5 * h2 * (ag + a1) : 2.0 * x1_ - x1_prev_ + h2 * (ag + a1));
      x2_next = x1_next - c_;
    } else {
      a1 = -f1 - q;
      a2 = rho * (q - f2);
      x1_next = first_ ? x1_ + 0.5 * h2 * (ag + a1) : 2.0 * x1_ - x1_prev_ + h2 * (ag + a1);
      x2_next = first_ ? x2_ + 0.5 * h2 * (ag + a2) : 2.0 * x2_ - x2_prev_ + h2 * (ag + a2);
    }
    // A finite but runaway response is as wrong as a NaN: stop before either reaches an output.
    if (!(std::abs(x1_next) < kRunaway && std::abs(x2_next) < kRunaway)) runaway(x1_next, x2_next, t + h);
    if (first_) { x1_prev_ = x1_next; x2_prev_ = x2_next; }  // x_{-1} = x_1 (at rest at t = 0)

    StructureState& s = state_;
    s.t = t;
    s.ag = ag;
    double* x = s.x.data();
    double* v = s.v.data();
    x[0] = x1_;
    x[1] = x2_;
    v[0] = (x1_next - x1_prev_) / (2.0 * h);
    v[1] = (x2_next - x2_prev_) / (2.0 * h);
    s.a_abs[0] = a1;
    s.a_abs[1] = a2;
    s.storey_force[0] = f1;
    s.storey_force[1] = f2;
    if (damper) {
      s.link_force[0] = q;
      s.link_stroke[0] = x1_ - x2_;
      s.link_velocity[0] = v[0] - v[1];
      s.link_phase[0] = phase_;
    }
    s.contact_gap[0] = gap0_ + x2_ - x1_;

    x1_prev_ = x1_; x2_prev_ = x2_;
    x1_ = x1_next; x2_ = x2_next;
    first_ = false;
    return s;
  }

  [[noreturn]] void runaway(double x1_next, double x2_next, double t) const {
    std::ostringstream s;
    s << "the displacement became " << (std::isfinite(x1_next + x2_next) ? "larger than 1e12" : "non-finite")
      << " at t = " << t << " with the paper scheme at solver.h = " << h_;
    // The step was checked against the stability bound before the run: a runaway then
    // comes from the amplitude of the forcing, not from the step.
    if (options_.stability_check)
      s << ", which is within the scheme's stability bound: the ground motion drives the response beyond "
           "1e12; check the ground motion's amplitude (ground.*) and units";
    else
      s << "; the explicit scheme is unstable here: reduce solver.h";
    throw NumericalError(s.str(), t);
  }

  const SolverOptions& options_;
  const Model& model_;
  const GroundMotion& ground_;
  const double h_, h2_;
  const std::size_t n_;
  const double rho_, mu_;
  const bool damper_;
  RodLaw rod1_, rod2_;
  // x_{m-1}, x_m, and the first step from rest.
  double x1_prev_ = 0.0, x2_prev_ = 0.0, x1_ = 0.0, x2_ = 0.0;
  Phase phase_ = Phase::stick;
  double c_ = 0.0;  // x1 - x2, frozen while stuck
  bool first_ = true;
  const double gap0_ = model_.gap0;
  structure::Structure structure_;
  StructureSolverOptions observed_;
  StructureState state_;
};

}  // namespace

SolverSummary run_paper_scheme(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                               StructureObserver& observer) {
  return integrate<PaperStepper>(observer, options, model, ground);
}

}  // namespace adjoin::detail
