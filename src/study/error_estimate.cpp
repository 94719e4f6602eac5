#include "adjoin/study/error_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "step_ladder.hpp"

namespace adjoin {
namespace {

double richardson(double fine, double coarse, double denominator) { return (fine - coarse) / denominator; }

PeakError peak_error(const Peak& fine, const Peak& coarse, double denominator) {
  return {std::abs(richardson(fine.max_abs, coarse.max_abs, denominator)), std::abs(richardson(fine.t, coarse.t, denominator))};
}

// The estimate of a refined peak, and the largest relative one so far.
void add_peak(const std::string& channel, const Peak& fine, const Peak& coarse, double denominator, ErrorEstimate* e) {
  e->peaks.push_back({channel, peak_error(fine, coarse, denominator)});
  if (fine.max_abs > 0.0) {
    const double relative = e->peaks.back().error.max_abs / fine.max_abs;
    if (relative > e->max_relative_peak || e->worst_channel.empty()) {
      e->max_relative_peak = std::max(e->max_relative_peak, relative);
      e->worst_channel = channel;
    }
  }
}

// A building's values: the refined channel peaks, the links, the contact pairs.
void compare_channels(const RunSpec& spec, const Report& fine, const Report& c, double denominator, ErrorEstimate* e) {
  auto error = [&](double f, double g) { return std::abs(richardson(f, g, denominator)); };
  // Both runs observe the same structure: the same channels in the same order.
  for (std::size_t i = 0; i < fine.peaks.size() && i < c.peaks.size(); ++i) {
    const ChannelPeak& p = fine.peaks[i];
    const auto channel = structure::find_channel(spec.structure, p.channel);
    if (!channel || structure::info(channel->quantity).peak != structure::PeakRule::refined) continue;
    add_peak(p.channel, p.peak, c.peaks[i].peak, denominator, e);
  }
  for (std::size_t l = 0; l < fine.links.size(); ++l) {
    const LinkReport& f = fine.links[l];
    const LinkReport& g = c.links.at(l);
    LinkError le;
    le.force_max = error(f.force_max, g.force_max);
    le.stroke_max = error(f.stroke_max, g.stroke_max);
    if (structure::kind_of(spec.structure.links.at(l)).family(spec.structure.links.at(l)) == structure::LinkFamily::friction) {
      le.energy = error(f.energy, g.energy);
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
    e->links.push_back(std::move(le));
  }
  for (std::size_t k = 0; k < fine.contacts.size(); ++k) {
    const ContactReport& f = fine.contacts[k];
    const ContactReport& g = c.contacts.at(k);
    e->contacts.push_back({error(f.min_gap, g.min_gap), error(f.t_min_gap, g.t_min_gap)});
  }
  if (fine.collapse && c.collapse && fine.collapse->building == c.collapse->building && fine.collapse->storey == c.collapse->storey)
    e->collapse_t = error(fine.collapse->t, c.collapse->t);
}

// A two-block spec's values: its 1 + 1 structure's refined peaks (the floors, the link's
// stroke, the storeys' forces, the link force), the contact pair's smallest gap, the friction
// link's work, the switching instants.
void compare_two_block(const RunSpec& spec, const Report& fine, const Report& c, double denominator, ErrorEstimate* e) {
  for (const char* channel : {"A.x1", "B.x1", "link1.stroke", "A.shear1", "B.shear1", "link1.force"})
    add_peak(channel, fine.peak(channel), c.peak(channel), denominator, e);
  if (spec.output.pounding) {
    e->min_gap = std::abs(richardson(fine.contacts.at(0).min_gap, c.contacts.at(0).min_gap, denominator));
    e->t_min_gap = std::abs(richardson(fine.contacts.at(0).t_min_gap, c.contacts.at(0).t_min_gap, denominator));
  }
  if (spec.output.energy) e->friction = std::abs(richardson(fine.link_energy(0), c.link_energy(0), denominator));
  e->switches_matched = fine.phases.size() == c.phases.size();
  for (std::size_t i = 0; e->switches_matched && i < fine.phases.size(); ++i)
    e->switches_matched = fine.phases[i].state == c.phases[i].state;
  if (e->switches_matched)
    for (std::size_t i = 1; i < fine.phases.size(); ++i)
      e->switches.push_back(std::abs(richardson(fine.phases[i].t_start, c.phases[i].t_start, denominator)));
}

// The Richardson estimate of `fine`'s errors from a run `c` on a grid `ratio` times coarser.
ErrorEstimate compare_runs(const RunSpec& spec, const Report& fine, const Report& c, double ratio) {
  ErrorEstimate e;
  e.order = scheme_order(spec.solver.scheme);
  const double denominator = std::pow(ratio, e.order) - 1.0;
  if (spec.two_block()) compare_two_block(spec, fine, c, denominator, &e);
  else compare_channels(spec, fine, c, denominator, &e);
  e.available = true;
  return e;
}

// The companion's spec: the same horizon on about half the steps, with the run's own scheme.
RunSpec companion_of(const RunSpec& spec, std::size_t n) {
  const std::size_t n_coarse = n / 2;
  RunSpec coarse = spec;
  coarse.solver.h = static_cast<double>(n) * spec.solver.h / static_cast<double>(n_coarse);
  coarse.solver.t_end = static_cast<double>(n) * spec.solver.h;
  coarse.output.spectra.reset();  // not estimated; not needed
  if (!spec.two_block() && spec.solver.restart == StructureSolverOptions::Restart::automatic)
    coarse.solver.restart = takes_restarts(spec.solver, spec.structure, *spec.ground) ? StructureSolverOptions::Restart::always
                                                                                     : StructureSolverOptions::Restart::never;
  return coarse;
}

// A rung that would not fit in memory is refused, saying that the tolerance chose its step: a
// building's by every run's rule (InputError), a two-block spec's history by the solver's
// estimate (NumericalError, as when it was read).
void check_rung_memory(const RunSpec& rung, double tolerance) {
  if (rung.two_block()) {
    const double memory = 0.8 * physical_memory_bytes();
    if (memory > 0.0 && estimated_history_bytes(two_block_options(rung), rung.structure) > memory)
      throw NumericalError("solver.tolerance = " + std::to_string(tolerance) + " would need solver.h = " +
                               std::to_string(rung.solver.h) +
                               " (dimensionless), whose history does not fit in memory; loosen solver.tolerance or set solver.h",
                           0.0);
    return;
  }
  try {
    RunSpec given = rung;
    given.accuracy.h_rule = "given";  // this rung's step is said below
    check_memory(given);
  } catch (const InputError& e) {
    char chose[96];
    std::snprintf(chose, sizeof chose, "solver.tolerance = %.3g chose solver.h = %.4g s: ", tolerance, rung.solver.h);
    throw InputError(chose + std::string(e.what()) + " (or loosen solver.tolerance)");
  }
}

// The rungs of a ladder: run() at each step, estimate_error to decide.
class Rungs final : public detail::StepLadder {
 public:
  Rungs(const RunSpec& spec, double tolerance, const RunObservers& extra) : spec_(spec), tolerance_(tolerance), extra_(extra) {}
  void run(double h) override {
    RunSpec s = spec_;
    s.solver.h = h;
    check_rung_memory(s, tolerance_);
    previous = std::move(current);
    // The extra observer (a streaming writer) sees every rung's run (not the companions);
    // each begin() starts a new one, and the last it sees is the run that is kept.
    current = adjoin::run(s, extra_);
    h_ = h;
  }
  double quick_error(double ratio) override { return compare_runs(spec_, current, previous, ratio).max_relative_peak; }
  double estimate() override {
    RunSpec s = spec_;
    s.solver.h = h_;
    kept = estimate_error(s, current);
    return kept.available ? kept.max_relative_peak : INFINITY;
  }
  Report current, previous;
  ErrorEstimate kept;  // the last rung's own estimate

 private:
  const RunSpec& spec_;
  double tolerance_;
  RunObservers extra_;
  double h_ = 0.0;
};

}  // namespace

ErrorEstimate estimate_error(const RunSpec& spec, const Report& fine) {
  ErrorEstimate e;
  e.order = scheme_order(spec.solver.scheme);
  // (A run that collapsed stopped early: its companion keeps the whole horizon, to collapse too.)
  const std::size_t n = fine.collapse ? spec.solver.steps() : fine.solver.steps;
  if (n < 8) {
    e.reason = "the run has fewer than 8 steps";
    return e;
  }
  const RunSpec coarse = companion_of(spec, n);
  e.companion_h = coarse.solver.h;
  Report c;
  try {
    c = run(coarse);
  } catch (const NumericalError& failure) {
    e.reason = std::string("the companion run at h = 2h failed: ") + failure.what();
    return e;
  }
  e = compare_runs(spec, fine, c, coarse.solver.h / spec.solver.h);
  e.companion_h = coarse.solver.h;
  e.companion_wall_seconds = c.solver.wall_seconds;
  return e;
}

TolerantRun run_to_tolerance(const RunSpec& spec, double tolerance, const RunObservers& extra) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw InputError("solver.tolerance must lie in (0, 1)");
  double h0 = spec.solver.h;
  if (spec.two_block()) {
    h0 = spec.solver.t_end / 2000.0;
    if (const double dt = spec.ground->sample_interval(); dt > 0.0) h0 = std::min(h0, dt);
  }
  Rungs rungs(spec, tolerance, extra);
  const detail::LadderOutcome climbed = detail::climb_to_tolerance(rungs, h0, tolerance, scheme_order(spec.solver.scheme));
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
