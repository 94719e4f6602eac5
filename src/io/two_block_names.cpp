#include "adjoin/io/two_block_names.hpp"

#include <string>
#include <utility>
#include <vector>

namespace adjoin {

std::span<const FrozenName> two_block_peak_names() {
  static const FrozenName names[] = {{"x1", &Scales::length},         {"x2", &Scales::length},
                                     {"f1", &Scales::force},          {"f2", &Scales::force},
                                     {"q", &Scales::force},           {"v1", &Scales::velocity},
                                     {"v2", &Scales::velocity},       {"a1_abs", &Scales::acceleration},
                                     {"a2_abs", &Scales::acceleration}, {"ag", &Scales::acceleration},
                                     {"drift", &Scales::length}};
  return names;
}

std::span<const FrozenName> two_block_final_names() {
  static const FrozenName names[] = {{"x1", &Scales::length},   {"x2", &Scales::length}, {"v1", &Scales::velocity},
                                     {"v2", &Scales::velocity}, {"f1", &Scales::force},  {"f2", &Scales::force},
                                     {"q", &Scales::force}};
  return names;
}

std::string two_block_quantity_name(const std::string& name) {
  static const std::pair<const char*, const char*> names[] = {{"A.x1", "x1"},         {"B.x1", "x2"},
                                                              {"link1.stroke", "stroke"}, {"A.shear1", "f1"},
                                                              {"B.shear1", "f2"},     {"link1.force", "q"}};
  for (const char* prefix : {"peak ", "t peak ", "final "}) {
    const std::string p = prefix;
    if (name.rfind(p, 0) != 0) continue;
    for (const auto& [channel, frozen] : names)
      if (name.substr(p.size()) == channel) return p + frozen;
  }
  return name;
}

namespace {
constexpr std::pair<const char*, const char*> kSignals[] = {{"block1", "A.a1_abs"}, {"block2", "B.a1_abs"}};
}  // namespace

std::string two_block_signal_channel(const std::string& signal) {
  for (const auto& [frozen, channel] : kSignals)
    if (signal == frozen) return channel;
  return signal;
}

std::string two_block_signal_name(const std::string& channel) {
  for (const auto& [frozen, floor] : kSignals)
    if (channel == floor) return frozen;
  return channel;
}

std::vector<SignalSpectrum> two_block_signal_names(std::vector<SignalSpectrum> spectra) {
  for (SignalSpectrum& s : spectra) s.signal = two_block_signal_name(s.signal);
  return spectra;
}

TwoBlockEnergy two_block_energy(const EnergyTerms& e) {
  TwoBlockEnergy out;
  out.input = e.total_input();
  out.kinetic = e.total_kinetic();
  out.rod1 = e.storey[0];
  out.rod2 = e.storey[1];
  out.friction = e.link;
  out.contact = e.contact;
  out.contact_dissipated = e.contact_dissipated;
  out.base_friction = e.base[0] + e.base[1];
  out.residual = e.residual;
  return out;
}

TwoBlockEnergy two_block_energy(const Report& r) {
  TwoBlockEnergy out;
  const BuildingEnergy& e = r.energy;
  if (e.buildings.size() != 2) return out;
  out.input = e.input;
  out.kinetic = e.buildings[0].kinetic + e.buildings[1].kinetic;
  out.rod1 = e.buildings[0].storeys.at(0);
  out.rod2 = e.buildings[1].storeys.at(0);
  out.friction = r.link_energy(0);
  out.contact = e.contacts.empty() ? 0.0 : e.contacts[0];
  out.contact_dissipated = r.contacts.empty() ? 0.0 : r.contacts[0].dissipated;
  out.base_friction = e.buildings[0].isolator + e.buildings[1].isolator;
  out.residual = e.residual;
  return out;
}

}  // namespace adjoin
