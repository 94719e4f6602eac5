#include "adjoin/study/error_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "adjoin/core/errors.hpp"
#include "adjoin/solver/simulate.hpp"
#include "step_ladder.hpp"

namespace adjoin {
namespace {

double richardson(double fine, double coarse, double denominator) { return (fine - coarse) / denominator; }

PeakError peak_error(const Peak& fine, const Peak& coarse, double denominator) {
  return {std::abs(richardson(fine.max_abs, coarse.max_abs, denominator)), std::abs(richardson(fine.t, coarse.t, denominator))};
}

// The Richardson estimate of `fine`'s errors from a run `c` on a grid `ratio` times coarser.
void compare_runs(const RunReport& fine, const RunReport& c, double ratio, ErrorEstimate* e) {
  const double denominator = std::pow(ratio, e->order) - 1.0;

  const Peaks& pf = fine.peaks;
  const Peaks& pc = c.peaks;
  e->x1 = peak_error(pf.x1, pc.x1, denominator);
  e->x2 = peak_error(pf.x2, pc.x2, denominator);
  e->drift = peak_error(pf.drift, pc.drift, denominator);
  e->f1 = peak_error(pf.f1, pc.f1, denominator);
  e->f2 = peak_error(pf.f2, pc.f2, denominator);
  e->q = peak_error(pf.q, pc.q, denominator);
  const std::pair<const Peak*, const PeakError*> peaks[] = {{&pf.x1, &e->x1}, {&pf.x2, &e->x2}, {&pf.drift, &e->drift},
                                                            {&pf.f1, &e->f1}, {&pf.f2, &e->f2}, {&pf.q, &e->q}};
  for (const auto& [value, error] : peaks)
    if (value->max_abs > 0.0) e->max_relative_peak = std::max(e->max_relative_peak, error->max_abs / value->max_abs);
  if (fine.pounding && c.pounding) {
    e->min_gap = std::abs(richardson(fine.pounding->min_gap, c.pounding->min_gap, denominator));
    e->t_min_gap = std::abs(richardson(fine.pounding->t_min_gap, c.pounding->t_min_gap, denominator));
  }
  if (fine.energy && c.energy) e->friction = std::abs(richardson(fine.energy->friction, c.energy->friction, denominator));
  e->switches_matched = fine.phases.size() == c.phases.size();
  for (std::size_t i = 0; e->switches_matched && i < fine.phases.size(); ++i)
    e->switches_matched = fine.phases[i].state == c.phases[i].state;
  if (e->switches_matched)
    for (std::size_t i = 1; i < fine.phases.size(); ++i)
      e->switches.push_back(std::abs(richardson(fine.phases[i].t_start, c.phases[i].t_start, denominator)));
  e->available = true;
}

}  // namespace

ErrorEstimate estimate_error(const RunSpec& scene, const RunReport& fine) {
  ErrorEstimate e;
  e.order = scheme_order(scene.solver.scheme);
  const std::size_t n = fine.solver.steps;
  if (n < 8) {
    e.reason = "the run has fewer than 8 steps";
    return e;
  }
  const std::size_t n_coarse = n / 2;
  RunSpec coarse = scene;
  coarse.solver.h = static_cast<double>(n) * fine.solver.h / static_cast<double>(n_coarse);
  coarse.solver.t_end = static_cast<double>(n) * fine.solver.h;
  coarse.output.spectra.reset();  // not estimated; not needed
  e.companion_h = coarse.solver.h;
  RunReport c;
  try {
    c = run_scene(coarse);
  } catch (const NumericalError& failure) {
    e.reason = std::string("the companion run at h = 2h failed: ") + failure.what();
    return e;
  }
  e.companion_wall_seconds = c.solver.wall_seconds;
  compare_runs(fine, c, coarse.solver.h / fine.solver.h, &e);
  return e;
}

namespace {

// The rungs of a two-block scene's ladder: run_scene at each step, estimate_error to decide.
class TwoBlockRungs final : public detail::StepLadder {
 public:
  TwoBlockRungs(const RunSpec& scene, double tolerance, Observer* extra) : scene_(scene), tolerance_(tolerance), extra_(extra) {}
  void run(double h) override {
    RunSpec s = scene_;
    s.solver.h = h;
    if (memory_ > 0.0 && estimated_history_bytes(s.solver, s.model) > memory_)
      throw NumericalError("solver.tolerance = " + std::to_string(tolerance_) + " would need solver.h = " + std::to_string(h) +
                               " (dimensionless), whose history does not fit in memory; loosen solver.tolerance or set solver.h",
                           0.0);
    previous = std::move(current);
    // The extra observer (a streaming writer) sees every rung's run (not the companions);
    // each begin() starts a new one, and the last it sees is the run that is kept.
    current = run_scene(s, extra_);
    h_ = h;
  }
  double quick_error(double ratio) override {
    ErrorEstimate quick;
    quick.order = scheme_order(scene_.solver.scheme);
    compare_runs(current, previous, ratio, &quick);
    return quick.max_relative_peak;
  }
  double estimate() override {
    RunSpec s = scene_;
    s.solver.h = h_;
    kept = estimate_error(s, current);
    return kept.available ? kept.max_relative_peak : INFINITY;
  }
  RunReport current, previous;
  ErrorEstimate kept;  // the last rung's own estimate

 private:
  const RunSpec& scene_;
  double tolerance_;
  Observer* extra_;
  double memory_ = 0.8 * physical_memory_bytes();
  double h_ = 0.0;
};

}  // namespace

TolerantRun run_to_tolerance(const RunSpec& scene, double tolerance, Observer* extra) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw InputError("solver.tolerance must lie in (0, 1)");
  double h0 = scene.solver.t_end / 2000.0;
  const double dt = scene.ground->sample_interval();
  if (dt > 0.0) h0 = std::min(h0, dt);
  TwoBlockRungs rungs(scene, tolerance, extra);
  const detail::LadderOutcome climbed = detail::climb_to_tolerance(rungs, h0, tolerance, scheme_order(scene.solver.scheme));
  TolerantRun out;
  out.tolerance = tolerance;
  out.report = std::move(rungs.current);
  out.estimate = std::move(rungs.kept);
  out.h = climbed.h;
  out.ladder = climbed.ladder;
  out.met = climbed.met;
  return out;
}

}  // namespace adjoin
