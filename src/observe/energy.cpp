#include "adjoin/observe/energy.hpp"

namespace adjoin {

void EnergyObserver::begin(const RunInfo& info) {
  rho_ = info.model.rho;
  contact_law_ = info.model.contact.model != structure::ContactModel::none;
  count_ = 0;
  balance_ = EnergyBalance{};
  history_.clear();
}

void EnergyObserver::observe(const State& s) {
  // This sample's powers: the right ends of this step's trapezoids, kept as the left ends of
  // the next step's (the terms as the sums had them, so the sums are the same to the bit).
  const double input = s.ag * (s.v1 + s.v2 / rho_);
  const double rod1 = s.f1 * s.v1, rod2 = s.f2 * s.v2, friction = s.q * (s.v1 - s.v2);
  const double base1 = s.qb1 * s.v1, base2 = s.qb2 * s.v2;
  if (count_ > 0) {
    const double half_dt = 0.5 * (s.t - previous_.t);
    balance_.input += half_dt * (previous_.input + input);
    balance_.rod1 += half_dt * (previous_.rod1 + rod1);
    balance_.rod2 += half_dt * (previous_.rod2 + rod2);
    balance_.friction += half_dt * (previous_.friction + friction);
    balance_.base_friction += half_dt * (previous_.base + base1 + base2);
  }
  previous_ = Powers{s.t, input, rod1, rod2, friction, base1 + base2};
  balance_.t = s.t;
  balance_.kinetic = 0.5 * s.v1 * s.v1 + 0.5 * s.v2 * s.v2 / rho_;
  if (contact_law_) {
    balance_.contact = s.contact_work;
    balance_.contact_dissipated = s.contact_dissipated;
    balance_.residual = balance_.input -
                        (balance_.kinetic + balance_.rod1 + balance_.rod2 + balance_.friction + balance_.contact);
  } else {
    balance_.residual = balance_.input - (balance_.kinetic + balance_.rod1 + balance_.rod2 + balance_.friction);
  }
  if (balance_.base_friction != 0.0) balance_.residual -= balance_.base_friction;
  if (keep_history_ && count_ % every_ == 0) history_.push_back(balance_);
  ++count_;
}

}  // namespace adjoin
