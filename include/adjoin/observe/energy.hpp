#pragma once
// The energy balance per unit mass m1 (dimensionless; SI scenes scale it to joules).
//
// Multiplying the equations of motion by x1' and x2'/rho and integrating from 0 to t:
//
//     input    = int a_g (x1' + x2'/rho) dt          work of the ground on the blocks
//     kinetic  = x1'^2/2 + x2'^2/(2 rho)             (relative to the moving base)
//     rod1     = int f1 x1' dt,  rod2 = int f2 x2' dt   (stored plus dissipated in the rods)
//     friction = int q (x1' - x2') dt                dissipated in the damper (>= 0)
//     contact  = int fc (x1' - x2') dt               work on the contact law (SPEC §6): its
//                                                    stored energy plus what it dissipated
//     base     = int (qb1 x1' + qb2 x2') dt           dissipated by the blocks' base friction
//                                                    (model.base_friction, SPEC §7; qb2 =
//                                                    mu_b / rho, block 2's slip force per m1 g)
//     residual = input - (kinetic + rod1 + rod2 + friction + contact + base)
//
// The contact terms are the solver's own (State::contact_work and contact_dissipated,
// integrated consistently with its step); without a contact law they are 0 and the residual is
// the four-term one.
//
// The exact solution has residual 0; the discrete one goes to zero with the step. Integrals
// use the trapezoidal rule on the grid samples.
#include <vector>

#include "adjoin/structure/observer.hpp"

namespace adjoin {

struct EnergyBalance {
  double t = 0.0;
  double input = 0.0, kinetic = 0.0, rod1 = 0.0, rod2 = 0.0, friction = 0.0, residual = 0.0;
  double contact = 0.0;              // work on the contact (0 without a contact law)
  double contact_dissipated = 0.0;   // the part of it the contact dissipated
  double base_friction = 0.0;        // dissipated by the base friction (0 without)
};

class EnergyObserver final : public Observer {
 public:
  // keep_history: also keep the balance at every `every`-th grid point.
  explicit EnergyObserver(bool keep_history = false, std::size_t every = 1)
      : keep_history_(keep_history), every_(every == 0 ? 1 : every) {}
  void begin(const RunInfo& info) override;
  void observe(const State& s) override;
  const EnergyBalance& balance() const { return balance_; }
  const std::vector<EnergyBalance>& history() const { return history_; }

 private:
  bool keep_history_;
  std::size_t every_;
  double rho_ = 1.0;
  bool contact_law_ = false;
  std::size_t count_ = 0;
  // The last sample's time and powers (ground, rods, damper, base friction).
  struct Powers {
    double t = 0.0, input = 0.0, rod1 = 0.0, rod2 = 0.0, friction = 0.0, base = 0.0;
  };
  Powers previous_;
  EnergyBalance balance_;
  std::vector<EnergyBalance> history_;
};

}  // namespace adjoin
