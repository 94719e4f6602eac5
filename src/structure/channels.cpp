#include "adjoin/structure/channels.hpp"

#include <array>

namespace adjoin::structure {
namespace {

constexpr QuantityInfo kQuantities[] = {
    {Quantity::displacement, ChannelScope::floor, "x", "", "m", PeakRule::refined, true,
     "floor displacement relative to the ground"},
    {Quantity::drift, ChannelScope::storey, "drift", "", "m", PeakRule::refined, false,
     "storey drift x_i - x_(i-1)"},
    {Quantity::drift_ratio, ChannelScope::storey, "drift_ratio", "", "-", PeakRule::refined, false,
     "storey drift ratio (x_i - x_(i-1)) / h_i (buildings with storey heights)"},
    {Quantity::absolute_acceleration, ChannelScope::floor, "a", "_abs", "m/s^2", PeakRule::sampled, true,
     "floor absolute acceleration"},
    {Quantity::storey_shear, ChannelScope::storey, "shear", "", "N", PeakRule::sampled, false,
     "storey shear (spring and devices)"},
    {Quantity::base_shear, ChannelScope::building, "base_shear", "", "N", PeakRule::sampled, false,
     "base shear -sum m_i a_i,abs"},
    {Quantity::link_force, ChannelScope::link, "force", "", "N", PeakRule::sampled, true,
     "link force (-q on A's floor, +q on B's)"},
    {Quantity::link_stroke, ChannelScope::link, "stroke", "", "m", PeakRule::refined, true,
     "link stroke x_A,i - x_B,j"},
    {Quantity::contact_gap, ChannelScope::contact, "gap", "", "m", PeakRule::none, true,
     "contact pair's gap (negative: overlap)"},
    {Quantity::contact_force, ChannelScope::contact, "force", "", "N", PeakRule::none, true,
     "contact pair's compressive force"},
    {Quantity::hysteretic, ChannelScope::storey, "hyst", "", "m", PeakRule::sampled, false,
     "storey's hysteretic variable z of a yielding storey (bilinear: at most F_y / k in size; Bouc-Wen: its z)"},
};

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

const QuantityInfo& info(Quantity q) {
  for (const auto& i : kQuantities)
    if (i.quantity == q) return i;
  return kQuantities[0];  // unreachable: every Quantity has its row
}

std::vector<Channel> channels(const Structure& s) {
  std::vector<Channel> out;
  auto building = [&](const Building& b, char name) {
    for (const auto& q : kQuantities) {
      if (q.scope == ChannelScope::building) out.push_back({element_name(q, name, 0), q.quantity, name, 0, -1});
      if (q.scope != ChannelScope::floor && q.scope != ChannelScope::storey) continue;
      if (q.quantity == Quantity::drift_ratio && !b.has_heights()) continue;  // needs the storey heights
      if (q.quantity == Quantity::hysteretic && b.hysteresis.model == HysteresisModel::elastic) continue;
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
