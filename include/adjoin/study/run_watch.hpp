#pragma once
// Long runs (building and two-block): each run's wall time estimated from its own first steps, the clearly
// unintended ones refused with the estimate, and the progress of the long ones shown.
//
// A command puts a RunWatch into RunSpec::watch (RunSpec::watch for two-block runs);
// every run made from that spec (the run, its error estimate's companion at 2h, a tolerance's rungs, a joint's bisection, a
// convergence ladder's runs) reports its steps to it. After a run's first steps (0.25 s of
// wall time, or its end) the watch estimates the run's wall time: its N steps at the cost of a
// step measured so far and, with the direct history engine, the sums that grow with the step
// number (each Zener element's or fractional rod's lag sum at step m costs m multiply-adds: the wall time after m
// steps is a m + b m^2 / 2, a and b fitted to the times of this run's steps at two step
// counts). The fft engine's sums grow as log^2 m and are left to the measured cost. Then:
//   - above `refuse_seconds` (default 2 hours: no building run a study needs is that long; a
//     step or horizon mistyped by a factor 100 is) it throws InputError with the estimate, exit
//     2, unless the command allows long runs (--allow-long, which sets refuse_seconds = 0);
//   - above `show_seconds` it calls `show` with the estimate, then with the progress (at most
//     10 times a second) and `finish` at the run's end. The command decides where (stderr on a
//     terminal, never in files, pipes or with --quiet).
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "adjoin/structure/observer.hpp"
#include "adjoin/solver/structure_solver.hpp"

namespace adjoin {

struct RunProgress {
  std::size_t run = 0;          // 1, 2, ...: the runs this watch has seen
  std::size_t done = 0, total = 0;  // steps
  double h = 0.0;               // the run's step [s, or dimensionless: h_unit]
  std::string h_unit = " s";
  double elapsed = 0.0;         // wall time since the run began [s]
  double estimate = 0.0;        // the run's estimated wall time [s]
  bool first = false;           // the first call for this run (the estimate's line)
};

// "2 h 05 min", "3 min 20 s", "12 s": a duration for messages.
std::string duration_text(double seconds);

class RunWatch final : public StructureObserver {
 public:
  struct Options {
    double refuse_seconds = 2.0 * 3600.0;  // 0: never refuse
    double show_seconds = 5.0;
    std::function<void(const RunProgress&)> show;  // null: nothing shown
    std::function<void()> finish;                   // after a run whose progress was shown
    // Two-block runs (dimensionless, their 1 + 1 structure's too): the scene's unit of time in seconds,
    // and how a step is written in messages (" s"; "" for a dimensionless scene).
    double time_scale = 1.0;
    std::string h_unit = " s";
  };
  explicit RunWatch(Options options);

  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& st) override;
  void end() override;

  // The estimate of the current run's wall time from its steps so far [s] (0 before any).
  double estimate() const;

 private:
  void start(std::size_t steps, double h_seconds, bool direct);
  void step();
  void calibrated();
  double seconds() const;

  Options options_;
  std::vector<std::pair<std::size_t, double>> marks_;  // direct engine: (steps, seconds) at powers of 2
  std::size_t run_ = 0, done_ = 0, total_ = 0, next_check_ = 0;
  bool direct_ = false, estimated_ = false, shown_ = false;
  double h_ = 0.0;
  std::chrono::steady_clock::time_point start_, last_shown_;
};

}  // namespace adjoin
