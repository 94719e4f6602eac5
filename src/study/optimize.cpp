// Design optimisation with NLopt (study/optimize.hpp). NLopt's C interface is used, not its
// C++ wrapper: the wrapper swallows an exception thrown in an objective, and ours (a bad
// scene, a numerical failure in a run) must reach the caller.
#include "adjoin/study/optimize.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <utility>

#include "adjoin/core/errors.hpp"

namespace adjoin {
namespace {

constexpr double kFeasibleSlack = 1e-6;  // relative to |max|
constexpr double kInitialStep = 0.25;    // on the unit box

// A constraint's scale: its limit's size (1 for a limit of 0), so that NLopt's constraint
// tolerances mean the same for a drift ratio and a force.
double limit_scale(double max) { return max != 0.0 ? std::abs(max) : 1.0; }

// How far the values are outside their limits, each relative to its scale (0 when feasible).
double violation(const std::vector<double>& values, const std::vector<double>& limits) {
  double v = 0.0;
  for (std::size_t k = 0; k < limits.size(); ++k) v += std::max(0.0, (values[k] - limits[k]) / limit_scale(limits[k]));
  return v;
}

std::string stop_reason(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS: return "converged";
    case NLOPT_STOPVAL_REACHED: return "stop value reached";
    case NLOPT_FTOL_REACHED: return "objective tolerance reached";
    case NLOPT_XTOL_REACHED: return "the step fell below the tolerance";
    case NLOPT_MAXEVAL_REACHED: return "max_evaluations reached";
    case NLOPT_MAXTIME_REACHED: return "time limit reached";
    case NLOPT_ROUNDOFF_LIMITED: return "stopped by roundoff";
    case NLOPT_FORCED_STOP: return "max_evaluations reached";  // our own budget (below)
    default: return "failed";
  }
}

// One optimisation's state, shared with NLopt's callbacks.
struct Search {
  const std::vector<OptimizeVariable>& variables;
  const std::vector<double>& limits;
  const DesignEvaluator& evaluate;
  const OptimizeOptions& options;
  OptimizeResult& result;
  std::map<std::pair<std::size_t, std::vector<double>>, std::size_t>& memo;

  Search(const std::vector<OptimizeVariable>& v, const std::vector<double>& l, const DesignEvaluator& e,
         const OptimizeOptions& o, OptimizeResult& r, std::map<std::pair<std::size_t, std::vector<double>>, std::size_t>& m)
      : variables(v), limits(l), evaluate(e), options(o), result(r), memo(m) {}

  std::size_t choice = 0;
  std::string stage;
  std::size_t minimise = 0;    // which objective
  std::optional<double> eps;   // f2 <= eps (the Pareto scan)
  double eps_scale = 1.0;
  nlopt_opt opt = nullptr;     // the outer optimiser, to stop
  std::exception_ptr failure;
  std::size_t calls = 0;
  std::vector<std::size_t> seen;  // the evaluations this run asked for

  // The design at u (the unit box), evaluated once.
  const Evaluation& at(const double* u) {
    std::vector<double> x(variables.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double t = std::clamp(u[i], 0.0, 1.0);
      x[i] = variables[i].min + t * (variables[i].max - variables[i].min);
    }
    return design(std::move(x));
  }
  const Evaluation& design(std::vector<double> x) {
    ++calls;
    auto key = std::make_pair(choice, x);
    auto it = memo.find(key);
    if (it == memo.end()) {
      Evaluation e;
      e.choice = choice;
      e.x = std::move(x);
      e.values = evaluate(choice, e.x);
      e.feasible = feasible(e.values.constraints, limits);
      e.stage = stage;
      result.evaluations.push_back(std::move(e));
      it = memo.emplace(std::move(key), result.evaluations.size() - 1).first;
    }
    seen.push_back(it->second);
    return result.evaluations[it->second];
  }
  // Runs `f` for NLopt: an exception stops the search (kept to rethrow), as does the budget.
  template <class F>
  double guarded(F&& f) {
    if (failure) return HUGE_VAL;
    try {
      const double v = f();
      if (calls >= options.max_evaluations) nlopt_force_stop(opt);
      return v;
    } catch (...) {
      failure = std::current_exception();
      nlopt_force_stop(opt);
      return HUGE_VAL;
    }
  }
};

double objective(unsigned, const double* u, double*, void* data) {
  auto* s = static_cast<Search*>(data);
  return s->guarded([&] { return s->at(u).values.objectives[s->minimise]; });
}

struct ConstraintData {
  Search* search;
  std::size_t k;  // a user constraint; k = limits.size(): the Pareto scan's f2 <= eps
};

double constraint(unsigned, const double* u, double*, void* data) {
  auto* c = static_cast<ConstraintData*>(data);
  Search* s = c->search;
  return s->guarded([&] {
    const Evaluation& e = s->at(u);
    if (c->k == s->limits.size()) return (e.values.objectives[1] - *s->eps) / s->eps_scale;
    return (e.values.constraints[c->k] - s->limits[c->k]) / limit_scale(s->limits[c->k]);
  });
}

struct OptDeleter {
  void operator()(nlopt_opt o) const { nlopt_destroy(o); }
};
using Opt = std::unique_ptr<std::remove_pointer_t<nlopt_opt>, OptDeleter>;

Opt make_opt(nlopt_algorithm algorithm, unsigned n, const OptimizeOptions& options) {
  Opt o(nlopt_create(algorithm, n));
  if (!o) throw NumericalError("optimize: NLopt could not create the optimiser (out of memory)", 0.0);
  nlopt_set_lower_bounds1(o.get(), 0.0);
  nlopt_set_upper_bounds1(o.get(), 1.0);
  nlopt_set_xtol_abs1(o.get(), options.tolerance);
  nlopt_set_maxeval(o.get(), static_cast<int>(std::min<std::size_t>(options.max_evaluations, 1u << 30)));
  nlopt_set_initial_step1(o.get(), kInitialStep);
  return o;
}

// The best of the run's evaluations: feasible first (within the Pareto scan's f2 <= eps too),
// then the smallest objective (the first on a tie); among infeasible ones the smallest violation.
std::size_t best_of(const OptimizeResult& r, const std::vector<std::size_t>& indices, std::size_t objective_index,
                    const std::vector<double>& limits, std::optional<double> eps, double eps_scale) {
  const auto rank = [&](std::size_t i) {
    const Evaluation& e = r.evaluations[i];
    double v = e.feasible ? 0.0 : violation(e.values.constraints, limits);
    if (eps && e.values.objectives[1] - *eps > kFeasibleSlack * eps_scale) v += (e.values.objectives[1] - *eps) / eps_scale;
    return std::make_pair(v, e.values.objectives[objective_index]);
  };
  std::size_t best = indices.front();
  for (std::size_t i : indices)
    if (rank(i) < rank(best)) best = i;
  return best;
}

// One NLopt optimisation of `s` (its choice, stage, objective and eps set).
void optimise(Search& s, const OptimizeMethod& method) {
  const auto n = static_cast<unsigned>(s.variables.size());
  const std::size_t constraints = s.limits.size() + (s.eps ? 1 : 0);
  const bool wrap = constraints > 0 && !method.constraints;
  const auto algorithm = static_cast<nlopt_algorithm>(method.algorithm);
  Opt outer = make_opt(wrap ? NLOPT_AUGLAG : algorithm, n, s.options);
  Opt local;
  if (wrap) {
    local = make_opt(algorithm, n, s.options);
    nlopt_set_local_optimizer(outer.get(), local.get());
  }
  s.opt = outer.get();
  s.calls = 0;
  s.seen.clear();
  nlopt_set_min_objective(outer.get(), objective, &s);
  std::vector<ConstraintData> data;
  for (std::size_t k = 0; k < s.limits.size(); ++k) data.push_back({&s, k});
  if (s.eps) data.push_back({&s, s.limits.size()});
  for (auto& d : data) nlopt_add_inequality_constraint(outer.get(), constraint, &d, 0.0);
  if (method.stochastic) nlopt_srand(s.options.seed);
  std::vector<double> u(n);
  for (unsigned i = 0; i < n; ++i) {
    const auto& v = s.variables[i];
    u[i] = v.start ? (*v.start - v.min) / (v.max - v.min) : 0.5;
  }
  double f = 0.0;
  const nlopt_result r = nlopt_optimize(outer.get(), u.data(), &f);
  if (s.failure) std::rethrow_exception(s.failure);
  if (r == NLOPT_INVALID_ARGS || r == NLOPT_OUT_OF_MEMORY || (r == NLOPT_FAILURE && s.seen.empty()))
    throw NumericalError("optimize: NLopt's " + method.name + " failed (" + std::string(nlopt_result_to_string(r)) + ")", 0.0);
  if (s.seen.empty()) s.at(u.data());  // NLopt stopped before asking: its start is the run's design
  OptimizeRun run;
  run.choice = s.choice;
  run.stage = s.stage;
  run.best = best_of(s.result, s.seen, s.minimise, s.limits, s.eps, s.eps_scale);
  run.evaluations = s.calls;
  run.stop = stop_reason(r);
  s.result.runs.push_back(std::move(run));
}

// The evaluation with the smallest objective among the feasible ones (the smallest violation
// if none is).
std::size_t overall_best(const OptimizeResult& r, const std::vector<double>& limits) {
  std::vector<std::size_t> all(r.evaluations.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return best_of(r, all, 0, limits, std::nullopt, 1.0);
}

}  // namespace

// ---- statistics ----

std::optional<Statistic> statistic_from_name(const std::string& name) {
  if (name == "mean") return Statistic::mean;
  if (name == "median") return Statistic::median;
  if (name == "p84") return Statistic::p84;
  if (name == "max") return Statistic::max;
  return std::nullopt;
}

std::string statistic_name(Statistic s) {
  switch (s) {
    case Statistic::mean: return "mean";
    case Statistic::median: return "median";
    case Statistic::p84: return "p84";
    case Statistic::max: return "max";
  }
  return "?";
}

double suite_statistic(std::vector<double> values, Statistic s) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const auto quantile = [&](double p) {
    const double at = p * static_cast<double>(values.size() - 1);
    const auto i = static_cast<std::size_t>(std::floor(at));
    if (i + 1 >= values.size()) return values.back();
    return values[i] + (at - static_cast<double>(i)) * (values[i + 1] - values[i]);
  };
  switch (s) {
    case Statistic::mean: {
      double sum = 0.0;
      for (double v : values) sum += v;
      return sum / static_cast<double>(values.size());
    }
    case Statistic::median: return quantile(0.5);
    case Statistic::p84: return quantile(0.84);
    case Statistic::max: return values.back();
  }
  return values.back();
}

// ---- methods ----

const std::vector<OptimizeMethod>& optimize_methods() {
  static const std::vector<OptimizeMethod> methods{
      {"bobyqa", NLOPT_LN_BOBYQA, false, false, false, "local: quadratic models in a trust region (Powell's BOBYQA)"},
      {"cobyla", NLOPT_LN_COBYLA, false, true, false, "local: linear models, takes constraints (Powell's COBYLA)"},
      {"neldermead", NLOPT_LN_NELDERMEAD, false, false, false, "local: the Nelder-Mead simplex"},
      {"sbplx", NLOPT_LN_SBPLX, false, false, false, "local: Nelder-Mead on subspaces (Rowan's Subplex)"},
      {"direct", NLOPT_GN_DIRECT_L, true, false, false, "global: dividing rectangles, locally biased (DIRECT-L)"},
      {"crs2", NLOPT_GN_CRS2_LM, true, false, true, "global: controlled random search with local mutation (seeded)"},
      {"isres", NLOPT_GN_ISRES, true, true, true, "global: an evolution strategy, takes constraints (seeded)"},
  };
  return methods;
}

const OptimizeMethod* find_optimize_method(const std::string& name) {
  for (const auto& m : optimize_methods())
    if (m.name == name) return &m;
  return nullptr;
}

std::string optimize_method_names() {
  std::string names;
  for (const auto& m : optimize_methods()) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

// ---- the search ----

bool feasible(const std::vector<double>& constraints, const std::vector<double>& limits) {
  for (std::size_t k = 0; k < limits.size(); ++k)
    if (!(constraints[k] <= limits[k] + kFeasibleSlack * std::abs(limits[k]))) return false;
  return true;
}

std::vector<std::size_t> non_dominated(const std::vector<std::pair<double, double>>& points) {
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return points[a] < points[b]; });
  // By increasing f1 (then f2): a point is kept when its f2 is below every kept one's.
  std::vector<std::size_t> front;
  for (std::size_t i : order)
    if (front.empty() || points[i].second < points[front.back()].second) front.push_back(i);
  return front;
}

OptimizeResult optimize_designs(const std::vector<OptimizeVariable>& variables, std::size_t choices,
                                std::size_t objectives, const std::vector<double>& limits,
                                const OptimizeOptions& options, const DesignEvaluator& evaluate) {
  const OptimizeMethod* method = find_optimize_method(options.method);
  if (!method) throw InputError("method \"" + options.method + "\": expected one of " + optimize_method_names());
  OptimizeResult result;
  std::map<std::pair<std::size_t, std::vector<double>>, std::size_t> memo;
  Search s(variables, limits, evaluate, options, result, memo);
  for (std::size_t choice = 0; choice < choices; ++choice) {
    s.choice = choice;
    s.eps.reset();
    if (variables.empty()) {  // a placement alone: nothing to optimise
      s.stage = "enumeration";
      s.calls = 0;
      s.seen.clear();
      s.design({});
      result.runs.push_back({choice, s.stage, s.seen.front(), 1, "enumerated"});
      continue;
    }
    s.stage = objectives == 1 ? "min" : "min f1";
    s.minimise = 0;
    optimise(s, *method);
    if (objectives == 1) continue;
    const Evaluation first = result.evaluations[result.runs.back().best];
    s.stage = "min f2";
    s.minimise = 1;
    optimise(s, *method);
    const Evaluation second = result.evaluations[result.runs.back().best];
    // f1 subject to f2 <= eps, eps between the f2 of the two optima.
    const double hi = first.values.objectives[1], lo = second.values.objectives[1];
    s.minimise = 0;
    s.eps_scale = hi > lo ? hi - lo : 1.0;
    for (std::size_t k = 1; k + 1 < options.pareto_points && hi > lo; ++k) {
      s.eps = hi - (hi - lo) * static_cast<double>(k) / static_cast<double>(options.pareto_points - 1);
      s.stage = "eps " + std::to_string(k) + "/" + std::to_string(options.pareto_points - 2);
      optimise(s, *method);
    }
    s.eps.reset();
  }
  if (result.evaluations.empty()) return result;
  if (objectives == 1) {
    result.best = overall_best(result, limits);
    return result;
  }
  std::vector<std::size_t> candidates;
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < result.evaluations.size(); ++i)
    if (result.evaluations[i].feasible) {
      candidates.push_back(i);
      points.emplace_back(result.evaluations[i].values.objectives[0], result.evaluations[i].values.objectives[1]);
    }
  for (std::size_t i : non_dominated(points)) result.pareto.push_back(candidates[i]);
  result.best = result.pareto.empty() ? overall_best(result, limits) : result.pareto.front();
  return result;
}

}  // namespace adjoin
