#pragma once
// One run of a spec, whatever the scene (SPEC §4: one model, one pipeline):
//
//     Report report = run(spec);                       // the run's own observers
//     Report report = run(spec, {&writer});            // and a structure observer
//
// Every spec takes one path: its structure through simulate_spec (below) with one list of
// structure observers, the report's and the caller's. A building (SPEC §5) runs on the structure
// stepper; a two-block spec (SPEC §1) runs as its 1 + 1 structure on the paper's stepper or on
// the structure stepper as its scheme says (solver/simulate.hpp simulate_as_structure). The
// report's observers are chosen by how the scene presents it: a building's channels (peaks,
// links, contact pairs, energy), or the paper's refined values of the 1 + 1 structure (peaks,
// phases, pounding margin, energy balance: observe/), which io shows under SPEC §3's names
// (io/two_block_names.hpp). Every run made from a spec goes through here: `adjoin run`, a sweep row, a convergence rung, an error estimate's companion, the
// tolerance ladder, the seismic joint. Parts the spec did not ask for are neither computed nor
// kept.
#include "adjoin/study/report.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin {

// What else sees a run's grid points (not owned; may be null).
struct RunObservers {
  StructureObserver* structure = nullptr;  // any run: its StructureState (a two-block run's 1 + 1)
};

Report run(const RunSpec& spec, const RunObservers& extra = {});

// Integrates `s` (the spec's structure or an edit of it of the same size; for a two-block spec,
// a model's 1 + 1 structure, on the scheme it names) with the spec's ground and solver options,
// the spec's memory checked first (check_memory) and its steps
// shown to the spec's watch: a building run whose observers the caller chooses (the seismic
// joint's bisection). A building with storey heights is watched for collapse (SPEC §7): a
// storey's |drift / h| past its collapse_drift_ratio ends the run there, an outcome, which
// *collapse receives (when given; reset otherwise).
SolverSummary simulate_spec(const RunSpec& spec, const structure::Structure& s, StructureObserver& observer,
                            std::optional<Collapse>* collapse = nullptr);

// Refuses (InputError, exit 2) before it starts a building run that could hold the step and
// horizon it needs only by using more memory than the machine can give: every run's rule
// (solver/simulate.hpp memory_problem). run() checks each run (and so `run`, `joint`,
// `converge` and sweeps); commands call it first to refuse before any work. (A two-block
// scene's history is checked when it is read: io/scene.hpp.)
void check_memory(const RunSpec& spec);
// What a building run holds [bytes], known before it starts: each Zener element's history
// (weights and past values, 16 bytes a step with the direct engine, 64 with fft: the two-block
// rods' figures), the quadrature weights of each order (8 bytes a step), the histories kept
// for in-run spectra (8 bytes a step each) and the step's dense matrices.
double estimated_run_bytes(const RunSpec& spec);

}  // namespace adjoin
