#include "adjoin/study/run.hpp"

#include <memory>

namespace adjoin {
namespace {

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

std::vector<SignalSpectrum> spectra_of(const RunSpec& scene, const AccelerationRecorder& recorded) {
  const SpectraOutput& asked = *scene.output.spectra;
  const Scales& k = scene.scales;
  SpectrumOptions options;
  options.dampings = asked.damping;
  // Periods are in the scene's time unit already, as is the step below.
  options.periods = asked.periods.empty() ? default_spectrum_periods() : asked.periods;
  // The library works in m/s^2 and s; dimensionless accelerations are in g. For a
  // dimensionless scene, lengths come out multiplied by g and are divided back below.
  const double dt = scene.solver.h * k.time;
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

}  // namespace

RunReport run_scene(const RunSpec& scene, Observer* extra) {
  const OutputOptions& asked = scene.output;
  PeakObserver peaks;
  PhaseObserver phases;
  PoundingObserver pounding;
  EnergyObserver energy;
  LastState last;
  std::unique_ptr<AccelerationRecorder> accelerations;
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
  if (extra) observers.add(extra);
  if (scene.watch) observers.add(scene.watch);  // (it may stop the run: a refusal)

  RunReport report;
  report.solver = simulate(scene.solver, scene.model, *scene.ground, observers);
  report.final = last.last;
  if (asked.phases) report.phases = phases.intervals();
  if (asked.peaks) report.peaks = peaks.peaks();
  if (asked.pounding) report.pounding = pounding.margin();
  if (pounding.margin().outside_model()) report.outside_model_from = pounding.margin().t_first_contact;
  if (asked.energy) report.energy = energy.balance();
  if (accelerations) report.spectra = spectra_of(scene, *accelerations);
  return report;
}

}  // namespace adjoin
