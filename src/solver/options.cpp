#include "adjoin/solver/options.hpp"

#include <cmath>
#include <sstream>

namespace adjoin {

namespace {

// Every scheme and its name, in one place.
struct SchemeName {
  Scheme scheme;
  const char* name;
  int order;
};
constexpr SchemeName kSchemes[] = {
    {Scheme::implicit, "implicit", 2},
    {Scheme::implicit_damped, "implicit-damped", 2},
    {Scheme::implicit_gl, "implicit-gl", 1},
    {Scheme::paper, "paper", 1},
};

}  // namespace

int scheme_order(Scheme scheme) {
  for (const auto& s : kSchemes)
    if (s.scheme == scheme) return s.order;
  return 1;
}

std::string to_string(Scheme scheme) {
  for (const auto& s : kSchemes)
    if (s.scheme == scheme) return s.name;
  return "?";
}

bool parse_scheme(const std::string& name, Scheme* scheme) {
  for (const auto& s : kSchemes)
    if (name == s.name) { *scheme = s.scheme; return true; }
  return false;
}

std::string scheme_names() {
  std::string out;
  for (const auto& s : kSchemes) {
    out += (out.empty() ? "\"" : ", \"") + std::string(s.name) + "\"";
    if (s.scheme == SolverOptions{}.scheme) out += " (default)";
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
