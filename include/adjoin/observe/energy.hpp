#pragma once
// The energy balance of a run, integrated from the grid's powers (trapezoidal).
//
// BuildingEnergy: any structure's balance [J] (the building observers compute it,
// study/channel_observer.hpp). EnergyObserver: the balance of the 1 + 1 structure (the two
// blocks, structure/two_block.hpp) from its states, in its units (per unit m1 when
// dimensionless: m_A = 1, m_B = 1/rho). Multiplying the equations of motion by the
// floors' velocities and integrating from 0 to t:
//
//     input[X]   = int a_g m_X v_X dt                 work of the ground on building X
//     kinetic[X] = m_X v_X^2 / 2                      (relative to the moving base)
//     storey[X]  = int f_X v_X dt                     work on X's storey (its rod: stored plus
//                                                     dissipated)
//     link       = int q (v_A - v_B) dt               dissipated in the friction link (>= 0)
//     contact    = the contact pair's work (SPEC §6): its stored energy plus what it
//                  dissipated, the solver's own (StructureState::contact_work, contact_dissipated,
//                  integrated consistently with its step); 0 without a contact law
//     base[X]    = int qb_X v_X dt                    dissipated by X's base friction
//                                                     (model.base_friction, SPEC §7: the
//                                                     ground sliders after the link)
//     residual   = input - (kinetic + storeys + link + contact + base)
//
// The exact solution has residual 0; the discrete one goes to zero with the step.
#include <cstddef>
#include <vector>

#include "adjoin/structure/observer.hpp"

namespace adjoin {

// The energy balance of a run [J]: for each building the input a_g 1'M v, the kinetic energy
// 1/2 v'M v, the work dissipated by its inherent damping v'C v and the work done on each storey
// (springs' strain energy and the devices' stored and dissipated work together); each link's
// work; each contact pair's work (its stored energy plus what it dissipated, exact from the
// solver); and the residual input - kinetic - inherent - storeys - links - contacts, which
// tends to 0 at the scheme's order.
struct BuildingEnergy {
  struct Part {
    double input = 0.0, kinetic = 0.0, inherent = 0.0;
    std::vector<double> storeys;
    // Bilinear storeys (SPEC §7): the plastic work of each storey's law (a part of its storey's
    // work, dissipated); empty for an elastic building.
    std::vector<double> hysteretic;
    // An isolated base (SPEC §7): the work done on its isolator, the slider's dissipated work
    // plus a friction pendulum's stored energy (0 without a base), and the slider's part.
    double isolator = 0.0, isolator_dissipated = 0.0;
  };
  std::vector<Part> buildings;  // A, then B
  std::vector<double> links;
  std::vector<double> contacts;
  double input = 0.0, residual = 0.0;
};

// The 1 + 1 structure's balance at a grid point (see above); index 0 is building A, 1 is B.
struct EnergyTerms {
  double t = 0.0;
  double input[2] = {0.0, 0.0}, kinetic[2] = {0.0, 0.0}, storey[2] = {0.0, 0.0}, base[2] = {0.0, 0.0};
  double link = 0.0;
  double contact = 0.0, contact_dissipated = 0.0;
  double residual = 0.0;
  double total_input() const { return input[0] + input[1]; }
  double total_kinetic() const { return kinetic[0] + kinetic[1]; }
};

class EnergyObserver final : public StructureObserver {
 public:
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& s) override;
  // The balance at the last sample observed. (Its kinetic energies and residual are made here,
  // from the last velocities, rather than at every step: they are not sums over the run.)
  EnergyTerms terms() const;
  // The balance as any structure's (the friction link only if the model has one; the contact
  // pair always).
  BuildingEnergy balance() const;

 private:
  double m_[2] = {1.0, 1.0};
  bool link_ = false, contact_law_ = false, sliders_ = false;
  std::size_t count_ = 0;
  // The last sample's time and powers (ground per building, storeys, link, base friction).
  struct Powers {
    double t = 0.0, input[2] = {0.0, 0.0}, storey[2] = {0.0, 0.0}, link = 0.0, base[2] = {0.0, 0.0};
  };
  Powers previous_;
  EnergyTerms terms_;  // the sums (input, storeys, base, link) and the last contact work
  double v_[2] = {0.0, 0.0};  // the last velocities
};

}  // namespace adjoin
