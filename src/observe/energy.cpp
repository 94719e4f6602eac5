#include "adjoin/observe/energy.hpp"

namespace adjoin {

void EnergyObserver::begin(const RunInfo& info) {
  m_[0] = 1.0;
  m_[1] = 1.0 / info.model.rho;
  link_ = info.model.mu > 0.0;
  contact_law_ = info.model.contact.model != structure::ContactModel::none;
  count_ = 0;
  terms_ = EnergyTerms{};
}

void EnergyObserver::observe(const State& s) {
  // This sample's powers: the right ends of this step's trapezoids, kept as the left ends of
  // the next step's.
  const double v[2] = {s.v1, s.v2}, force[2] = {s.f1, s.f2}, slider[2] = {s.qb1, s.qb2};
  Powers now;
  now.t = s.t;
  for (int i = 0; i < 2; ++i) {
    now.input[i] = s.ag * (m_[i] * v[i]);
    now.storey[i] = force[i] * v[i];
    now.base[i] = slider[i] * v[i];
  }
  now.link = s.q * (s.v1 - s.v2);
  EnergyTerms& e = terms_;
  if (count_ > 0) {
    const double half_dt = 0.5 * (s.t - previous_.t);
    for (int i = 0; i < 2; ++i) {
      e.input[i] += half_dt * (previous_.input[i] + now.input[i]);
      e.storey[i] += half_dt * (previous_.storey[i] + now.storey[i]);
      e.base[i] += half_dt * (previous_.base[i] + now.base[i]);
    }
    e.link += half_dt * (previous_.link + now.link);
  }
  previous_ = now;
  e.t = s.t;
  for (int i = 0; i < 2; ++i) e.kinetic[i] = 0.5 * m_[i] * v[i] * v[i];
  if (contact_law_) {
    e.contact = s.contact_work;
    e.contact_dissipated = s.contact_dissipated;
  }
  e.residual = e.total_input() - (e.total_kinetic() + e.storey[0] + e.storey[1] + e.link + e.contact);
  const double base = e.base[0] + e.base[1];
  if (base != 0.0) e.residual -= base;
  ++count_;
}

BuildingEnergy EnergyObserver::balance() const {
  const EnergyTerms& e = terms_;
  BuildingEnergy out;
  for (int i = 0; i < 2; ++i) {
    BuildingEnergy::Part p;
    p.input = e.input[i];
    p.kinetic = e.kinetic[i];
    p.storeys = {e.storey[i]};
    p.isolator = p.isolator_dissipated = e.base[i];
    out.buildings.push_back(p);
  }
  if (link_) out.links = {e.link};
  out.contacts = {e.contact};
  out.input = e.total_input();
  out.residual = e.residual;
  return out;
}

}  // namespace adjoin
