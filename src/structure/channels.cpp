#include "adjoin/structure/channels.hpp"

#include <array>

namespace adjoin::structure {
namespace {

// The quantities computed by a function of their own (StateRead::function).
// The sum of the floors' inertia forces.
double base_shear_value(const Structure& s, const Channel& c, const StructureState& st) {
  const Building& b = c.building == 'A' ? s.a : *s.b;
  const int first = s.dof(c.building, 1);
  double shear = 0.0;
  for (int i = 0; i < b.floors(); ++i) shear -= b.masses[i] * st.a_abs[first + i];
  return shear;
}
// Without the solver's gaps (a state made elsewhere), from the floors.
double contact_gap_value(const Structure& s, const Channel& c, const StructureState& st) {
  const auto k = static_cast<Eigen::Index>(c.index - 1);
  if (st.contact_gap.size() == static_cast<Eigen::Index>(s.contacts.size())) return st.contact_gap[k];
  const Contact& pair = s.contacts[static_cast<std::size_t>(k)];
  return pair.gap - (st.x[s.dof('A', pair.floor_a)] - st.x[s.dof('B', pair.floor_b)]);
}
double contact_force_value(const Structure& s, const Channel& c, const StructureState& st) {
  const auto k = static_cast<Eigen::Index>(c.index - 1);
  return st.contact_force.size() == static_cast<Eigen::Index>(s.contacts.size()) ? st.contact_force[k] : 0.0;
}
double hysteretic_value(const Structure&, const Channel& c, const StructureState& st) {
  return st.hyst.size() > c.dof ? st.hyst[c.dof] : 0.0;
}

// The table, in Quantity's order (info() indexes it).
#define ADJOIN_QUANTITY_ROW(value, scope, stem, suffix, unit, peak, timeseries, read, applies, label, meaning) \
  {Quantity::value, ChannelScope::scope, stem, suffix, unit, PeakRule::peak, timeseries, read, applies, label, meaning},
const QuantityInfo kQuantities[] = {ADJOIN_QUANTITIES(ADJOIN_QUANTITY_ROW)};
#undef ADJOIN_QUANTITY_ROW

std::string element_name(const QuantityInfo& q, char building, int index) {
  switch (q.scope) {
    case ChannelScope::floor:
    case ChannelScope::storey:
      return std::string(1, building) + "." + q.stem + std::to_string(index) + q.suffix;
    case ChannelScope::building: return std::string(1, building) + "." + q.stem;
    case ChannelScope::link: return "link" + std::to_string(index) + "." + q.stem;
    case ChannelScope::contact: return "contact" + std::to_string(index) + "." + q.stem;
  }
  return {};
}

}  // namespace

std::span<const QuantityInfo> quantities() { return kQuantities; }

const QuantityInfo& info(Quantity q) { return kQuantities[static_cast<std::size_t>(q)]; }

std::vector<Channel> channels(const Structure& s) {
  std::vector<Channel> out;
  auto building = [&](const Building& b, char name) {
    for (const auto& q : kQuantities) {
      if (q.scope == ChannelScope::building) out.push_back({element_name(q, name, 0), q.quantity, name, 0, -1});
      if (q.scope != ChannelScope::floor && q.scope != ChannelScope::storey) continue;
      if (!q.applies(b)) continue;  // (drift ratios need the storey heights; z, yielding storeys)
      // An isolated base's displacement is floor 0's (X.x0, SPEC §7), before floor 1's.
      if (q.quantity == Quantity::displacement && b.base) out.push_back({element_name(q, name, 0), q.quantity, name, 0, s.base_dof(name)});
      for (int i = 1; i <= b.floors(); ++i) out.push_back({element_name(q, name, i), q.quantity, name, i, s.dof(name, i)});
    }
  };
  building(s.a, 'A');
  if (s.b) building(*s.b, 'B');
  auto elements = [&](ChannelScope scope, std::size_t count) {
    for (std::size_t k = 1; k <= count; ++k)
      for (const auto& q : kQuantities)
        if (q.scope == scope) out.push_back({element_name(q, 'A', static_cast<int>(k)), q.quantity, 'A', static_cast<int>(k), -1});
  };
  elements(ChannelScope::link, s.links.size());
  elements(ChannelScope::contact, s.contacts.size());
  return out;
}

std::optional<Channel> find_channel(const Structure& s, const std::string& name) {
  for (auto& c : channels(s))
    if (c.name == name) return c;
  return std::nullopt;
}

}  // namespace adjoin::structure
