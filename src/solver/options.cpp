#include "adjoin/solver/options.hpp"

#include <cmath>
#include <sstream>

namespace adjoin {

std::string to_string(Scheme scheme) {
  switch (scheme) {
    case Scheme::paper: return "paper";
    case Scheme::implicit: return "implicit";
    case Scheme::implicit_gl: return "implicit-gl";
  }
  return "?";
}

bool parse_scheme(const std::string& name, Scheme* scheme) {
  if (name == "paper") { *scheme = Scheme::paper; return true; }
  if (name == "implicit") { *scheme = Scheme::implicit; return true; }
  if (name == "implicit-gl") { *scheme = Scheme::implicit_gl; return true; }
  return false;
}

std::string scheme_names() { return "\"implicit\" (default), \"implicit-gl\", \"paper\""; }

std::size_t SolverOptions::steps() const {
  // The smallest N with N h >= t_end, forgiving the rounding in t_end / h.
  return static_cast<std::size_t>(std::ceil(t_end / h * (1.0 - 1e-12)));
}

bool SolverOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) { if (error) *error = m; return false; };
  std::ostringstream s;
  s.precision(12);
  if (!(std::isfinite(h) && h > 0.0)) { s << "solver.h = " << h << " must be a positive number"; return fail(s.str()); }
  if (!(std::isfinite(t_end) && t_end > 0.0)) { s << "solver.t_end = " << t_end << " must be a positive number"; return fail(s.str()); }
  if (t_end / h > 2.0e9) {
    s << "solver.t_end / solver.h = " << t_end / h << " steps is more than the 2e9 supported; raise solver.h";
    return fail(s.str());
  }
  if (t_end / h < 1.0) { s << "solver.h = " << h << " must not exceed solver.t_end = " << t_end; return fail(s.str()); }
  return true;
}

}  // namespace adjoin
