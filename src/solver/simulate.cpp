#include "adjoin/solver/simulate.hpp"

#include <chrono>

#include "adjoin/errors.hpp"
#include "schemes.hpp"

namespace adjoin {

SolverSummary simulate(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                       Observer& observer) {
  std::string error;
  if (!model.IsValid(&error) || !options.IsValid(&error)) throw InputError(error);

  const auto start = std::chrono::steady_clock::now();
  std::size_t history_bytes = 0;
  switch (options.scheme) {
    case Scheme::paper: history_bytes = detail::run_paper_scheme(options, model, ground, observer); break;
    case Scheme::implicit:
    case Scheme::implicit_gl: history_bytes = detail::run_implicit_scheme(options, model, ground, observer); break;
  }
  const auto stop = std::chrono::steady_clock::now();

  SolverSummary summary;
  summary.scheme = to_string(options.scheme);
  summary.history = to_string(options.history);
  summary.h = options.h;
  summary.steps = options.steps();
  summary.wall_seconds = std::chrono::duration<double>(stop - start).count();
  summary.history_bytes = history_bytes;
  return summary;
}

}  // namespace adjoin
