#pragma once
// The one time loop of the solver (internal; SPEC §4 solver/), in the style of Boost.Odeint:
// a scheme is a stepper that knows how to take one grid step, and integrate() drives any
// stepper over the grid and feeds the observer. The grid, the order of the observer's calls
// and the run's timing live here and nowhere else.
//
// Contract of a stepper S (the concept Stepper below):
//
//   - S(setup...)        is constructed from its run's inputs (options, model or structure,
//                        ground) and does all its set-up there: weights, factorisations, and
//                        the checks that refuse a run (InputError) or a step (NumericalError)
//                        before any observer call.
//   - info()             what observer.begin receives: one value, or a std::tuple of values
//                        spread into begin's arguments (a StructureObserver's begin takes two).
//   - steps()            N: the grid is t_0 = 0, t_1, ..., t_N.
//   - start()            the state at t_0, called once, after begin and before any advance.
//   - advance(n)         the step from t_n to t_{n+1}, called for n = 0, 1, ..., N-1 in order;
//                        returns the state at t_{n+1}. A state returned by start() or
//                        advance() needs to stay valid only until the next call.
//                        A non-finite or runaway value throws NumericalError (with the time)
//                        inside advance, so it never reaches an observer; the loop adds no
//                        check of its own (each scheme knows its scale and what to advise).
//   - history_bytes()    after the run: the memory its history engines held.
//   - history_error(), history_modes()  the largest relative weight error and number of
//                        recurrences of its history engines (soe; 0 for exact engines).
//   - impacts()          optional: after advance(n), the impacts to report before the state
//                        at t_{n+1} (any range of Impact): those that ended in the step and,
//                        after the last step, those still going on (complete = false).
//
// integrate<S>(observer, setup...) constructs S(setup...), then calls observer.begin(info),
// observer.observe(start()), and for each step advance(n), observer.impact(i) for each of
// its impacts, observer.observe(state) (and, for an observer with done(), stops after a state
// it is done at: CanStop below); then observer.end(). An exception from the stepper
// or an observer propagates at once: end() is not called (a run's files are then discarded
// by whoever owns them). It returns the number of steps, the wall time from before the
// stepper's construction to after end() (set-up included: it is part of a run's cost), and
// the stepper's history bytes.
//
// Why a template over the stepper and not a virtual Stepper base: a step of the two-block
// schemes costs tens of nanoseconds, so an indirect call per step would show; as a template
// the loop is compiled with each stepper's advance() in view and can inline it, and the loop
// is still written once. The observer stays a virtual interface (StructureObserver): it is
// the library's public extension point and is called once per grid point anyway. The state
// and observer types are template parameters too (any stepper and observer that fit, as the
// loop's tests use).
#include <chrono>
#include <concepts>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include "adjoin/solver/options.hpp"

namespace adjoin::detail {

template <class S>
concept Stepper = requires(S& s, const S& cs, std::size_t n) {
  s.info();
  { cs.steps() } -> std::convertible_to<std::size_t>;
  s.start();
  s.advance(n);
  requires std::same_as<std::remove_cvref_t<decltype(s.start())>, std::remove_cvref_t<decltype(s.advance(n))>>;
  { cs.history_bytes() } -> std::convertible_to<std::size_t>;
  { cs.history_error() } -> std::convertible_to<double>;
  { cs.history_modes() } -> std::convertible_to<std::size_t>;
};

// A stepper that counts the steps whose viscous dampers' passes were split (SolverSummary).
template <class S>
concept CountsSplitSteps = requires(const S& cs) {
  { cs.viscous_split_steps() } -> std::convertible_to<std::size_t>;
};

// A stepper that reports impacts (contact laws).
template <class S>
concept ReportsImpacts = requires(S& s) {
  { s.impacts() };
};

// An observer that may end the run early (StructureObserver::done): after each observe() the
// loop asks it, and on true calls end() at once; the result's steps are those taken.
template <class O>
concept CanStop = requires(const O& o) {
  { o.done() } -> std::convertible_to<bool>;
};


namespace loop_detail {
template <class T>
struct is_tuple : std::false_type {};
template <class... T>
struct is_tuple<std::tuple<T...>> : std::true_type {};

template <class Obs, class Info>
void begin(Obs& observer, Info&& info) {
  if constexpr (is_tuple<std::remove_cvref_t<Info>>::value)
    std::apply([&](auto&&... args) { observer.begin(std::forward<decltype(args)>(args)...); }, std::forward<Info>(info));
  else
    observer.begin(std::forward<Info>(info));
}
}  // namespace loop_detail

template <Stepper S, class Obs, class... Setup>
SolverSummary integrate(Obs& observer, Setup&&... setup) {
  const auto start = std::chrono::steady_clock::now();
  S stepper(std::forward<Setup>(setup)...);
  const std::size_t n_steps = stepper.steps();
  loop_detail::begin(observer, stepper.info());
  observer.observe(stepper.start());
  std::size_t taken = n_steps;
  for (std::size_t n = 0; n < n_steps; ++n) {
    const auto& state = stepper.advance(n);
    if constexpr (ReportsImpacts<S>)
      for (const auto& impact : stepper.impacts()) observer.impact(impact);
    observer.observe(state);
    if constexpr (CanStop<Obs>)
      if (observer.done()) {  // an outcome ends the run here (a collapse), not an error
        taken = n + 1;
        break;
      }
  }
  observer.end();
  SolverSummary result;  // (its names and step are the caller's)
  result.steps = taken;
  result.history_bytes = stepper.history_bytes();
  result.history_error = stepper.history_error();
  result.history_modes = stepper.history_modes();
  if constexpr (CountsSplitSteps<S>) result.viscous_split_steps = stepper.viscous_split_steps();
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace adjoin::detail
