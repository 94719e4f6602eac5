#pragma once
// The two kinds of failure adjoin reports, and the exit status each one maps to.
//
//  - InputError: the user's input is wrong (a scene key, a record line, a command-line value).
//    The message names the file, line or key and says what was expected. Exit status 2.
//  - NumericalError: the input was valid but the computation went wrong (instability,
//    non-finite values). The message says when (simulation time) and what to change. Exit 3.
//
// Library code throws these; only the command-line layer turns them into exit statuses.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace adjoin {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message, std::string field = {})
      : std::runtime_error(message), field_(std::move(field)) {}
  // The field the error is about, as a path (below), or "" when it is not about one field (a
  // file that cannot be read, a record's line). Code that must know which field was wrong (a
  // sweep pointing at the axis value that set it) reads this, never the message.
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// An InputError about one field of a description built in code (structure/builder.hpp), named
// by its path: "building.A.period", "building.A.masses[3]", "link[1].slip_force" (elements and
// list items counted from 1, as a scene's [[link]] tables are). what() is "path: problem"; a
// reader that took the value from elsewhere (a scene line, a --set) spells the path its way.
class FieldError : public InputError {
 public:
  FieldError(std::string field, std::string problem)
      : InputError(field + ": " + problem, field), problem_(std::move(problem)) {}
  const std::string& problem() const { return problem_; }

 private:
  std::string problem_;
};

// The field path of a scene's dotted key, as InputError::field() spells it: a component that
// is a number counts list items from 1 and is written in brackets ("link.1.slip_force" ->
// "link[1].slip_force", "building.A.masses.2" -> "building.A.masses[2]").
inline std::string field_path(const std::string& dotted_key) {
  std::string out;
  std::size_t start = 0;
  while (start <= dotted_key.size()) {
    const std::size_t dot = std::min(dotted_key.find('.', start), dotted_key.size());
    const std::string part = dotted_key.substr(start, dot - start);
    const bool number = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    out += number && !out.empty() ? "[" + part + "]" : (out.empty() ? "" : ".") + part;
    start = dot + 1;
  }
  return out;
}

class NumericalError : public std::runtime_error {
 public:
  NumericalError(const std::string& message, double time)
      : std::runtime_error(message), time_(time) {}
  // Simulation time (in the solver's dimensionless units) at which the failure was detected.
  double time() const { return time_; }

 private:
  double time_;
};

inline constexpr int kExitInputError = 2;
inline constexpr int kExitNumericalError = 3;

}  // namespace adjoin
