#pragma once
// Observers receive the solution as the solver produces it, one grid point at a time, so a
// long run need not keep its whole history: each observer keeps only what it reports.
//
// Call order: begin(info) once, observe(state) for t_0 = 0, t_1, ..., t_N in order, then
// end() once. Every run is a structure's (a two-block scene's: its 1 + 1 structure,
// structure/two_block.hpp), so there is one interface, StructureObserver, in the structure's units.
#include <cstddef>
#include <vector>

#include "adjoin/core/history_engine.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/structure/parameters.hpp"
#include "adjoin/structure/state.hpp"

namespace adjoin {

struct StructureSolverOptions;  // solver/structure_solver.hpp: what begin() is told of the run

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
