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

structure::Structure solver_structure(const RunSpec& spec) {
  return spec.model ? structure::two_block_structure(*spec.model) : spec.structure;
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
  if (two_block) return two_block->outside_model_from.value_or(std::numeric_limits<double>::quiet_NaN());
  double t = std::numeric_limits<double>::quiet_NaN();
  for (const auto& c : contacts)
    if (c.outside_model() && !(t <= c.unmodelled_from)) t = c.unmodelled_from;
  return t;
}

namespace {

// ---- two-block specs ----

// Keeps only the last state.
class LastState final : public Observer {
 public:
  void observe(const State& s) override { last = s; }
  State last;
};

// Keeps the acceleration histories that spectra need (only when spectra are asked for).
class AccelerationRecorder final : public Observer {
 public:
  void begin(const RunInfo& info) override {
    for (auto* v : {&ag, &a1, &a2}) { v->clear(); v->reserve(info.steps + 1); }
  }
  void observe(const State& s) override {
    ag.push_back(s.ag);
    a1.push_back(s.a1);
    a2.push_back(s.a2);
  }
  std::vector<double> ag, a1, a2;
};

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
    const std::vector<double>& a = signal == "ground" ? recorded.ag : (signal == "block1" ? recorded.a1 : recorded.a2);
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

// A two-block State as the 1 + 1 structure's StructureState (dimensionless), for the
// structure observers of a two-block run.
class AsStructure final : public Observer {
 public:
  AsStructure(StructureObserver& inner, const RunSpec& spec) : inner_(inner), structure_(solver_structure(spec)), options_(spec.solver) {
    const bool link = !structure_.links.empty(), contact = !structure_.contacts.empty();
    for (auto* v : {&state_.x, &state_.v, &state_.a_abs, &state_.storey_force}) v->setZero(2);
    // (after the link, the base friction's two sliders, model.base_friction > 0: SPEC §7)
    sliders_ = structure_.ground_sliders().size();
    const Eigen::Index n_links = (link ? 1 : 0) + static_cast<Eigen::Index>(sliders_);
    for (auto* v : {&state_.link_force, &state_.link_stroke, &state_.link_velocity}) v->setZero(n_links);
    state_.link_phase.assign(static_cast<std::size_t>(n_links), Phase::stick);
    state_.link_switch.assign(static_cast<std::size_t>(n_links), 0.0);
    for (auto* v : {&state_.contact_gap, &state_.contact_force, &state_.contact_work, &state_.contact_dissipated})
      v->setZero(contact ? 1 : 0);
    gap0_ = spec.model->gap0;
  }
  void begin(const RunInfo&) override { inner_.begin(structure_, options_); }
  void observe(const State& s) override {
    StructureState& o = state_;
    o.t = s.t;
    o.ag = s.ag;
    o.x << s.x1, s.x2;
    o.v << s.v1, s.v2;
    o.a_abs << s.a1, s.a2;
    o.storey_force << s.f1, s.f2;
    if (sliders_ == 2) {  // the blocks' base friction: force, the block's motion, its phase
      const Eigen::Index k = o.link_force.size() - 2;
      const double q[2] = {s.qb1, s.qb2}, x[2] = {s.x1, s.x2}, v[2] = {s.v1, s.v2};
      for (Eigen::Index i = 0; i < 2; ++i) {
        o.link_force[k + i] = q[i];
        o.link_stroke[k + i] = x[i];
        o.link_velocity[k + i] = v[i];
        o.link_phase[static_cast<std::size_t>(k + i)] = v[i] > 0.0 ? Phase::slip_right : (v[i] < 0.0 ? Phase::slip_left : Phase::stick);
      }
    }
    if (o.link_force.size() - static_cast<Eigen::Index>(sliders_) == 1) {
      o.link_force[0] = s.q;
      o.link_stroke[0] = s.x1 - s.x2;
      o.link_velocity[0] = s.v1 - s.v2;
      o.link_phase[0] = s.phase;
      o.link_switch[0] = s.t_switch;
    }
    if (o.contact_gap.size() == 1) {
      o.contact_gap[0] = gap0_ + s.x2 - s.x1;
      o.contact_force[0] = s.fc;
      o.contact_work[0] = s.contact_work;
      o.contact_dissipated[0] = s.contact_dissipated;
    }
    inner_.observe(o);
  }
  void impact(const Impact& i) override { inner_.impact(i); }
  void end() override { inner_.end(); }

 private:
  StructureObserver& inner_;
  structure::Structure structure_;
  StructureSolverOptions options_;
  StructureState state_;
  double gap0_ = 0.0;
  std::size_t sliders_ = 0;  // the base friction's sliders (0 or 2)
};

Report run_two_block(const RunSpec& spec, const RunObservers& extra) {
  const OutputOptions& asked = spec.output;
  PeakObserver peaks;
  PhaseObserver phases;
  PoundingObserver pounding;
  EnergyObserver energy;
  LastState last;
  std::unique_ptr<AccelerationRecorder> accelerations;
  std::unique_ptr<AsStructure> structure_extra;
  ObserverList observers({&last});
  if (asked.peaks) observers.add(&peaks);
  if (asked.phases) observers.add(&phases);
  // Always watched (it costs a few operations a step): a run without a contact law whose gap
  // closes is flagged even when the pounding margin is not reported.
  observers.add(&pounding);
  if (asked.energy) observers.add(&energy);
  if (asked.spectra) {
    accelerations = std::make_unique<AccelerationRecorder>();
    observers.add(accelerations.get());
  }
  if (extra.two_block) observers.add(extra.two_block);
  if (extra.structure) {
    structure_extra = std::make_unique<AsStructure>(*extra.structure, spec);
    observers.add(structure_extra.get());
  }
  if (spec.watch) observers.add(spec.watch);  // (it may stop the run: a refusal)

  Report report;
  report.solver = simulate(two_block_options(spec), *spec.model, *spec.ground, observers);
  TwoBlockReport& r = report.two_block.emplace();
  r.final = last.last;
  if (asked.phases) r.phases = phases.intervals();
  if (asked.peaks) r.peaks = peaks.peaks();
  if (asked.pounding) r.pounding = pounding.margin();
  if (pounding.margin().outside_model()) r.outside_model_from = pounding.margin().t_first_contact;
  if (asked.energy) r.energy = energy.balance();
  if (accelerations) report.spectra = spectra_of(spec, *accelerations);
  return report;
}

// ---- buildings ----

// Fans every call out to a list of structure observers (not owned), in order.
class StructureObserverList final : public StructureObserver {
 public:
  void add(StructureObserver* o) { if (o) observers_.push_back(o); }
  // A list's observers join this one in their order (one virtual call per observer and step,
  // not two); any other observer is added.
  void add_flat(StructureObserver* o) {
    if (const auto* list = dynamic_cast<const StructureObserverList*>(o))
      for (StructureObserver* x : list->observers_) add(x);
    else
      add(o);
  }
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override { for (auto* x : observers_) x->begin(s, o); }
  void observe(const StructureState& st) override { for (auto* x : observers_) x->observe(st); }
  void impact(const Impact& e) override { for (auto* x : observers_) x->impact(e); }
  void end() override { for (auto* x : observers_) x->end(); }
  bool done() const override {
    return std::any_of(observers_.begin(), observers_.end(), [](const StructureObserver* x) { return x->done(); });
  }

 private:
  std::vector<StructureObserver*> observers_;
};

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

Report run_building(const RunSpec& spec, const RunObservers& extra) {
  Report r;
  const structure::Structure& s = spec.structure;
  r.modes.push_back(structure::building_modes(s.a));
  if (s.b) {
    r.modes.push_back(structure::building_modes(*s.b));
    r.coupled = structure::coupled_modes(s);
  }
  detail::ChannelObserver observer(s);
  detail::YieldObserver yielding(s);
  const auto& asked = spec.output.spectra;
  std::unique_ptr<detail::SignalRecorder> recorder;
  if (asked) recorder = std::make_unique<detail::SignalRecorder>(s, asked->signals);
  StructureObserverList all;
  all.add(&observer);
  if (yielding.watches()) all.add(&yielding);  // (its report is empty otherwise)
  all.add(recorder.get());
  all.add(extra.structure);
  r.solver = simulate_spec(spec, s, all, &r.collapse);
  if (recorder) {
    SpectrumOptions options;
    options.dampings = asked->damping;
    options.periods = asked->periods.empty() ? default_spectrum_periods() : asked->periods;
    for (std::size_t k = 0; k < asked->signals.size(); ++k)
      r.spectra.push_back({asked->signals[k], response_spectrum(spec.solver.h, recorder->histories[k], options)});
  }
  r.peaks = observer.peaks();
  r.links = observer.links();
  r.contacts = observer.contacts();
  r.energy = observer.energy();
  r.residual = observer.residual();
  r.bases = observer.bases();
  r.yield = yielding.report();
  for (const BuildingYield& y : r.yield)
    for (const StoreyYield& st : y.storeys) r.energy.buildings[y.building == 'A' ? 0 : 1].hysteretic.push_back(st.plastic_work);
  return r;
}

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
  watched.add(spec.watch);
  const StructureSolverOptions options = with_scheme(spec.solver, spec.solver.scheme);
  SolverSummary summary = simulate_structure(options, s, *spec.ground, watched);
  if (collapse) *collapse = collapse_watch.collapse();
  return summary;
}

Report run(const RunSpec& spec, const RunObservers& extra) {
  return spec.two_block() ? run_two_block(spec, extra) : run_building(spec, extra);
}

}  // namespace adjoin
