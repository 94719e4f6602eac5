#pragma once
// The two kinds of failure adjoin reports, and the exit status each one maps to.
//
//  - InputError: the user's input is wrong (a scene key, a record line, a command-line value).
//    The message names the file, line or key and says what was expected. Exit status 2.
//  - NumericalError: the input was valid but the computation went wrong (instability,
//    non-finite values). The message says when (simulation time) and what to change. Exit 3.
//
// Library code throws these; only the command-line layer turns them into exit statuses.
#include <stdexcept>
#include <string>
#include <utility>

namespace adjoin {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An InputError about one field of a description built in code (structure/builder.hpp), named
// by its path: "building.A.period", "building.A.masses[3]", "link[1].slip_force" (elements and
// list items counted from 1, as a scene's [[link]] tables are). what() is "path: problem"; a
// reader that took the value from elsewhere (a scene line, a --set) spells the path its way.
class FieldError : public InputError {
 public:
  FieldError(std::string field, std::string problem)
      : InputError(field + ": " + problem), field_(std::move(field)), problem_(std::move(problem)) {}
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string field_, problem_;
};

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
