// The one time loop (src/solver/time_loop.hpp) with trivial steppers whose exact solution is
// known: the grid, the order of the observer's calls, impacts before their step's state, an
// exception stopping the run before the bad state is observed, and the loop's result.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "../src/solver/time_loop.hpp"
#include "adjoin/structure/state.hpp"

namespace {

using adjoin::Impact;

// What the trivial steppers below tell begin() and report at each grid point.
struct Info {
  double h = 0.0;
  std::size_t steps = 0;
};
struct Point {
  double t = 0.0, x = 0.0, v = 0.0;
};

// x' = -x from x(0) = 1, stepped exactly (x_{n+1} = x_n e^{-h}), and v = x' = -x; at the
// step named `impact_step` it reports an impact, and at `throw_step` it fails as a scheme
// does on a runaway value (before returning the state).
class Decay {
 public:
  Decay(double h, std::size_t steps, int* constructed, std::size_t impact_step = 0, std::size_t throw_step = 0)
      : h_(h), steps_(steps), impact_step_(impact_step), throw_step_(throw_step) {
    ++*constructed;
  }
  Info info() const {
    Info i;
    i.h = h_;
    i.steps = steps_;
    return i;
  }
  std::size_t steps() const { return steps_; }
  std::size_t history_bytes() const { return 1234; }
  double history_error() const { return 0.5; }
  std::size_t history_modes() const { return 7; }
  const Point& start() {
    ++starts;
    state_.t = 0.0;
    state_.x = 1.0;
    state_.v = -1.0;
    return state_;
  }
  const Point& advance(std::size_t n) {
    if (n + 1 != next_) throw std::logic_error("advance out of order");
    ++next_;
    if (throw_step_ != 0 && n + 1 == throw_step_) throw std::runtime_error("runaway");
    impacts_.clear();
    if (impact_step_ != 0 && n + 1 == impact_step_) {
      Impact i;
      i.start = static_cast<double>(n) * h_;
      impacts_.push_back(i);
    }
    state_.t = static_cast<double>(n + 1) * h_;
    state_.x *= std::exp(-h_);
    state_.v = -state_.x;
    return state_;
  }
  const std::vector<Impact>& impacts() const { return impacts_; }
  int starts = 0;

 private:
  double h_;
  std::size_t steps_, impact_step_, throw_step_;
  std::size_t next_ = 1;
  Point state_;
  std::vector<Impact> impacts_;
};

// Records every call as a letter (b, o, i, e) and the observed states.
class Recorder final {
 public:
  void begin(const Info& info) {
    calls += 'b';
    h = info.h;
    steps = info.steps;
  }
  void observe(const Point& s) {
    calls += 'o';
    states.push_back(s);
  }
  void impact(const Impact& i) {
    calls += 'i';
    impact_starts.push_back(i.start);
  }
  void end() { calls += 'e'; }
  std::string calls;
  double h = 0.0;
  std::size_t steps = 0;
  std::vector<Point> states;
  std::vector<double> impact_starts;
};

}  // namespace

TEST_CASE("time loop: every grid point observed once in order, between begin and end, on the exact decay") {
  const double h = 0.01;
  const std::size_t n = 250;
  int constructed = 0;
  Recorder r;
  const auto before = std::chrono::steady_clock::now();
  const auto result = adjoin::detail::integrate<Decay>(r, h, n, &constructed);
  const double outside = std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
  CHECK(constructed == 1);
  CHECK(r.h == h);
  CHECK(r.steps == n);
  REQUIRE(r.states.size() == n + 1);
  CHECK(r.calls == "b" + std::string(n + 1, 'o') + "e");
  for (std::size_t m = 0; m <= n; ++m) {
    CHECK(r.states[m].t == static_cast<double>(m) * h);
    // n multiplications by e^{-h}: the exact solution to a few ulps per step.
    CHECK(r.states[m].x == Approx(std::exp(-static_cast<double>(m) * h)).epsilon(1e-13));
  }
  CHECK(r.states.back().x == Approx(std::exp(-2.5)).epsilon(1e-13));
  CHECK(result.steps == n);
  CHECK(result.history_bytes == 1234);
  CHECK(result.history_error == 0.5);  // the stepper's own, passed through
  CHECK(result.history_modes == 7);
  // The loop's own clock: some time passed, and no more than the whole call took.
  CHECK(result.wall_seconds > 0.0);
  CHECK(result.wall_seconds <= outside);
}

TEST_CASE("time loop: an impact is reported after the previous state and before its step's state") {
  Recorder r;
  int constructed = 0;
  adjoin::detail::integrate<Decay>(r, 0.5, std::size_t{4}, &constructed, std::size_t{3});
  // t_0, t_1, t_2 observed; the impact of the step t_2 -> t_3; then t_3, t_4.
  CHECK(r.calls == "boooiooe");
  REQUIRE(r.impact_starts.size() == 1);
  CHECK(r.impact_starts[0] == 1.0);
  CHECK(r.states[3].t == 1.5);
}

TEST_CASE("time loop: an exception in a step stops the run before that state, without end") {
  Recorder r;
  int constructed = 0;
  CHECK_THROWS_WITH(adjoin::detail::integrate<Decay>(r, 0.1, std::size_t{10}, &constructed, std::size_t{0},
                                                     std::size_t{6}),
                    "runaway");
  // t_0 .. t_5 observed, t_6 not, and no end().
  CHECK(r.calls == "b" + std::string(6, 'o'));
  CHECK(r.states.back().t == Approx(0.5).epsilon(1e-15));
}

namespace {

// A stepper whose observer's begin takes two arguments (as a StructureObserver's does): its
// info() is a tuple, spread into them. No impacts() member: none are reported.
struct Counter {
  explicit Counter(std::size_t steps) : steps_(steps) {}
  std::tuple<int, double> info() const { return {7, 0.25}; }
  std::size_t steps() const { return steps_; }
  std::size_t history_bytes() const { return 0; }
  double history_error() const { return 0.0; }
  std::size_t history_modes() const { return 0; }
  const int& start() { return value_; }
  const int& advance(std::size_t n) {
    value_ = static_cast<int>(n + 1) * 2;
    return value_;
  }
  std::size_t steps_;
  int value_ = 0;
};

struct TwoArgumentObserver {
  void begin(int a, double b) { begun = a + b; }
  void observe(int v) { seen.push_back(v); }
  void end() { ended = true; }
  double begun = 0.0;
  std::vector<int> seen;
  bool ended = false;
};

}  // namespace

TEST_CASE("time loop: a tuple info is spread into begin, and any state and observer type is driven") {
  static_assert(adjoin::detail::Stepper<Counter>);
  static_assert(!adjoin::detail::ReportsImpacts<Counter>);
  static_assert(adjoin::detail::ReportsImpacts<Decay>);
  TwoArgumentObserver o;
  const auto result = adjoin::detail::integrate<Counter>(o, std::size_t{3});
  CHECK(o.begun == 7.25);
  CHECK(o.seen == std::vector<int>{0, 2, 4, 6});
  CHECK(o.ended);
  CHECK(result.steps == 3);
}
