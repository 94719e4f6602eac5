#include "adjoin/study/error_estimate.hpp"

#include <algorithm>
#include <optional>
#include <cmath>

#include "adjoin/errors.hpp"
#include "adjoin/solver/simulate.hpp"

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

TolerantRun run_to_tolerance(const RunSpec& scene, double tolerance, Observer* extra) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw InputError("solver.tolerance must lie in (0, 1)");
  TolerantRun out;
  out.tolerance = tolerance;
  const double t_end = scene.solver.t_end;
  double h = t_end / 2000.0;
  const double dt = scene.ground->sample_interval();
  if (dt > 0.0) h = std::min(h, dt);
  const double memory = 0.8 * physical_memory_bytes();
  const int p = scheme_order(scene.solver.scheme);
  std::optional<RunReport> previous;  // the last rung run, and its step
  double previous_h = 0.0;
  for (int rung = 0; rung < 6; ++rung) {
    RunSpec s = scene;
    s.solver.h = h;
    if (memory > 0.0 && estimated_history_bytes(s.solver, s.model) > memory)
      throw NumericalError("solver.tolerance = " + std::to_string(tolerance) + " would need solver.h = " + std::to_string(h) +
                               " (dimensionless), whose history does not fit in memory; loosen solver.tolerance or set solver.h",
                           0.0);
    const bool last = rung == 5;
    out.ladder.push_back(h);
    // The extra observer (a streaming writer) sees every rung's run (not the companions);
    // each begin() starts a new one, and the last it sees is the run that is kept.
    RunReport r = run_scene(s, extra);
    // After the first rung, the previous rung (H = h / factor, at least 2h) is a free
    // companion: its estimate decides whether this rung can meet the tolerance and, if not,
    // the next step. Only a rung that looks good pays for the run at 2h, whose estimate is
    // the one reported (the previous rung is too coarse to be trusted for that).
    if (previous && !last) {
      ErrorEstimate quick;
      quick.order = p;
      compare_runs(r, *previous, previous_h / h, &quick);
      const double guess = quick.available ? quick.max_relative_peak : INFINITY;
      if (std::isfinite(guess) && guess > 2.0 * tolerance) {
        const double factor = guess > 0.0 ? std::pow(0.7 * tolerance / guess, 1.0 / p) : 0.5;
        previous = std::move(r);
        previous_h = h;
        h *= std::clamp(factor, 1.0 / 16.0, 0.5);
        continue;
      }
    }
    ErrorEstimate e = estimate_error(s, r);
    const double achieved = e.available ? e.max_relative_peak : INFINITY;
    if (achieved <= tolerance || last) {
      out.report = std::move(r);
      out.estimate = std::move(e);
      out.h = h;
      out.met = achieved <= tolerance;
      return out;
    }
    // The step the tolerance asks for, by the observed error and the order; at most 16x finer
    // per rung, and a failed estimate halves the step.
    const double factor = std::isfinite(achieved) && achieved > 0.0 ? std::pow(0.7 * tolerance / achieved, 1.0 / p) : 0.5;
    previous = std::move(r);
    previous_h = h;
    h *= std::clamp(factor, 1.0 / 16.0, 0.5);
  }
  return out;  // not reached
}

}  // namespace adjoin
