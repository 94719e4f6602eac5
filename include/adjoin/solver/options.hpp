#pragma once
// How to integrate: the scheme, the history engine, the step and the horizon.
#include <cstddef>
#include <string>

#include "adjoin/fractional/history.hpp"

namespace adjoin {

enum class Scheme {
  // The paper's algorithm (3.1)/(3.2): explicit central differences, Grünwald–Letnikov
  // history, stick/slip switching on the grid. First order, conditionally stable. The
  // regression baseline.
  paper,
};

std::string to_string(Scheme scheme);
bool parse_scheme(const std::string& name, Scheme* scheme);
// Names accepted by parse_scheme, for error messages.
std::string scheme_names();

struct SolverOptions {
  Scheme scheme = Scheme::paper;
  HistoryEngine history = HistoryEngine::direct;
  double h = 0.002;      // dimensionless time step
  double t_end = 16.0;   // dimensionless horizon
  // Explicit schemes refuse a step beyond their stability bound before they start. Turning
  // this off is for verifying the bound itself (the run then blows up or stops on a
  // non-finite value); not settable from scenes.
  bool stability_check = true;

  // Number of steps N: the smallest with N h >= t_end. The grid is t_m = m h, m = 0..N.
  std::size_t steps() const;
  // Checks h > 0, t_end > 0, and a grid that fits in memory; names the scene key on failure.
  bool IsValid(std::string* error) const;
};

}  // namespace adjoin
