#pragma once
// Streams the energy balance's time history to CSV as the solver runs, in the scene's units
// (per unit m1 for dimensionless scenes, joules for SI ones):
//
//     t,input,kinetic,rod1,rod2,friction,residual
//
// With a contact law (SPEC §6) the work on the contact and the part it dissipated come before
// the residual, which then subtracts the contact term:
//
//     t,input,kinetic,rod1,rod2,friction,contact,contact_dissipated,residual
//
// The definitions are those of observe/energy.hpp (and docs/reference/outputs.md).
#include <ostream>

#include "adjoin/core/units.hpp"
#include "adjoin/observe/energy.hpp"

namespace adjoin {

// Of a two-block run's 1 + 1 structure (solver/simulate.hpp simulate_as_structure).
class EnergyCsvWriter final : public StructureObserver {
 public:
  EnergyCsvWriter(std::ostream& out, const Scales& scales, std::size_t every = 1);
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& s) override;
  void end() override;

 private:
  std::ostream& out_;
  Scales scales_;
  std::size_t every_, steps_ = 0, count_ = 0;
  EnergyObserver energy_;
  bool contact_law_ = false;
  std::string buffer_;
};

}  // namespace adjoin
