// The implicit schemes of the two-block system ("implicit", "implicit-damped", "implicit-gl",
// with or without a contact law, SPEC §6 `[model.contact]`): the paper's system is the smallest
// structure (SPEC §5: one storey each, Zener storeys, one friction link, one contact pair at
// gap0), so it runs on the structure solver, whose step is the implicit scheme's for vectors
// (its restart rule and quadrature weights are the scheme's options), in the model's
// dimensionless units. Its states go to the observers as they are (simulate_as_structure).
// Only the paper's explicit scheme has a stepper of its own (paper_scheme.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/two_block.hpp"
#include "schemes.hpp"

namespace adjoin {

namespace detail {
namespace {

// The contact law stores or dissipates the work done on it, never gives back more: a pair
// that has given back more than 1 % of the input energy so far had a step too long for its
// stiffness (as for building runs, study/channel_observer.hpp). Checked before the observers
// see the state.
class ContactEnergyCheck final : public StructureObserver {
 public:
  ContactEnergyCheck(StructureObserver& inner, double m1, double m2) : inner_(inner), m1_(m1), m2_(m2) {}
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override { inner_.begin(s, o); }
  void end() override { inner_.end(); }
  void impact(const Impact& i) override { inner_.impact(i); }
  void observe(const StructureState& s) override {
    check(s);
    inner_.observe(s);
  }

 private:
  void check(const StructureState& s) {
    const double power = s.ag * (m1_ * s.v[0] + m2_ * s.v[1]);
    if (started_) input_ += 0.5 * (s.t - t_) * (power + power_);
    started_ = true;
    t_ = s.t;
    power_ = power;
    input_scale_ = std::max(input_scale_, std::abs(input_));
    if (s.contact_dissipated.size() == 0 || !(-s.contact_dissipated[0] > 1e-2 * input_scale_)) return;
    std::ostringstream m;
    m << "the contact (model.contact) has given back " << -s.contact_dissipated[0] << " more than the work done on it "
      << "at t = " << s.t << " (the input so far " << input_scale_ << "): the step is too long for the contact's "
      << "stiffness; make solver.h smaller or lower model.contact.stiffness";
    throw NumericalError(m.str(), s.t);
  }

  StructureObserver& inner_;
  double m1_, m2_;
  bool started_ = false;
  double t_ = 0.0, power_ = 0.0, input_ = 0.0, input_scale_ = 0.0;
};

}  // namespace

SolverSummary run_two_block_on_structure(const SolverOptions& options, const structure::Structure& s,
                                         const GroundMotion& ground, StructureObserver& observer) {
  const bool contact = s.contacts[0].law.model != structure::ContactModel::none;
  if (contact && !(s.contacts[0].gap >= 0.0))
    throw InputError("model.gap0 must be >= 0 with a contact law (the blocks may not start overlapping)");
  StructureSolverOptions o;
  o.h = options.h;
  o.t_end = options.t_end;
  o.history = options.history;
  o.history_tolerance = options.history_tolerance;
  o.locate_switches = options.locate_switches;  // (for the observers: the stepper always locates)
  if (options.scheme == Scheme::implicit_damped) o.restart = StructureSolverOptions::Restart::always;
  if (options.scheme == Scheme::implicit_gl) o.quadrature = StructureSolverOptions::Quadrature::grunwald_letnikov;
  const ScaledGround g(ground, 1.0 / kStandardGravity);
  if (!contact) return simulate_structure(o, s, g, observer);  // (nothing stored or dissipated to check)
  ContactEnergyCheck checked(observer, s.a.masses[0], s.b->masses[0]);
  return simulate_structure(o, s, g, checked);
}

}  // namespace detail
}  // namespace adjoin
