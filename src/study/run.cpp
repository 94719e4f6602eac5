#include "adjoin/study/run.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <utility>

#include "adjoin/core/errors.hpp"
#include "adjoin/structure/device_kinds.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "adjoin/structure/two_block.hpp"
#include "adjoin/study/run_watch.hpp"
#include "channel_observer.hpp"
#include "collapse_observer.hpp"
#include "yield_observer.hpp"

namespace adjoin {

Model two_block_model(const RunSpec& spec) {
  std::string why;
  const std::optional<Model> model = structure::two_block_model(spec.structure, &why);
  if (!model) throw InputError((spec.file.empty() ? spec.name : spec.file.string()) + ": " + why);
  return *model;
}

SolverOptions two_block_options(const RunSpec& spec) {
  SolverOptions o;
  o.scheme = spec.solver.scheme;
  o.history = spec.solver.history;
  o.h = spec.solver.h;
  o.t_end = spec.solver.t_end;
  o.stability_check = spec.solver.stability_check;
  o.locate_switches = spec.solver.locate_switches;
  o.history_tolerance = spec.solver.history_tolerance;
  return o;
}

double Report::unmodelled_from() const {
  double t = std::numeric_limits<double>::quiet_NaN();
  for (const auto& c : contacts)
    if (c.outside_model() && !(t <= c.unmodelled_from)) t = c.unmodelled_from;
  return t;
}

Peak Report::peak(const std::string& channel) const { return find_peak(peaks, channel); }

double Report::last_value(const std::string& channel) const {
  for (const ChannelValue& v : last)
    if (v.channel == channel) return v.value;
  return 0.0;
}

namespace {

// ---- buildings ----

// Fans every call out to a list of structure observers (not owned), in order. Only the
// observers added as able to stop the run (a collapse watch, the caller's) are ever asked
// done(), by the StoppableObserverList made of this one when there are any: the report's own
// observers never stop a run, and a list that does not override done() costs the time loop
// nothing at each step (its call is devirtualised).
class StructureObserverList : public StructureObserver {
 public:
  void add(StructureObserver* o, bool may_stop = true) {
    if (!o) return;
    observers_.push_back(o);
    if (may_stop) stoppers_.push_back(o);
  }
  // A list's observers join this one in their order (one virtual call per observer and step,
  // not two); any other observer is added.
  void add_flat(StructureObserver* o) {
    if (const auto* list = dynamic_cast<const StructureObserverList*>(o)) {
      observers_.insert(observers_.end(), list->observers_.begin(), list->observers_.end());
      stoppers_.insert(stoppers_.end(), list->stoppers_.begin(), list->stoppers_.end());
    } else {
      add(o);
    }
  }
  bool may_stop() const { return !stoppers_.empty(); }
  // The list's one observer when it has one and nothing in it may stop the run (the loop then
  // calls it directly, not through the list: a two-block run's report is one observer).
  StructureObserver* only() const { return observers_.size() == 1 && stoppers_.empty() ? observers_.front() : nullptr; }
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override { for (auto* x : observers_) x->begin(s, o); }
  void observe(const StructureState& st) override { for (auto* x : observers_) x->observe(st); }
  void impact(const Impact& e) override { for (auto* x : observers_) x->impact(e); }
  void end() override { for (auto* x : observers_) x->end(); }

 protected:
  std::vector<StructureObserver*> observers_, stoppers_;
};

// A list whose stoppers are asked done() after each state.
class StoppableObserverList final : public StructureObserverList {
 public:
  explicit StoppableObserverList(const StructureObserverList& list) : StructureObserverList(list) {}
  bool done() const override {
    return std::any_of(stoppers_.begin(), stoppers_.end(), [](const StructureObserver* x) { return x->done(); });
  }
};

// ---- the 1 + 1 structure's refined report (a scene written with the two-block keys) ----

// Keeps the last grid point's values (Report::last) and phase, read at end() from the state
// observed last (the stepper's own, still valid then: solver/time_loop.hpp), not copied at
// every step.
class LastValues final : public StructureObserver {
 public:
  void begin(const structure::Structure& s, const StructureSolverOptions&) override {
    link_ = !s.links.empty();
    last_ = nullptr;
  }
  void observe(const StructureState& s) override { last_ = &s; }
  void end() override {
    if (!last_) return;
    const StructureState& s = *last_;
    t_ = s.t;
    const double values[] = {s.x[0], s.x[1], s.v[0], s.v[1], s.storey_force[0], s.storey_force[1], link_ ? s.link_force[0] : 0.0};
    const char* const channels[] = {"A.x1", "B.x1", "A.v1", "B.v1", "A.shear1", "B.shear1", "link1.force"};
    values_.clear();
    for (std::size_t i = 0; i < std::size(channels); ++i) values_.push_back({channels[i], values[i]});
    // Link 1's phase, or the sign of the floors' relative velocity (observe/pair_phase.hpp).
    const double w = s.v[0] - s.v[1];
    phase_ = link_ ? s.link_phase[0] : (w > 0.0 ? Phase::slip_right : (w < 0.0 ? Phase::slip_left : Phase::stick));
    last_ = nullptr;
  }
  void report(Report& r) const {
    r.last = values_;
    r.last_phase = phase_;
    r.t_last = t_;
  }

 private:
  const StructureState* last_ = nullptr;
  bool link_ = false;
  double t_ = 0.0;
  std::vector<ChannelValue> values_;
  Phase phase_ = Phase::stick;
};

// Keeps the acceleration histories that spectra need (only when spectra are asked for): the
// ground's and the 1 + 1 structure's floors' absolute accelerations ("ground", A.a1_abs,
// B.a1_abs).
class AccelerationRecorder final : public StructureObserver {
 public:
  void begin(const structure::Structure&, const StructureSolverOptions& o) override {
    for (auto* v : {&ag, &a_abs[0], &a_abs[1]}) { v->clear(); v->reserve(o.steps() + 1); }
  }
  // (Out of line: inlined into PairReport::observe, its push_backs' reallocation paths made
  // that save and restore six registers at every step of every run, spectra asked or not.)
  [[gnu::noinline]] void observe(const StructureState& s) override {
    ag.push_back(s.ag);
    a_abs[0].push_back(s.a_abs[0]);
    a_abs[1].push_back(s.a_abs[1]);
  }
  std::vector<double> ag, a_abs[2];
};

// The signals a 1 + 1 structure's run keeps for spectra (AccelerationRecorder's): a spec made in
// code may name others, which io's reader refuses in a scene.
void check_pair_signals(const RunSpec& spec) {
  if (!spec.output.spectra) return;
  for (const std::string& signal : spec.output.spectra->signals)
    if (signal != "ground" && signal != "A.a1_abs" && signal != "B.a1_abs")
      throw InputError("output.spectra.signals: \"" + signal +
                       "\" is not a signal of a two-block run; expected \"ground\", \"A.a1_abs\" or \"B.a1_abs\"");
}

std::vector<SignalSpectrum> spectra_of(const RunSpec& spec, const AccelerationRecorder& recorded) {
  const SpectraOutput& asked = *spec.output.spectra;
  const Scales& k = spec.scales;
  SpectrumOptions options;
  options.dampings = asked.damping;
  // Periods are in the scene's time unit already, as is the step below.
  options.periods = asked.periods.empty() ? default_spectrum_periods() : asked.periods;
  // The library works in m/s^2 and s; dimensionless accelerations are in g. For a
  // dimensionless scene, lengths come out multiplied by g and are divided back below.
  const double dt = spec.solver.h * k.time;
  const double length_back = k.si ? 1.0 : 1.0 / kStandardGravity;
  std::vector<SignalSpectrum> out;
  for (const std::string& signal : asked.signals) {
    const std::vector<double>& a = signal == "ground" ? recorded.ag : recorded.a_abs[signal == "A.a1_abs" ? 0 : 1];
    std::vector<double> accel(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) accel[i] = a[i] * kStandardGravity;
    SignalSpectrum s{signal, response_spectrum(dt, accel, options)};
    for (auto& v : s.spectrum.values) {
      v.sd *= length_back;
      v.sv *= length_back;
      v.psv *= length_back;
    }
    out.push_back(std::move(s));
  }
  return out;
}

// The pounding margin as the 1 + 1 structure's contact pair (its work: the energy observer's).
ContactReport contact_report(const PoundingMargin& g, double work) {
  ContactReport c;
  c.model = g.model;
  c.min_gap = g.min_gap;
  c.t_min_gap = g.t_min_gap;
  c.contact = g.contact;
  c.t_first_contact = g.t_first_contact.value_or(0.0);
  c.impact_list = g.impacts;
  c.impacts = g.impacts.size();
  c.force_max = g.force_max;
  c.t_force_max = g.t_force_max;
  c.penetration_max = g.penetration_max;
  c.impulse = g.impulse;
  c.impulse_max = g.impulse_max;
  c.work = work;
  c.dissipated = g.dissipated;
  if (g.outside_model()) c.unmodelled_from = *g.t_first_contact;
  return c;
}

// The observers a run's report is made of, chosen by how the scene presents the structure:
// its channels (a building scene), or the paper's refined values of the 1 + 1 structure (a
// scene written with the two-block keys: SPEC §3's quantities, observe/peaks.hpp, phases.hpp,
// pounding.hpp, energy.hpp). Either joins the run's one list of observers and fills the one
// Report when the run is over.
class ReportObservers {
 public:
  virtual ~ReportObservers() = default;
  virtual void join(StructureObserverList& all) = 0;
  virtual void fill(const RunSpec& spec, Report& r) const = 0;
};

// One observer for all of them, so that a step costs one virtual call rather than one per
// observer, and link 1's phase is read once for the three that need it (peaks, phases,
// pounding). Each receives the calls it would receive in the run's list, in the same order.
class PairReport final : public StructureObserver, public ReportObservers {
 public:
  explicit PairReport(const OutputOptions& asked)
      : asked_(asked), peaks_on_(asked.peaks), phases_on_(asked.phases), energy_on_(asked.energy) {
    if (asked.spectra) accelerations_ = std::make_unique<AccelerationRecorder>();
  }
  void join(StructureObserverList& all) override { all.add(this, false); }
  void fill(const RunSpec& spec, Report& r) const override {
    last_.report(r);
    if (asked_.phases) r.phases = phases_.intervals();
    if (asked_.peaks) r.peaks = peaks_.peaks();
    if (asked_.energy) r.energy = energy_.balance();
    r.contacts = {contact_report(pounding_.margin(), energy_.terms().contact)};
    if (accelerations_) r.spectra = spectra_of(spec, *accelerations_);
  }

  void begin(const structure::Structure& s, const StructureSolverOptions& o) override {
    phase_.begin(s, o);
    last_.begin(s, o);
    if (asked_.peaks) peaks_.begin(s, o);
    if (asked_.phases) phases_.begin(s, o);
    pounding_.begin(s, o);
    if (asked_.energy) energy_.begin(s, o);
    if (accelerations_) accelerations_->begin(s, o);
  }
  void observe(const StructureState& s) override {
    phase_.update(s);
    last_.observe(s);
    if (peaks_on_) peaks_.observe(s, phase_);
    if (phases_on_) phases_.observe(s, phase_);
    // Always watched (it costs a few operations a step): a run without a contact law whose gap
    // closes is flagged even when the pounding margin is not reported.
    pounding_.observe(s, phase_);
    if (energy_on_) energy_.observe(s);
    if (accelerations_) accelerations_->observe(s);
  }
  void impact(const Impact& i) override {
    last_.impact(i);
    if (asked_.peaks) peaks_.impact(i);
    if (asked_.phases) phases_.impact(i);
    pounding_.impact(i);
    if (asked_.energy) energy_.impact(i);
    if (accelerations_) accelerations_->impact(i);
  }
  void end() override {
    last_.end();
    if (asked_.peaks) peaks_.end();
    if (asked_.phases) phases_.end();
    pounding_.end();
    if (asked_.energy) energy_.end();
    if (accelerations_) accelerations_->end();
  }

 private:
  const OutputOptions& asked_;
  const bool peaks_on_, phases_on_, energy_on_;  // asked_'s, read at each step without its indirection
  PairPhase phase_;  // link 1's phase, shared by the refined observers
  PeakObserver peaks_;
  PhaseObserver phases_;
  PoundingObserver pounding_;
  EnergyObserver energy_;
  LastValues last_;
  std::unique_ptr<AccelerationRecorder> accelerations_;
};

// ---- buildings, continued ----

// The structure's Zener elements (each storey of a Zener device, each Zener link) and their
// distinct orders (the weights are computed once per order).
std::pair<std::size_t, std::size_t> zener_elements(const structure::Structure& s) {
  std::size_t elements = 0;
  std::vector<double> orders;
  for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr}) {
    if (!b) continue;
    for (const auto& d : b->devices)
      if (structure::kind_of(d).family(d) == structure::DeviceFamily::zener) {
        elements += d.storeys.size();
        orders.push_back(d.zener.order);
      }
  }
  for (const auto& l : s.links)
    if (structure::kind_of(l).family(l) == structure::LinkFamily::zener) {
      ++elements;
      orders.push_back(l.zener.order);
    }
  std::sort(orders.begin(), orders.end());
  return {elements, static_cast<std::size_t>(std::unique(orders.begin(), orders.end()) - orders.begin())};
}

std::string shortest(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

// A structure's channels, links, contact pairs, energy balance, yielding storeys and isolated
// bases (study/channel_observer.hpp, yield_observer.hpp), and the modes.
class ChannelReport final : public ReportObservers {
 public:
  ChannelReport(const structure::Structure& s, const OutputOptions& asked)
      : s_(s), observer_(s), yielding_(s), asked_(asked.spectra) {
    if (asked_) recorder_ = std::make_unique<detail::SignalRecorder>(s, asked_->signals);
  }
  void join(StructureObserverList& all) override {
    all.add(&observer_, false);
    if (yielding_.watches()) all.add(&yielding_, false);  // (its report is empty otherwise)
    all.add(recorder_.get(), false);
  }
  void fill(const RunSpec& spec, Report& r) const override {
    r.modes.push_back(structure::building_modes(s_.a));
    if (s_.b) {
      r.modes.push_back(structure::building_modes(*s_.b));
      r.coupled = structure::coupled_modes(s_);
    }
    if (recorder_) {
      SpectrumOptions options;
      options.dampings = asked_->damping;
      options.periods = asked_->periods.empty() ? default_spectrum_periods() : asked_->periods;
      for (std::size_t k = 0; k < asked_->signals.size(); ++k)
        r.spectra.push_back({asked_->signals[k], response_spectrum(spec.solver.h, recorder_->histories[k], options)});
    }
    r.peaks = observer_.peaks();
    r.links = observer_.links();
    r.contacts = observer_.contacts();
    r.energy = observer_.energy();
    r.residual = observer_.residual();
    r.bases = observer_.bases();
    r.yield = yielding_.report();
    for (const BuildingYield& y : r.yield)
      for (const StoreyYield& st : y.storeys) r.energy.buildings[y.building == 'A' ? 0 : 1].hysteretic.push_back(st.plastic_work);
  }

 private:
  const structure::Structure& s_;
  detail::ChannelObserver observer_;
  detail::YieldObserver yielding_;
  const std::optional<SpectraOutput>& asked_;
  std::unique_ptr<detail::SignalRecorder> recorder_;
};

}  // namespace

double estimated_run_bytes(const RunSpec& spec) {
  const double steps = static_cast<double>(spec.solver.steps()) + 2.0;
  const auto [elements, orders] = zener_elements(spec.structure);
  // (soe: a constant few kilobytes per element, in the last term.)
  const double per_element_step = spec.solver.history == HistoryEngine::fft   ? 64.0
                                  : spec.solver.history == HistoryEngine::soe ? 0.0
                                                                               : 16.0;
  const double signals = spec.output.spectra ? static_cast<double>(spec.output.spectra->signals.size()) : 0.0;
  const double dofs = static_cast<double>(spec.structure.dofs());
  return steps * (static_cast<double>(elements) * per_element_step + 8.0 * static_cast<double>(orders) + 8.0 * signals) +
         16.0 * 8.0 * dofs * dofs + 65536.0;
}

void check_memory(const RunSpec& spec) {
  if (spec.two_block()) return;  // checked when read (io/scene.hpp)
  const auto elements = zener_elements(spec.structure).first;
  std::string what = "the " + to_string(spec.solver.history) + " history of " + std::to_string(elements) + " Zener element" +
                     (elements == 1 ? "" : "s");
  if (spec.output.spectra) what += " and the accelerations kept for output.spectra";
  const std::string problem = memory_problem(estimated_run_bytes(spec), what);
  if (problem.empty()) return;
  const std::string where = spec.file.empty() ? std::string() : spec.file.string() + ": ";
  const std::string& h_rule = spec.accuracy.h_rule;
  const std::string& t_end_rule = spec.accuracy.t_end_rule;
  const bool h_given = h_rule.empty() || h_rule == "given";
  const bool t_end_given = t_end_rule.empty() || t_end_rule == "given";
  throw InputError(where + "a run of " + shortest(static_cast<double>(spec.solver.steps())) + " steps (solver.h = " +
                   shortest(spec.solver.h) + " s" + (h_given ? "" : ", " + h_rule) + "; solver.t_end = " +
                   shortest(spec.solver.t_end) + " s" + (t_end_given ? "" : ", " + t_end_rule) + ") " + problem +
                   (h_given ? "; raise solver.h or shorten solver.t_end"
                            : "; set a coarser solver.h, loosen solver.tolerance or shorten solver.t_end"));
}

SolverSummary simulate_spec(const RunSpec& spec, const structure::Structure& s, StructureObserver& observer,
                            std::optional<Collapse>* collapse) {
  check_memory(spec);
  StructureObserverList watched;
  detail::CollapseObserver collapse_watch;  // first: the others see the state it stops at
  if (detail::CollapseObserver::watches(s)) watched.add(&collapse_watch);
  watched.add_flat(&observer);
  watched.add(spec.watch, false);  // (it refuses a run by throwing, never by done())
  // A two-block spec runs on the paper's stepper or on the structure stepper as its scheme
  // says, in the model's units (solver/simulate.hpp simulate_as_structure).
  StoppableObserverList stoppable(watched);
  StructureObserver& observers = watched.only()       ? *watched.only()
                                 : watched.may_stop() ? static_cast<StructureObserver&>(stoppable)
                                                      : watched;
  SolverSummary summary = spec.two_block() ? simulate_as_structure(two_block_options(spec), s, *spec.ground, observers)
                                           : simulate_structure(with_scheme(spec.solver, spec.solver.scheme), s, *spec.ground, observers);
  if (collapse) *collapse = collapse_watch.collapse();
  return summary;
}

// Every spec runs here: its structure through simulate_spec with one list of observers (the
// report's, then the caller's), and the report made of them.
Report run(const RunSpec& spec, const RunObservers& extra) {
  const structure::Structure& s = spec.structure;
  std::unique_ptr<ReportObservers> made;
  if (spec.two_block()) {
    check_pair_signals(spec);
    made = std::make_unique<PairReport>(spec.output);
  } else {
    made = std::make_unique<ChannelReport>(s, spec.output);
  }
  StructureObserverList all;
  made->join(all);
  all.add(extra.structure);
  Report r;
  r.solver = simulate_spec(spec, s, all, &r.collapse);
  made->fill(spec, r);
  return r;
}

}  // namespace adjoin
