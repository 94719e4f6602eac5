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
  if (count_ > 0) {
    const State& p = previous_;
    const double half_dt = 0.5 * (s.t - p.t);
    auto power_in = [&](const State& z) { return z.ag * (z.v1 + z.v2 / rho_); };
    balance_.input += half_dt * (power_in(p) + power_in(s));
    balance_.rod1 += half_dt * (p.f1 * p.v1 + s.f1 * s.v1);
    balance_.rod2 += half_dt * (p.f2 * p.v2 + s.f2 * s.v2);
    balance_.friction += half_dt * (p.q * (p.v1 - p.v2) + s.q * (s.v1 - s.v2));
    balance_.base_friction += half_dt * (p.qb1 * p.v1 + p.qb2 * p.v2 + s.qb1 * s.v1 + s.qb2 * s.v2);
  }
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
  previous_ = s;
  ++count_;
}

}  // namespace adjoin
