#pragma once
// Output writers refuse non-finite values: a NaN or an Inf stops the run with a numerical
// failure (exit status 3) naming the file, the quantity and the time, and since a run's files
// are committed as a set (temporary files renamed at the end), nothing of that run is left.
#include <cmath>
#include <sstream>
#include <string>

#include "adjoin/core/errors.hpp"

namespace adjoin::detail {

[[noreturn]] inline void non_finite_output(const std::string& file, const std::string& quantity, double value,
                                           double t_seconds, double t_solver) {
  std::ostringstream s;
  s << file << ": " << quantity << " became " << value << " at t = " << t_seconds
    << "; the values overflow the floating-point range: check the scene's scales (masses, "
       "stiffnesses, ground motion amplitude) or reduce solver.h";
  throw NumericalError(s.str(), t_solver);
}

inline void require_finite_output(double value, const char* file, const char* quantity, double t_seconds,
                                  double t_solver) {
  if (!std::isfinite(value)) non_finite_output(file, quantity, value, t_seconds, t_solver);
}

}  // namespace adjoin::detail
