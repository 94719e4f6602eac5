#pragma once
// The event of a fragility curve, written as a condition on a run's values (SPEC §9):
//
//     contact1.impacts > 0
//     A.drift_ratio1 > 0.02 or link1.stroke_max >= 0.1
//     contact1.impacts > 0 and (A.drift_max > 0.05 or B.drift_max > 0.05)
//
// A comparison is a column's name, one of > >= < <=, and a number; `and` binds tighter than
// `or` (a or b and c = a or (b and c)); parentheses group. A boolean column (true/false) reads
// as 1/0: `contact1.contact > 0`. Names are the table's columns (letters, digits, _ . : -),
// keywords are lower case.
//
// A run whose value is missing (an empty cell, NaN) makes its comparison unknown; `and` and
// `or` then follow Kleene's logic (false and unknown = false, true or unknown = true), and a
// run whose event stays unknown has no outcome (the caller leaves it out and says so).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/post/fragility.hpp"

namespace adjoin {

class FragilityEvent {
 public:
  // InputError (a message starting `OPTION "TEXT": ...`, `--event` unless `option` says
  // otherwise: ida's `--capacity`) naming the unknown column with the columns there are, or the
  // token that is not what was expected, with its position.
  static FragilityEvent parse(const std::string& text, const std::vector<std::string>& columns,
                              const std::string& option = "--event");

  // The event for one run: `values[i]` is the run's value in columns[i] (as given to parse);
  // nullopt when it depends on a missing value.
  std::optional<bool> evaluate(const std::vector<double>& values) const;

  // The columns the expression reads (indices into the columns given to parse), each once.
  std::vector<std::size_t> columns_used() const;
  const std::string& text() const { return text_; }

 private:
  enum class Op { greater, greater_equal, less, less_equal, and_, or_ };
  struct Node {
    Op op;
    std::size_t column = 0;  // a comparison's column
    double number = 0.0;     // a comparison's number
    int left = -1, right = -1;  // and/or: the operands' nodes
  };
  std::optional<bool> evaluate(int node, const std::vector<double>& values) const;

  std::string text_, option_;
  std::vector<Node> nodes_;
  int root_ = -1;
  friend class EventParser;
};

// The runs of a table with the event evaluated (`adjoin fragility` and adjoin.fragility):
// row r is record `records[r]` at `im[r]`, `values[c][r]` its value in the event's column c
// (NaN for an empty cell; only the columns the event reads need values), `errors[r]` non-empty
// for a run that failed (`errors` may be empty: none failed). A failed run, or one whose event
// reads a missing value, is left out and counted. The caller checks the IMs and record names.
struct FragilityOutcomes {
  std::vector<FragilityRun> runs;
  std::size_t failed = 0, unknown = 0;
  std::size_t first_unknown = 0;  // the row of the first unknown run
  bool trace = false;             // fragility_is_trace of every row (failed ones too: they were run there)
};
FragilityOutcomes fragility_outcomes(const FragilityEvent& event, const std::vector<std::string>& records,
                                     const std::vector<double>& im, const std::vector<std::vector<double>>& values,
                                     const std::vector<std::string>& errors);

}  // namespace adjoin
