#pragma once
// Observers receive the solution as the solver produces it, one grid point at a time, so a
// long run need not keep its whole history: each observer keeps only what it reports.
//
// Call order: begin(info) once, observe(state) for t_0 = 0, t_1, ..., t_N in order, then
// end() once. Two interfaces: Observer for the two-block solver (solver/simulate.hpp), in its
// dimensionless units; StructureObserver for the structure solver
// (solver/structure_solver.hpp), in SI units.
#include <cstddef>
#include <vector>

#include "adjoin/core/history_engine.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/structure/parameters.hpp"
#include "adjoin/structure/state.hpp"

namespace adjoin {

struct StructureSolverOptions;  // solver/structure_solver.hpp: what begin() is told of the run

struct RunInfo {
  Model model;
  double h = 0.0;
  std::size_t steps = 0;  // N: grid points t_0..t_N are observed
  HistoryEngine history = HistoryEngine::soe;  // the rods' history sums (a run's cost grows as N^2 with direct)
};

class Observer {
 public:
  virtual ~Observer() = default;
  virtual void begin(const RunInfo& /*info*/) {}
  virtual void observe(const State& state) = 0;
  // An impact that ended in the step ending at the next observe() (called before it), or
  // that is still going on at the end of the run (complete = false, before the last observe).
  virtual void impact(const Impact& /*impact*/) {}
  virtual void end() {}
};

// Fans every call out to a list of observers (not owned), in order.
class ObserverList final : public Observer {
 public:
  ObserverList() = default;
  explicit ObserverList(std::vector<Observer*> observers) : observers_(std::move(observers)) {}
  void add(Observer* observer) { observers_.push_back(observer); }
  void begin(const RunInfo& info) override { for (auto* o : observers_) o->begin(info); }
  void observe(const State& state) override { for (auto* o : observers_) o->observe(state); }
  void impact(const Impact& i) override { for (auto* o : observers_) o->impact(i); }
  void end() override { for (auto* o : observers_) o->end(); }

 private:
  std::vector<Observer*> observers_;
};

class StructureObserver {
 public:
  virtual ~StructureObserver() = default;
  virtual void begin(const structure::Structure&, const StructureSolverOptions&) {}
  virtual void observe(const StructureState& state) = 0;
  // An impact that ended in the step ending at the next observe() (called before it), or
  // that is still going on at the end of the run (complete = false, before the last observe).
  virtual void impact(const Impact& /*impact*/) {}
  virtual void end() {}
  // True when the run should end at the state just observed: an outcome, not an error (a
  // collapse, SPEC §7). The loop then calls end() at once; a list is done when one of its
  // observers is. Observers that write files write what they have seen (the run's last state
  // is the one observed last).
  virtual bool done() const { return false; }
};

}  // namespace adjoin
