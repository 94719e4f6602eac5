#include "adjoin/solver/options.hpp"

#include <cmath>
#include <sstream>

namespace adjoin {

int scheme_order(Scheme scheme) {
  return scheme == Scheme::implicit || scheme == Scheme::implicit_damped ? 2 : 1;
}

std::string scheme_names() {
  std::string out;
  for (const std::string& name : names<Scheme>()) {
    out += (out.empty() ? "\"" : ", \"") + name + "\"";
    if (name == to_string(SolverOptions{}.scheme)) out += " (default)";
  }
  return out;
}

std::size_t SolverOptions::steps() const {
  // The smallest N with N h >= t_end, forgiving the rounding in t_end / h.
  return static_cast<std::size_t>(std::ceil(t_end / h * (1.0 - 1e-12)));
}

std::string step_count_problem(double t_end, double h) {
  if (!(t_end / h > kMaxSteps)) return "";
  std::ostringstream s;
  s.precision(4);
  s << "solver.t_end / solver.h = " << t_end / h << " steps is more than the " << kMaxSteps / 1e9
    << "e9 supported; raise solver.h or shorten solver.t_end";
  return s.str();
}

bool SolverOptions::IsValid(std::string* error, std::string* field) const {
  auto fail = [&](const char* key, const std::string& m) {
    if (error) *error = m;
    if (field) *field = key;
    return false;
  };
  std::ostringstream s;
  s.precision(12);
  if (!(std::isfinite(h) && h > 0.0)) { s << "solver.h = " << h << " must be a positive number"; return fail("solver.h", s.str()); }
  if (!(std::isfinite(t_end) && t_end > 0.0)) { s << "solver.t_end = " << t_end << " must be a positive number"; return fail("solver.t_end", s.str()); }
  if (const std::string problem = step_count_problem(t_end, h); !problem.empty()) return fail("solver.t_end", problem);
  if (t_end / h < 1.0) { s << "solver.h = " << h << " must not exceed solver.t_end = " << t_end; return fail("solver.h", s.str()); }
  if (!(history_tolerance >= 1e-15 && history_tolerance < 1.0)) {
    s << "solver.history_tolerance = " << history_tolerance << " must lie in [1e-15, 1) (a relative error of the weights)";
    return fail("solver.history_tolerance", s.str());
  }
  return true;
}

}  // namespace adjoin
