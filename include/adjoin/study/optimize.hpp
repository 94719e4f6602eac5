#pragma once
// Design optimisation (SPEC §9 "Optimisation"): the numbers of `adjoin optimize` without its
// files or runs. A design is a discrete choice (a placement: one of `choices`, enumerated) and
// continuous variables x within bounds; `evaluate(choice, x)` gives its objective(s) and its
// constraint values. io/optimize_study.hpp reads the study file and evaluates a design by
// running the suite through the sweep machinery.
//
//     OptimizeOptions options;                       // method "bobyqa", tolerance 1e-3, ...
//     OptimizeResult r = optimize_designs(variables, choices, 1, 0, options, evaluate);
//     const Evaluation& best = r.evaluations[*r.best];
//
// How it searches:
//  - every choice is optimised in turn (enumeration), with the same method, start and seed;
//  - NLopt works on the unit box u in [0, 1]^n, x = min + u (max - min): `tolerance` is an
//    absolute tolerance on u (a fraction of each variable's range, NLopt's xtol_abs), and
//    `max_evaluations` bounds each optimisation (NLopt's maxeval). The start is each
//    variable's `start` or the middle of its range; the initial step a quarter of the range;
//  - constraints (value <= max) are NLopt inequality constraints, scaled by |max|: natively for
//    the methods that take them (cobyla, isres), through NLopt's augmented Lagrangian (AUGLAG,
//    with the method as its subsidiary optimiser) for the others;
//  - a design evaluated again (NLopt revisits points) is taken from a memo: `evaluations` holds
//    each distinct design once, in the order first evaluated;
//  - two objectives: an epsilon-constraint scan with `pareto_points` points: minimise f1, then
//    f2, then f1 subject to f2 <= eps at pareto_points - 2 levels evenly between the two
//    optima's f2; the front is the non-dominated set of every feasible design evaluated;
//  - stochastic methods (crs2, isres) are seeded with `seed` (nlopt_srand) before each
//    optimisation, so a study is reproducible.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace adjoin {

// ---- a demand's statistic over the suite's records ----

enum class Statistic { mean, median, p84, max };
// "mean", "median", "p84", "max"; nullopt for another word.
std::optional<Statistic> statistic_from_name(const std::string& name);
std::string statistic_name(Statistic s);
// The statistic of the values (one per record, every one finite, at least one): the mean; the
// median and the 84th percentile as sample quantiles (linear between order statistics, the
// p-quantile at position p (n - 1) of the sorted values); the largest.
double suite_statistic(std::vector<double> values, Statistic s);

// ---- the methods ----

struct OptimizeMethod {
  std::string name;         // as the study file names it
  int algorithm = 0;        // nlopt_algorithm
  bool global = false;      // searches the whole box (else: local, from the start)
  bool constraints = false; // takes inequality constraints itself (else: through AUGLAG)
  bool stochastic = false;  // uses the seed
  std::string meaning;      // for messages and docs
};
// bobyqa (the default), cobyla, neldermead, sbplx (local, derivative-free); direct (DIRECT-L),
// crs2 (controlled random search), isres (evolution strategy; global).
const std::vector<OptimizeMethod>& optimize_methods();
const OptimizeMethod* find_optimize_method(const std::string& name);
// "bobyqa, cobyla, ..." for messages.
std::string optimize_method_names();

// ---- the problem ----

struct OptimizeVariable {
  std::string key;  // what it names (a scene key); min < max
  double min = 0.0, max = 1.0;
  std::optional<double> start;  // inside [min, max]; default the middle
};

struct OptimizeOptions {
  std::string method = "bobyqa";
  double tolerance = 1e-3;            // on the unit box, in (0, 1)
  std::size_t max_evaluations = 60;   // per optimisation, >= 1
  std::uint32_t seed = 1;
  std::size_t pareto_points = 5;      // two objectives: points of the scan, >= 2
};

// What a design gives: its objective(s) (to minimise) and its constraint values with their
// limits (feasible when value <= max, up to 1e-6 |max|).
struct DesignValues {
  std::vector<double> objectives;
  std::vector<double> constraints;
};

struct Evaluation {
  std::size_t choice = 0;
  std::vector<double> x;
  DesignValues values;
  bool feasible = true;
  std::string stage;  // which optimisation first asked for it: "min f1", "min f2", "eps 2/5", "enumeration"
};

// One optimisation (one choice, one stage).
struct OptimizeRun {
  std::size_t choice = 0;
  std::string stage;
  std::size_t best = 0;          // the evaluation NLopt returned (index into evaluations)
  std::size_t evaluations = 0;   // NLopt's calls of the objective in this run (memo hits included)
  std::string stop;              // NLopt's reason, in words
};

struct OptimizeResult {
  std::vector<Evaluation> evaluations;
  std::vector<OptimizeRun> runs;
  // One objective: the feasible evaluation with the smallest objective (the first, on a tie);
  // if none is feasible, the one with the smallest constraint violation. Two objectives: the
  // front's point with the smallest f1.
  std::optional<std::size_t> best;
  // Two objectives: the non-dominated feasible evaluations, by increasing f1.
  std::vector<std::size_t> pareto;
};

using DesignEvaluator = std::function<DesignValues(std::size_t choice, const std::vector<double>& x)>;

// Optimises (see above). `limits`: each constraint's max (size = the constraint count).
// Exceptions from `evaluate` stop the search and propagate; NumericalError if NLopt fails
// (invalid arguments, out of memory) for another reason.
OptimizeResult optimize_designs(const std::vector<OptimizeVariable>& variables, std::size_t choices,
                                std::size_t objectives, const std::vector<double>& limits,
                                const OptimizeOptions& options, const DesignEvaluator& evaluate);

// Whether the values meet the limits (value <= max + 1e-6 |max|).
bool feasible(const std::vector<double>& constraints, const std::vector<double>& limits);

// The indices of the points not dominated by another (a dominates b when a <= b in both and
// a < b in one), by increasing first coordinate; of equal points only the first is kept.
std::vector<std::size_t> non_dominated(const std::vector<std::pair<double, double>>& points);

}  // namespace adjoin
