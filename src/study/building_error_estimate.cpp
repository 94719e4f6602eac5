#include "adjoin/study/building_error_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/structure/channels.hpp"
#include "step_ladder.hpp"

namespace adjoin {
namespace {

constexpr int kOrder = 2;  // the building step is trapezoidal

double richardson(double fine, double coarse, double denominator) { return (fine - coarse) / denominator; }

// The Richardson estimate of `fine`'s errors from a run `c` on a grid `ratio` times coarser.
BuildingErrorEstimate compare_runs(const BuildingRunSpec& spec, const BuildingReport& fine, const BuildingReport& c, double ratio) {
  BuildingErrorEstimate e;
  e.order = kOrder;
  const double denominator = std::pow(ratio, kOrder) - 1.0;
  auto error = [&](double f, double g) { return std::abs(richardson(f, g, denominator)); };

  // Both runs observe the same structure: the same channels in the same order.
  for (std::size_t i = 0; i < fine.peaks.size() && i < c.peaks.size(); ++i) {
    const ChannelPeak& p = fine.peaks[i];
    const auto channel = structure::find_channel(spec.structure, p.channel);
    if (!channel || structure::info(channel->quantity).peak != structure::PeakRule::refined) continue;
    const Peak& q = c.peaks[i].peak;
    e.peaks.push_back({p.channel, {error(p.peak.max_abs, q.max_abs), error(p.peak.t, q.t)}});
    if (p.peak.max_abs > 0.0) {
      const double relative = e.peaks.back().error.max_abs / p.peak.max_abs;
      if (relative > e.max_relative_peak || e.worst_channel.empty()) {
        e.max_relative_peak = std::max(e.max_relative_peak, relative);
        e.worst_channel = p.channel;
      }
    }
  }
  for (std::size_t l = 0; l < fine.links.size(); ++l) {
    const LinkReport& f = fine.links[l];
    const LinkReport& g = c.links.at(l);
    LinkError le;
    le.force_max = error(f.force_max, g.force_max);
    le.stroke_max = error(f.stroke_max, g.stroke_max);
    if (spec.structure.links.at(l).type == structure::LinkType::friction) {
      le.energy = error(f.friction_energy, g.friction_energy);
      le.switches_matched = f.switch_times.size() == g.switch_times.size();
      if (le.switches_matched) {
        for (std::size_t k = 0; k < f.switch_times.size(); ++k) le.switches.push_back(error(f.switch_times[k], g.switch_times[k]));
      } else {
        le.switches_note = "the companion run found " + std::to_string(g.switch_times.size()) + " switches, this run " +
                           std::to_string(f.switch_times.size()) + "; instants not estimated";
      }
    } else {
      le.switches_matched = true;  // none to match
    }
    e.links.push_back(std::move(le));
  }
  for (std::size_t k = 0; k < fine.contacts.size(); ++k) {
    const ContactReport& f = fine.contacts[k];
    const ContactReport& g = c.contacts.at(k);
    e.contacts.push_back({error(f.min_gap, g.min_gap), error(f.t_min_gap, g.t_min_gap)});
  }
  e.available = true;
  return e;
}

// The rungs of a building scene's ladder: run_building at each step, estimate_error to decide.
class BuildingRungs final : public detail::StepLadder {
 public:
  BuildingRungs(const BuildingRunSpec& spec, double tolerance, StructureObserver* extra)
      : spec_(spec), tolerance_(tolerance), extra_(extra) {}
  void run(double h) override {
    BuildingRunSpec s = spec_;
    s.solver.h = h;
    // The fractional histories grow with the number of steps: a rung that would not fit is
    // refused by every run's rule, saying that the tolerance chose its step.
    try {
      BuildingRunSpec rung = s;
      rung.h_rule = "given";  // this rung's step is said below
      check_building_memory(rung);
    } catch (const InputError& e) {
      char chose[96];
      std::snprintf(chose, sizeof chose, "solver.tolerance = %.3g chose solver.h = %.4g s: ", tolerance_, h);
      throw InputError(chose + std::string(e.what()) + " (or loosen solver.tolerance)");
    }
    previous = std::move(current);
    // The extra observer (a streaming writer) sees every rung's run (not the companions);
    // each begin() starts a new one, and the last it sees is the run that is kept.
    current = run_building(s, extra_);
    h_ = h;
  }
  double quick_error(double ratio) override { return compare_runs(spec_, current, previous, ratio).max_relative_peak; }
  double estimate() override {
    BuildingRunSpec s = spec_;
    s.solver.h = h_;
    kept = estimate_error(s, current);
    return kept.available ? kept.max_relative_peak : INFINITY;
  }
  BuildingReport current, previous;
  BuildingErrorEstimate kept;  // the last rung's own estimate

 private:
  const BuildingRunSpec& spec_;
  double tolerance_;
  StructureObserver* extra_;
  double h_ = 0.0;
};

}  // namespace

BuildingErrorEstimate estimate_error(const BuildingRunSpec& spec, const BuildingReport& fine) {
  BuildingErrorEstimate e;
  const std::size_t n = fine.solver.steps;
  if (n < 8) {
    e.reason = "the run has fewer than 8 steps";
    return e;
  }
  const std::size_t n_coarse = n / 2;
  BuildingRunSpec coarse = spec;
  coarse.solver.h = static_cast<double>(n) * spec.solver.h / static_cast<double>(n_coarse);
  coarse.solver.t_end = static_cast<double>(n) * spec.solver.h;
  coarse.base.output.spectra.reset();  // not estimated; not needed
  // The companion integrates with the run's own scheme: at 2h the automatic rule could switch
  // the backward-Euler restart on (h omega_max > 1) where the run had it off, and Richardson
  // would then compare two methods of different order.
  if (spec.solver.restart == StructureSolverOptions::Restart::automatic)
    coarse.solver.restart = takes_restarts(spec.solver, spec.structure, *spec.base.ground)
                                ? StructureSolverOptions::Restart::always
                                : StructureSolverOptions::Restart::never;
  BuildingReport c;
  try {
    c = run_building(coarse);
  } catch (const NumericalError& failure) {
    e.reason = std::string("the companion run at h = 2h failed: ") + failure.what();
    return e;
  }
  e = compare_runs(spec, fine, c, coarse.solver.h / spec.solver.h);
  e.companion_h = coarse.solver.h;
  e.companion_wall_seconds = c.solver.wall_seconds;
  return e;
}

BuildingTolerantRun run_to_tolerance(const BuildingRunSpec& spec, double tolerance, StructureObserver* extra) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw InputError("solver.tolerance must lie in (0, 1)");
  BuildingRungs rungs(spec, tolerance, extra);
  const detail::LadderOutcome climbed = detail::climb_to_tolerance(rungs, spec.solver.h, tolerance, kOrder);
  BuildingTolerantRun out;
  out.tolerance = tolerance;
  out.report = std::move(rungs.current);
  out.estimate = std::move(rungs.kept);
  out.h = climbed.h;
  out.ladder = climbed.ladder;
  out.met = climbed.met;
  return out;
}

}  // namespace adjoin
