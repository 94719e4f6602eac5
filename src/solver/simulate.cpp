#include "adjoin/solver/simulate.hpp"

#include <unistd.h>

#include <cstdio>
#include <optional>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/two_block.hpp"
#include "schemes.hpp"

namespace adjoin {

double estimated_history_bytes(const SolverOptions& options, const Model& model) {
  return estimated_history_bytes(options, structure::two_block_structure(model));
}

double estimated_history_bytes(const SolverOptions& options, const structure::Structure& s) {
  // Per rod with memory and per step: direct sums keep the weights and the past values (2
  // doubles); the fft engine also keeps its blocks' spectra (measured about 57 bytes; 64
  // allowed). Elastic rods keep nothing; soe keeps a constant few kilobytes (in the 4096).
  const double per_rod_step = options.history == HistoryEngine::fft ? 64.0 : options.history == HistoryEngine::soe ? 0.0 : 16.0;
  // The rods with memory: the 1 + 1 structure's Zener storeys (one device each).
  const double rods = static_cast<double>(s.a.devices.size() + (s.b ? s.b->devices.size() : 0));
  return rods * per_rod_step * (static_cast<double>(options.steps()) + 2.0) + 4096.0;
}

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 0.0;
}

std::string memory_problem(double need_bytes, const std::string& what) {
  const double have = physical_memory_bytes();
  if (have <= 0.0 || need_bytes <= 0.8 * have) return "";
  char text[160];
  std::snprintf(text, sizeof text, "would need about %.3g GB of memory (", need_bytes / 1e9);
  std::string out = text + what;
  std::snprintf(text, sizeof text, "), more than the %.3g GB this machine can give (80 %% of %.3g GB)", 0.8 * have / 1e9,
                have / 1e9);
  return out + text;
}

namespace {

// The checks and the summary's names every two-block run shares.
void check_run(const SolverOptions& options, const Model& model) {
  std::string error;
  if (!model.IsValid(&error) || !options.IsValid(&error)) throw InputError(error);

  if (options.scheme == Scheme::paper && model.contact.model != structure::ContactModel::none)
    throw InputError("solver.scheme = \"paper\": a contact law (model.contact) runs on the implicit schemes only; use solver.scheme = \"implicit\"");
  if (options.scheme == Scheme::paper && model.base_friction > 0.0)
    throw InputError("solver.scheme = \"paper\": the base friction (model.base_friction) runs on the implicit schemes only; use solver.scheme = \"implicit\"");
}

SolverSummary named(SolverSummary summary, const SolverOptions& options) {
  summary.scheme = to_string(options.scheme);
  summary.history = to_string(options.history);
  summary.h = options.h;
  summary.steps = options.steps();
  return summary;
}

// Each scheme is a stepper driven by the one time loop (time_loop.hpp), which also times the
// run (set-up included). `s` is `model`'s 1 + 1 structure: the implicit schemes run it, the
// paper's scheme the model.
SolverSummary run(const SolverOptions& options, const Model& model, const structure::Structure& s, const GroundMotion& ground,
                  StructureObserver& observer) {
  check_run(options, model);
  return named(options.scheme == Scheme::paper ? detail::run_paper_scheme(options, model, ground, observer)
                                               : detail::run_two_block_on_structure(options, s, ground, observer),
               options);
}

}  // namespace

SolverSummary simulate_as_structure(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                                    StructureObserver& observer) {
  return run(options, model, structure::two_block_structure(model), ground, observer);
}

SolverSummary simulate_as_structure(const SolverOptions& options, const structure::Structure& structure,
                                    const GroundMotion& ground, StructureObserver& observer) {
  std::string why;
  const std::optional<Model> model = structure::two_block_model(structure, &why);
  if (!model) throw InputError("the two-block solver (simulate_as_structure) was given " + why);
  return run(options, *model, structure, ground, observer);
}

StructureSolverOptions with_scheme(StructureSolverOptions o, Scheme scheme) {
  o.scheme = scheme;
  if (scheme == Scheme::implicit_damped) o.restart = StructureSolverOptions::Restart::always;
  if (scheme == Scheme::implicit_gl) o.quadrature = StructureSolverOptions::Quadrature::grunwald_letnikov;
  return o;
}

}  // namespace adjoin
