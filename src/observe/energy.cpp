#include "adjoin/observe/energy.hpp"

namespace adjoin {

void EnergyObserver::begin(const structure::Structure& s, const StructureSolverOptions&) {
  m_[0] = s.a.masses[0];
  m_[1] = s.b->masses[0];
  link_ = !s.links.empty();
  sliders_ = s.ground_sliders().size() == 2;
  contact_law_ = s.contacts.at(0).law.model != structure::ContactModel::none;
  count_ = 0;
  terms_ = EnergyTerms{};
  v_[0] = v_[1] = 0.0;
}

void EnergyObserver::observe(const StructureState& s) {
  // This sample's powers: the right ends of this step's trapezoids, kept as the left ends of
  // the next step's. The base friction's sliders follow the link in the link arrays.
  const double v[2] = {s.v[0], s.v[1]}, force[2] = {s.storey_force[0], s.storey_force[1]};
  const Eigen::Index first_slider = link_ ? 1 : 0;
  const double slider[2] = {sliders_ ? s.link_force[first_slider] : 0.0, sliders_ ? s.link_force[first_slider + 1] : 0.0};
  Powers now;
  now.t = s.t;
  for (int i = 0; i < 2; ++i) {
    now.input[i] = s.ag * (m_[i] * v[i]);
    now.storey[i] = force[i] * v[i];
    now.base[i] = slider[i] * v[i];
  }
  now.link = (link_ ? s.link_force[0] : 0.0) * (v[0] - v[1]);
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
  v_[0] = v[0];
  v_[1] = v[1];
  if (contact_law_) {
    e.contact = s.contact_work[0];
    e.contact_dissipated = s.contact_dissipated[0];
  }
  ++count_;
}

EnergyTerms EnergyObserver::terms() const {
  EnergyTerms e = terms_;
  if (count_ == 0) return e;
  for (int i = 0; i < 2; ++i) e.kinetic[i] = 0.5 * m_[i] * v_[i] * v_[i];
  e.residual = e.total_input() - (e.total_kinetic() + e.storey[0] + e.storey[1] + e.link + e.contact);
  const double base = e.base[0] + e.base[1];
  if (base != 0.0) e.residual -= base;
  return e;
}

BuildingEnergy EnergyObserver::balance() const {
  const EnergyTerms e = terms();
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
