#pragma once
// The observers of a run's channels (study/run.cpp, internal): the peak of every channel, the
// links' extremes and switches, the contact pairs' gaps and impacts, the energy balance; and the
// histories of the signals whose spectra a run is asked for.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "adjoin/core/errors.hpp"
#include "adjoin/observe/channel_values.hpp"
#include "adjoin/observe/peak_table.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/study/report.hpp"

namespace adjoin::detail {

// Peaks of every channel, the links' extremes and switches, the contact pairs' gaps.
class ChannelObserver final : public StructureObserver {
 public:
  explicit ChannelObserver(const structure::Structure& s) : s_(s) {}

  void begin(const structure::Structure& s, const StructureSolverOptions&) override {
    // Every channel with a peak (structure/channels.hpp): floors, storeys, buildings, links;
    // read and kept with the refined ones first (PeakTable), reported in the channels' order.
    std::vector<structure::Channel> smooth, sampled;
    std::vector<std::pair<bool, std::size_t>> place;  // each reported channel: refined?, its index in that list
    for (auto& c : structure::channels(s)) {
      const structure::PeakRule rule = structure::info(c.quantity).peak;
      if (rule == structure::PeakRule::none) continue;
      auto& list = rule == structure::PeakRule::refined ? smooth : sampled;
      place.emplace_back(&list == &smooth, list.size());
      list.push_back(std::move(c));
    }
    const std::size_t n_smooth = smooth.size();
    order_.clear();
    for (const auto& [refined, index] : place) order_.push_back(refined ? index : n_smooth + index);
    smooth.insert(smooth.end(), sampled.begin(), sampled.end());
    values_ = ChannelValues(s, std::move(smooth));
    peaks_.reset(n_smooth, values_.size());
    links_.assign(s.links.size(), LinkReport{});
    last_force_.assign(s.links.size(), 0.0);
    last_stroke_.assign(s.links.size(), 0.0);
    friction_.clear();
    for (const structure::Link& l : s.links) friction_.push_back(structure::kind_of(l).family(l) == structure::LinkFamily::friction);
    contacts_.assign(s.contacts.size(), ContactReport{});
    for (std::size_t k = 0; k < s.contacts.size(); ++k) contacts_[k].model = s.contacts[k].law.model;
    contact_work_.assign(s.contacts.size(), 0.0);
    parts_.clear();
    parts_.push_back(EnergyPart(s, s.a, 0));
    if (s.b) parts_.push_back(EnergyPart(s, *s.b, s.a.floors()));
    // The isolated bases (SPEC §7): each slider's place in the state's link arrays (after the
    // links) and its X.x0 channel.
    // (A base friction under floor 1, the two-block scene's, is a slider with no X.x0.)
    bases_.clear();
    for (const structure::GroundSlider& slider : s.ground_sliders()) {
      Base base;
      base.report.building = slider.building;
      base.slider = s.links.size() + bases_.size();
      base.dof = slider.dof;
      base.isolated = slider.base;
      base.stiffness = slider.base ? (slider.building == 'A' ? s.a : *s.b).base_stiffness() : 0.0;
      for (std::size_t i = 0; i < values_.size(); ++i)
        if (values_.channels()[i].name == std::string(1, slider.building) + ".x0") base.channel = i;
      bases_.push_back(base);
    }
    std::size_t powers = s.links.size() + bases_.size();
    for (const EnergyPart& p : parts_) powers += 2 + p.masses.size();
    last_powers_.assign(powers, 0.0);
    powers_.assign(powers, 0.0);
    work_.assign(powers, 0.0);
    kinetic_.assign(parts_.size(), 0.0);
    last_phase_.assign(s.links.size() + bases_.size(), Phase::stick);
    last_power_.assign(s.links.size(), 0.0);
    input_scale_ = 0.0;
    first_ = true;
  }

  void observe(const StructureState& st) override {
    values_.read(st, peaks_.row());
    peaks_.update(st.t);
    for (std::size_t l = 0; l < s_.links.size(); ++l) {
      LinkReport& r = links_[l];
      r.force_max = std::max(r.force_max, std::abs(st.link_force[l]));
      r.stroke_max = std::max(r.stroke_max, std::abs(st.link_stroke[l]));
      if (friction_[l] && !first_ && st.link_phase[l] != last_phase_[l]) {
        ++r.switches;
        r.switch_times.push_back(std::isnan(st.link_switch[l]) ? st.t : st.link_switch[l]);
      }
      // Work of the link's force on its relative motion (trapezoidal in time); links() takes
      // off what an elastic link still holds (its kind's rule, from its last force and stroke).
      if (!first_) r.energy += 0.5 * (st.t - last_t_) * (st.link_force[l] * st.link_velocity[l] + last_power_[l]);
      last_force_[l] = st.link_force[l];
      last_stroke_[l] = st.link_stroke[l];
    }
    const auto n_contacts = static_cast<Eigen::Index>(s_.contacts.size());
    for (std::size_t k = 0; k < s_.contacts.size(); ++k) {
      const auto& pair = s_.contacts[k];
      const auto i = static_cast<Eigen::Index>(k);
      const double gap = st.contact_gap.size() == n_contacts
                             ? st.contact_gap[i]
                             : pair.gap - (st.x[s_.dof('A', pair.floor_a)] - st.x[s_.dof('B', pair.floor_b)]);
      ContactReport& r = contacts_[k];
      if (first_ || gap < r.min_gap) { r.min_gap = gap; r.t_min_gap = st.t; }
      if (!r.contact && gap <= 0.0) { r.contact = true; r.t_first_contact = st.t; }
      if (st.contact_work.size() == n_contacts) contact_work_[k] = st.contact_work[i];
      if (st.contact_dissipated.size() == n_contacts) r.dissipated = st.contact_dissipated[i];
    }
    for (Base& b : bases_) {
      const double power = st.link_force[static_cast<Eigen::Index>(b.slider)] * st.link_velocity[static_cast<Eigen::Index>(b.slider)];
      if (!first_) {
        if (st.link_phase[b.slider] != last_phase_[b.slider]) ++b.report.switches;
        b.report.energy += 0.5 * (st.t - last_t_) * (power + b.last_power);
      }
      b.last_power = power;
    }
    energy_step(st);
    check_contact_energy(st.t);
    for (std::size_t l = 0; l < last_phase_.size(); ++l) last_phase_[l] = st.link_phase[l];
    for (std::size_t l = 0; l < s_.links.size(); ++l) last_power_[l] = st.link_force[l] * st.link_velocity[l];
    last_t_ = st.t;
    first_ = false;
  }

  void impact(const Impact& e) override {
    if (e.contact >= 0 && static_cast<std::size_t>(e.contact) < contacts_.size())
      contacts_[static_cast<std::size_t>(e.contact)].impact_list.push_back(e);
  }

  // Powers at a grid point, integrated by the trapezoidal rule between grid points: per
  // building its input, its inherent damping and each storey, then each link. The powers are
  // made into an array (powers_), then every term is integrated in one pass over the arrays
  // sized in begin() (work_[k] += dt/2 (power + its last value): independent terms, a loop the
  // compiler vectorises); a step allocates nothing.
  void energy_step(const StructureState& st) {
    double* __restrict power = powers_.data();
    std::size_t k = 0;
    for (std::size_t part = 0; part < parts_.size(); ++part) k += building_powers(parts_[part], st, power + k, &kinetic_[part]);
    for (std::size_t l = 0; l < s_.links.size(); ++l) power[k++] = st.link_force[l] * st.link_velocity[l];
    // Each isolator: its slider's power and its pendulum's, k_p x_b v_b.
    for (const Base& b : bases_) {
      const auto l = static_cast<Eigen::Index>(b.slider);
      power[k++] = st.link_force[l] * st.link_velocity[l] + b.stiffness * st.x[b.dof] * st.v[b.dof];
    }
    if (!first_) {
      const double half_dt = 0.5 * (st.t - last_t_);
      double* __restrict work = work_.data();
      const double* __restrict last = last_powers_.data();
      for (std::size_t i = 0; i < k; ++i) work[i] += half_dt * (power[i] + last[i]);
    }
    powers_.swap(last_powers_);  // (this step's powers are the next step's last)
    // The input so far (the contact check's scale), summed as energy() sums it.
    input_ = 0.0;
    input_ += work_[0];
    if (s_.b) input_ += work_[2 + static_cast<std::size_t>(s_.a.floors())];
  }

  // The balance at the last grid point (see BuildingEnergy).
  BuildingEnergy energy() const {
    BuildingEnergy e;
    std::size_t k = 0, part = 0;
    auto unpack = [&](const structure::Building& b) {
      BuildingEnergy::Part p;
      p.input = work_.at(k++);
      p.inherent = work_.at(k++);
      for (int i = 0; i < b.floors(); ++i) p.storeys.push_back(work_.at(k++));
      p.kinetic = kinetic_.at(part++);
      e.input += p.input;
      e.buildings.push_back(p);
    };
    unpack(s_.a);
    if (s_.b) unpack(*s_.b);
    for (std::size_t l = 0; l < s_.links.size(); ++l) e.links.push_back(work_.at(k++));
    for (const Base& b : bases_) {
      BuildingEnergy::Part& p = e.buildings[b.report.building == 'A' ? 0 : 1];
      p.isolator += work_.at(k++);
      p.isolator_dissipated += b.report.energy;
    }
    double out = 0.0;
    for (const auto& p : e.buildings) {
      out += p.kinetic + p.inherent + p.isolator;
      for (double w : p.storeys) out += w;
    }
    for (double w : e.links) out += w;
    e.contacts = contact_work_;  // exact from the solver, not integrated here
    for (double w : e.contacts) out += w;
    e.residual = e.input - out;
    return e;
  }

  // Every contact law stores or dissipates the work done on it, never gives back more: a pair
  // whose dissipated energy falls below -1 % of the input so far has a step too long for its
  // stiffness (with a friction damper on the same floors the two are split within the step,
  // and a very stiff contact breaks that split). A wrong answer would follow: exit 3.
  void check_contact_energy(double t) {
    input_scale_ = std::max(input_scale_, std::abs(input_));
    for (std::size_t k = 0; k < contacts_.size(); ++k)
      if (-contacts_[k].dissipated > 1e-2 * input_scale_) refuse_contact_energy(k, t);
  }
  // (Out of line: the message is built only when it is thrown.)
  [[noreturn, gnu::noinline, gnu::cold]] void refuse_contact_energy(std::size_t k, double t) const {
    const double created = -contacts_[k].dissipated;
    std::ostringstream m;
    m << "contact pair " << k + 1 << " (" << structure::to_string(s_.contacts[k].law.model) << "): at t = " << t
      << " s it has given back " << created << " J more than the work done on it (the input so far " << input_scale_
      << " J): the step is too long for the contact's stiffness; make solver.h smaller or lower contact["
      << k + 1 << "].stiffness (docs/how-to/choose-contact-stiffness.md)";
    throw NumericalError(m.str(), t);
  }

  std::vector<ChannelPeak> peaks() const {
    std::vector<ChannelPeak> out;
    for (std::size_t i : order_) out.push_back({values_.channels()[i].name, peaks_.peak(i)});
    return out;
  }
  // Each drift and drift-ratio channel at the last grid point observed (SPEC §7 `residual`).
  std::vector<ChannelValue> residual() const {
    std::vector<ChannelValue> out;
    for (std::size_t i : order_) {
      const structure::Quantity q = values_.channels()[i].quantity;
      const bool base = q == structure::Quantity::displacement && values_.channels()[i].index == 0;  // X.x0
      if (q == structure::Quantity::drift || q == structure::Quantity::drift_ratio || base) out.push_back({values_.channels()[i].name, peaks_.last()[i]});
    }
    return out;
  }
  // The isolated bases (SPEC §7 `base`): X.x0's peak and its value at the last grid point.
  std::vector<BaseReport> bases() const {
    std::vector<BaseReport> out;
    for (const Base& b : bases_) {
      if (!b.isolated) continue;
      BaseReport r = b.report;
      const Peak peak = peaks_.peak(b.channel);
      r.max_abs = peak.max_abs;
      r.t = peak.t;
      r.residual = peaks_.last()[b.channel];
      out.push_back(r);
    }
    return out;
  }
  // The links, each with the work dissipated in it (LinkReport::energy): the work done on it,
  // less what its elastic part still holds at the last grid point (LinkKind::dissipated).
  std::vector<LinkReport> links() const {
    std::vector<LinkReport> out = links_;
    for (std::size_t l = 0; l < out.size(); ++l) {
      const structure::Link& link = s_.links[l];
      out[l].energy = structure::kind_of(link).dissipated(link, out[l].energy, last_force_[l], last_stroke_[l]);
    }
    return out;
  }
  // The contact pairs with their impacts' totals (in the order the impacts started).
  std::vector<ContactReport> contacts() const {
    std::vector<ContactReport> out = contacts_;
    for (ContactReport& r : out) {
      auto& list = r.impact_list;
      std::stable_sort(list.begin(), list.end(), [](const Impact& a, const Impact& b) { return a.start < b.start; });
      r.impacts = list.size();
      for (const Impact& e : list) {
        if (e.force_max > r.force_max) { r.force_max = e.force_max; r.t_force_max = e.t_force_max; }
        r.penetration_max = std::max(r.penetration_max, e.penetration_max);
        r.impulse += e.impulse;
        r.impulse_max = std::max(r.impulse_max, e.impulse);
      }
      if (!list.empty()) {
        r.t_first_contact = r.contact ? std::min(r.t_first_contact, list.front().start) : list.front().start;
        r.contact = true;
      }
      if (r.model == structure::ContactModel::none && r.contact) r.unmodelled_from = r.t_first_contact;
    }
    for (std::size_t k = 0; k < out.size(); ++k) out[k].work = contact_work_[k];
    return out;
  }

 private:
  const structure::Structure& s_;
  struct Base {
    BaseReport report;
    std::size_t slider = 0, channel = 0;  // its slider in the state's link arrays; its X.x0 among values_
    int dof = -1;
    bool isolated = true;     // an isolated base's slider (else a base friction under floor 1)
    double stiffness = 0.0;   // a friction pendulum's W / R
    double last_power = 0.0;  // the slider's at the last grid point
  };
  std::vector<Base> bases_;
  ChannelValues values_;
  // The channels' last values and peaks: displacements, drifts, strokes refined between
  // samples; accelerations, shears, link forces (kinks at switches) the largest samples.
  PeakTable peaks_;
  std::vector<std::size_t> order_;  // the channels' places in values_, in the channels' order
  std::vector<LinkReport> links_;
  std::vector<double> last_force_, last_stroke_;  // per link, at the last grid point
  std::vector<char> friction_;                     // per link: a friction link's (it counts switches)
  std::vector<ContactReport> contacts_;
  std::vector<double> contact_work_;  // the solver's contact_work at the last grid point
  std::vector<Phase> last_phase_;
  // A building's part of the energy balance: its floors' masses and inherent damping matrix
  // (row-major), and its velocities relative to its base (a work array).
  struct EnergyPart {
    EnergyPart(const structure::Structure& s, const structure::Building& b, int first) : offset(first) {
      const int n = b.floors();
      base = s.base_dof(first == 0 ? 'A' : 'B');
      base_mass = base >= 0 ? b.base->mass : 0.0;
      masses.assign(b.masses.data(), b.masses.data() + n);
      const Eigen::MatrixXd damping = structure::inherent_damping_matrix(b);
      c.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) c[static_cast<std::size_t>(i * n + j)] = damping(i, j);
      v.assign(static_cast<std::size_t>(n), 0.0);
    }
    int offset = 0, base = -1;
    double base_mass = 0.0;
    std::vector<double> masses, c, v;
  };
  std::vector<EnergyPart> parts_;                    // A's, then B's

  // A building's powers into `power`: its input, its inherent damping v'C v, each storey's;
  // returns how many (2 + floors). Small buildings take a copy compiled for their number of
  // floors (the loops unrolled, the velocities in registers: the dynamic-size loops' set-up
  // and counting cost more than their few multiply-adds); the same operations in the same
  // order either way.
  static std::size_t building_powers(EnergyPart& p, const StructureState& st, double* power, double* kinetic) {
    switch (p.masses.size()) {
      case 1: return powers_of<1>(p, st, power, kinetic);
      case 2: return powers_of<2>(p, st, power, kinetic);
      case 3: return powers_of<3>(p, st, power, kinetic);
      case 4: return powers_of<4>(p, st, power, kinetic);
      case 5: return powers_of<5>(p, st, power, kinetic);
      case 6: return powers_of<6>(p, st, power, kinetic);
      case 7: return powers_of<7>(p, st, power, kinetic);
      case 8: return powers_of<8>(p, st, power, kinetic);
      default: return powers_of<0>(p, st, power, kinetic);
    }
  }
  // N floors (0: any number, p.masses.size()).
  template <std::size_t N>
  static std::size_t powers_of(EnergyPart& p, const StructureState& st, double* __restrict power, double* kinetic) {
    const std::size_t n = N > 0 ? N : p.masses.size();
    const double* __restrict v_abs = st.v.data() + p.offset;
    const double* __restrict force = st.storey_force.data() + p.offset;
    const double* __restrict mass = p.masses.data();
    double fixed[N > 0 ? N : 1];  // (N floors: the relative velocities kept in registers)
    double* __restrict v = N > 0 ? fixed : p.v.data();
    // An isolated base (SPEC §7): its mass takes input and kinetic energy, the inherent
    // damping acts on the floors' velocities relative to it, storey 1 deforms against it.
    const double vb = p.base >= 0 ? st.v[p.base] : 0.0;
    double momentum = p.base_mass * vb, twice_kinetic = p.base_mass * vb * vb;
    for (std::size_t i = 0; i < n; ++i) {
      momentum += mass[i] * v_abs[i];
      twice_kinetic += mass[i] * v_abs[i] * v_abs[i];
      v[i] = v_abs[i] - vb;
    }
    power[0] = st.ag * momentum;  // input
    *kinetic = 0.5 * twice_kinetic;
    double damping = 0.0;  // v' C v, C row-major
    for (std::size_t i = 0; i < n; ++i) {
      const double* __restrict row = p.c.data() + i * n;
      double cv = 0.0;
      for (std::size_t j = 0; j < n; ++j) cv += row[j] * v[j];
      damping += v[i] * cv;
    }
    power[1] = damping;  // inherent damping
    double below = 0.0;  // storey i's deformation rate v_i - v_{i-1}
    for (std::size_t i = 0; i < n; ++i) {
      power[2 + i] = force[i] * (v[i] - below);
      below = v[i];
    }
    return 2 + n;
  }

  std::vector<double> powers_, last_powers_, work_;  // per power term (energy_step): now, at the last grid point, integrated
  std::vector<double> kinetic_;                      // per building, at the last grid point
  double input_ = 0.0;                               // the input so far [J]
  std::vector<double> last_power_;
  double last_t_ = 0.0;
  double input_scale_ = 0.0;  // the largest |input energy| so far [J]
  bool first_ = true;
};

// Keeps the histories of the signals whose spectra are asked for: a_g or a floor's a_abs.
class SignalRecorder final : public StructureObserver {
 public:
  SignalRecorder(const structure::Structure& s, const std::vector<std::string>& signals) {
    for (const auto& signal : signals) {
      int index = -1;  // a_g
      if (signal != "ground") {
        // io checked the name: a floor's absolute acceleration (X.aN_abs).
        const auto channel = structure::find_channel(s, signal);
        if (!channel || channel->quantity != structure::Quantity::absolute_acceleration)
          throw InputError("output.spectra.signals: \"" + signal + "\" is not a floor's absolute acceleration (A.a3_abs)");
        index = channel->dof;
      }
      index_.push_back(index);
    }
    histories.assign(signals.size(), {});
  }
  void observe(const StructureState& st) override {
    for (std::size_t k = 0; k < index_.size(); ++k) histories[k].push_back(index_[k] < 0 ? st.ag : st.a_abs[index_[k]]);
  }
  std::vector<std::vector<double>> histories;

 private:
  std::vector<int> index_;
};

}  // namespace adjoin::detail
