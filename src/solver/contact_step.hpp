#pragma once
// One contact pair over one step of the structure solver (SPEC §6), internal to the solver.
//
// Stiff contact must not force a small step on the whole run, so the step of the structure
// stays h and each contact pair's relative motion is integrated on its own through the step,
// finely where the floors are in contact, as a one-degree-of-freedom problem:
//
//     delta' = w,   w' = a - kappa p(delta, w),   delta = s - gap (the penetration), w = s',
//
// with a the pair's free relative acceleration over the step (what the rest of the structure
// does to it, taken constant: the step's trapezoidal mechanics is second order in it) and
// kappa = B A^-1 B' the pair's inverse effective mass in the step (A = M + h/2 C + h^2/4 K
// the step matrix), so that the pair's velocity at the end, w0 + a h - kappa I, is exactly the
// one the structure's step gives it for the contact impulse I (the structure sees I as a step
// force I / h, as it sees a friction damper's). The structure's trapezoidal displacement is
// then corrected by A^-1 B' (h/2 I - J), J = the integral of (h - tau) p(tau), which makes it
// equal to the pair's own integrated penetration at the end of the step.
//
// Free flight is a parabola, so the first touch is the root of a quadratic (exact for a
// constant a). In contact the compliant laws are integrated with an embedded Runge-Kutta pair
// (Dormand-Prince 5(4)) under a tolerance far below the structure step's error, and the
// separation (the penetration or, for laws that do not pull, the force returning to 0) is
// located by bisection on the step. The Newton law is event by event: free flight to the
// touch, the velocity reversed to -e times itself, again; a sequence of bounces that would
// accumulate inside the step (e < 1 under a pushing a) ends at rest in a held contact (w = 0,
// force a / kappa), released when a pulls the floors apart.
#include <string>
#include <vector>

#include "adjoin/structure/state.hpp"
#include "adjoin/structure/contact.hpp"

namespace adjoin::detail {

// What a contact pair carries from step to step.
struct ContactMemory {
  bool engaged = false;      // in contact (compliant: pressed; Newton: held at rest)
  double approach = 0.0;     // the current impact's approach speed (hertzdamp's v0)
  Impact current;            // the impact under way, if engaged
};

struct ContactStepIn {
  double t0 = 0.0, h = 0.0;        // the step [t0, t0 + h]
  double delta0 = 0.0, w0 = 0.0;   // penetration and its rate at t0
  double a = 0.0;                  // free relative acceleration over the step
  double kappa = 0.0;              // inverse effective mass in the step
};

struct ContactStepOut {
  double impulse = 0.0;      // I: the integral of p over the step
  double moment = 0.0;       // J: the integral of (h - tau) p
  double delta = 0.0, w = 0.0;  // at the end of the step (the pair's own)
  double force = 0.0;        // p at the end of the step
  double work = 0.0;         // the integral of p w over the step
  bool touched = false;      // any contact inside the step
};

class ContactStepper {
 public:
  // `m_eff` the pair's floors' m_i m_j / (m_i + m_j), for the damping constants of SPEC §6.
  ContactStepper(const structure::ContactLaw& law, double m_eff, int index);
  // Whether the pair can touch in the step at all (cheap: the free parabola stays apart).
  bool quiet(const ContactMemory& memory, const ContactStepIn& in) const;
  // Integrates the step; appends the impacts that ended in it to `ended`.
  ContactStepOut step(ContactMemory& memory, const ContactStepIn& in, std::vector<Impact>& ended) const;
  // The force of the compliant law at penetration delta, rate w, approach speed v0 (0 apart).
  double force(double delta, double w, double v0) const;
  // The elastic energy stored at penetration delta (what the floors would get back).
  double stored(double delta) const;
  const structure::ContactLaw& law() const { return law_; }

 private:
  struct Flow;
  // The static scale of a load pressing the pair (a free relative acceleration): the law's
  // static penetration under it, the pair's frequency there and the speed omega delta.
  struct Scale {
    double delta = 0.0, omega = 0.0, speed = 0.0;
  };
  Scale static_scale(double acceleration, double kappa) const;
  // Exit 3 when a step's contact motion exceeds its bounds (kMaxSubsteps, kMaxEntries).
  [[noreturn]] void fail_bound(double t, double delta, double w, const std::string& what) const;
  static constexpr long kMaxSubsteps = 200000;  // Runge-Kutta steps in one structure step
  static constexpr int kMaxEntries = 1000;      // touches (and separations) in one structure step
  ContactStepOut compliant_step(ContactMemory& memory, const ContactStepIn& in, std::vector<Impact>& ended) const;
  ContactStepOut newton_step(ContactMemory& memory, const ContactStepIn& in, std::vector<Impact>& ended) const;

  structure::ContactLaw law_;
  double m_eff_ = 0.0;
  int index_ = 0;
  double c_linear_ = 0.0;  // linear: 2 zeta sqrt(k m_eff)
  double damping_ = 0.0;   // zeta, xi_bar or xi
  double inv_125_m_eff_ = 0.0;  // 1 / (1.25 m_eff): hertzdamp's least v0 (force())
};

}  // namespace adjoin::detail
