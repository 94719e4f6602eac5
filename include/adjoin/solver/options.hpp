#pragma once
// How to integrate: the scheme, the history engine, the step and the horizon.
#include <cstddef>
#include <string>

#include "adjoin/core/enum_names.hpp"
#include "adjoin/fractional/history.hpp"

namespace adjoin {

// Scheme and its names ("implicit", "implicit-damped", "implicit-gl", "paper"): core/enum_names.hpp.

// The order of convergence of a scheme's reported values: 2 for "implicit" and
// "implicit-damped", 1 for "implicit-gl" and "paper".
int scheme_order(Scheme scheme);
// The schemes' names for error messages: "implicit" (default), "implicit-damped", ...
std::string scheme_names();

struct SolverOptions {
  Scheme scheme = Scheme::implicit;
  HistoryEngine history = HistoryEngine::soe;  // O(1) a step; "fft" O(N log^2 N), "direct" the O(N^2) reference
  double history_tolerance = 1e-12;  // "soe": the largest relative error of its weights, in [1e-15, 1)
  double h = 0.002;      // dimensionless time step
  double t_end = 16.0;   // dimensionless horizon
  // Explicit schemes refuse a step beyond their stability bound before they start. Turning
  // this off is for verifying the bound itself (the run then blows up or stops on a
  // non-finite value); not settable from scenes.
  bool stability_check = true;
  // Implicit schemes: report the switching instants inside the step where a phase changes
  // (StructureState::link_switch, by linear interpolation of the relative velocity or of the stick
  // force), instead of at the grid point that ends it.
  bool locate_switches = true;

  // Number of steps N: the smallest with N h >= t_end. The grid is t_m = m h, m = 0..N.
  std::size_t steps() const;
  // Checks h > 0, t_end > 0, and a grid that fits in memory; names the scene key on failure.
  // `field` (optional): the key of the problem (solver.h or solver.t_end).
  bool IsValid(std::string* error, std::string* field = nullptr) const;
};

// What a run reports of itself, whichever stepper ran it (the time loop fills the counts and
// the wall time; simulate_as_structure() and simulate_structure() the names and the step).
struct SolverSummary {
  std::string scheme;
  std::string history;
  double h = 0.0;
  std::size_t steps = 0;
  double wall_seconds = 0.0;      // the loop's: the stepper's set-up (weights) included
  std::size_t history_bytes = 0;  // memory held by the history engines
  double history_error = 0.0;     // soe: the largest relative weight error (0: exact engines)
  std::size_t history_modes = 0;  // soe: recurrences per element (Q)
  // Steps in which a friction damper at its onset and a nonlinear viscous damper on its floors
  // flipped each other's answer and the step took the mean of the two (structure_solver.cpp's
  // viscous_step): each carries the viscous force's error over one step.
  std::size_t viscous_split_steps = 0;
};

// The most steps a run takes (two-block and building runs alike), and the one message for a
// run beyond it (empty when t_end / h is within it).
inline constexpr double kMaxSteps = 2e9;  // (below 2^31)
std::string step_count_problem(double t_end, double h);

}  // namespace adjoin
