#include "adjoin/study/run.hpp"

namespace adjoin {
namespace {

// Keeps only the last state.
class LastState final : public Observer {
 public:
  void observe(const State& s) override { last = s; }
  State last;
};

}  // namespace

RunReport run_scene(const Scene& scene, Observer* extra) {
  PeakObserver peaks;
  PhaseObserver phases;
  PoundingObserver pounding;
  EnergyObserver energy;
  LastState last;
  ObserverList observers({&peaks, &phases, &pounding, &energy, &last});
  if (extra) observers.add(extra);

  RunReport report;
  report.solver = simulate(scene.solver, scene.model, *scene.ground, observers);
  report.phases = phases.intervals();
  report.peaks = peaks.peaks();
  report.final = last.last;
  report.pounding = pounding.margin();
  report.energy = energy.balance();
  return report;
}

}  // namespace adjoin
