#pragma once
// The pounding margin: the gap xi(t) = gap0 + x2 - x1 between the blocks. xi <= 0 means the
// structures touch. The minimum is refined between samples from the gap's derivatives, with
// the damper's located switch as a kink (step_extremum in extremum.hpp: second order even when
// the minimum sits on a switch); the first contact time is interpolated linearly between the
// grid points that bracket it.
//
// With a contact law (Model::contact, SPEC §6) the observer also keeps the solver's impacts
// (StructureObserver::impact): their list, the peak contact force and its time, the largest
// penetration, and the energy the contact dissipated (StructureState::contact_dissipated). The first
// contact is then the first impact's located start; under the Newton law (no penetration) the
// minimum gap is 0 at that instant. Without a law (model none) the blocks pass
// through each other: every value computed after the first contact is outside the model
// (PoundingMargin::outside_model()).
#include <cstddef>
#include <optional>
#include <vector>

#include "adjoin/observe/extremum.hpp"
#include "adjoin/observe/pair_phase.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/structure/contact.hpp"

namespace adjoin {

struct PoundingMargin {
  double min_gap = 0.0;
  double t_min_gap = 0.0;
  bool contact = false;
  std::optional<double> t_first_contact;

  // The contact law of the run (none: no law, the blocks pass through each other).
  structure::ContactModel model = structure::ContactModel::none;
  // With a law: every impact in order (the last one may be incomplete), the peak contact force
  // over the run and its time, the largest penetration (0 for the Newton law), and the energy
  // dissipated by the contact from t = 0 to the end. Taken from the impacts when there are
  // any, otherwise from the sampled states.
  std::vector<Impact> impacts;
  double force_max = 0.0, t_force_max = 0.0;
  double penetration_max = 0.0;
  double dissipated = 0.0;
  double impulse = 0.0, impulse_max = 0.0;  // sum and largest of the impacts' impulses

  bool has_law() const { return model != structure::ContactModel::none; }
  // No contact law and the gap closed: every value after t_first_contact is outside the model.
  bool outside_model() const { return !has_law() && contact; }
};

// Of a run of the 1 + 1 structure (structure/two_block.hpp): contact pair 1, between A's and
// B's floor 1; the kinks are link 1's located switches (observe/pair_phase.hpp).
class PoundingObserver final : public StructureObserver {
 public:
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& s) override { phase_.update(s); observe(s, phase_); }
  // The same with link 1's phase at s given (the report's observers share one PairPhase).
  void observe(const StructureState& s, const PairPhase& phase);
  void impact(const Impact& i) override;
  void end() override;
  const PoundingMargin& margin() const { return margin_; }

 private:
  PairPhase phase_;
  double gap0_ = 0.0;
  bool started_ = false;
  Sample previous_{};  // the gap, its rate and its acceleration at the previous sample
  // The sampled contact force's peak and the deepest sampled penetration (the fallback when
  // the solver reported no impact).
  double sampled_force_max_ = 0.0, sampled_t_force_max_ = 0.0, sampled_penetration_ = 0.0;
  PoundingMargin margin_;
};

}  // namespace adjoin
