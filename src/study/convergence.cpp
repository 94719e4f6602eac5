#include "adjoin/study/convergence.hpp"

#include "building_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/study/linear_reference.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Keeps the displacements at every `stride`-th grid point: the coarsest grid of the ladder.
class CoarseGrid final : public Observer {
 public:
  explicit CoarseGrid(std::size_t stride) : stride_(stride) {}
  void begin(const RunInfo&) override { count_ = 0; t.clear(); x1.clear(); x2.clear(); all_stuck = true; max_q = 0.0; }
  void observe(const State& s) override {
    if (s.phase != Phase::stick) all_stuck = false;
    max_q = std::max(max_q, std::abs(s.q));
    if (count_++ % stride_ != 0) return;
    t.push_back(s.t);
    x1.push_back(s.x1);
    x2.push_back(s.x2);
  }
  std::vector<double> t, x1, x2;
  bool all_stuck = true;
  double max_q = 0.0;

 private:
  std::size_t stride_;
  std::size_t count_ = 0;
};

// Every reported quantity of a run, by name (see the header).
std::vector<QuantityError> reported_quantities(const Report& r) {
  std::vector<QuantityError> out;
  auto value = [&](const std::string& name, double v) { out.push_back({name, false, v, kNaN}); };
  auto instant = [&](const std::string& name, double t) { out.push_back({name, true, t, kNaN}); };
  const std::pair<const char*, const Peak*> peaks[] = {{"x1", &r.two_block->peaks.x1},   {"x2", &r.two_block->peaks.x2}, {"stroke", &r.two_block->peaks.drift},
                                                       {"f1", &r.two_block->peaks.f1},   {"f2", &r.two_block->peaks.f2}, {"q", &r.two_block->peaks.q}};
  for (const auto& [name, p] : peaks) {
    value(std::string("peak ") + name, p->max_abs);
    instant(std::string("t peak ") + name, p->t);
  }
  if (r.two_block->pounding) {
    value("min gap", r.two_block->pounding->min_gap);
    instant("t min gap", r.two_block->pounding->t_min_gap);
  }
  if (r.two_block->energy) value("friction", r.two_block->energy->friction);
  value("final q", r.two_block->final.q);
  for (std::size_t i = 1; i < r.two_block->phases.size(); ++i) instant("switch " + std::to_string(i), r.two_block->phases[i].t_start);
  return out;
}

bool same_phases(const Report& a, const Report& b) {
  if (a.two_block->phases.size() != b.two_block->phases.size()) return false;
  for (std::size_t i = 0; i < a.two_block->phases.size(); ++i)
    if (a.two_block->phases[i].state != b.two_block->phases[i].state) return false;
  return true;
}

struct Reference {
  std::string description;
  std::vector<double> x1, x2;  // on the coarsest grid
  double scale = 1.0;          // max |x_ref|
  bool has_summary = false;
  double peak_x1 = 0.0, min_gap = 0.0, friction = 0.0;
  Report report;  // the finer run (has_summary)
};

std::size_t stride_of(double coarse, double h) {
  const double ratio = coarse / h;
  const double rounded = std::round(ratio);
  if (std::abs(ratio - rounded) > 1e-9 * ratio)
    throw InputError("convergence steps must divide the largest one an integer number of times (" +
                     std::to_string(coarse) + " / " + std::to_string(h) + " is not an integer)");
  return static_cast<std::size_t>(rounded);
}

double relative(double value, double reference) {
  return std::abs(value - reference) / std::max(std::abs(reference), 1e-300);
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace

bool ConvergenceOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) { if (error) *error = m; return false; };
  for (double h : steps)
    if (!(std::isfinite(h) && h > 0.0)) return fail("every step must be a positive number (got " + number(h) + ")");
  if (!(reference_factor >= 2.0)) return fail("the reference run must be at least 2 times finer");
  return true;
}

ConvergenceResult run_convergence(const RunSpec& scene, const ConvergenceOptions& asked) {
  std::string error;
  if (!asked.IsValid(&error)) throw InputError(error);
  ConvergenceOptions options = asked;
  if (options.engines.empty()) options.engines = {scene.two_block() ? HistoryEngine::direct : HistoryEngine::fft};
  if (!scene.two_block()) return detail::building_convergence(scene, options);
  if (options.schemes.empty()) options.schemes = {Scheme::paper, Scheme::implicit_gl, Scheme::implicit};
  std::vector<double> steps = options.steps;
  if (steps.empty())
    for (double f : {4.0, 2.0, 1.0, 0.5, 0.25}) steps.push_back(scene.solver.h * f);
  std::sort(steps.rbegin(), steps.rend());
  const double coarse = steps.front(), finest = steps.back();
  for (double h : steps) stride_of(coarse, h);

  auto with = [&](Scheme scheme, HistoryEngine engine, double h) {
    RunSpec s = scene;
    s.solver.scheme = scheme;
    s.solver.history = engine;
    s.solver.h = h;
    return s;
  };

  // ---- the reference ----
  Reference ref;
  const auto* sine = dynamic_cast<const DecayingSine*>(scene.ground.get());
  bool analytic = false;
  if (sine) {
    bool stuck = false;
    if (scene.model->mu > 0.0) {
      // Linear only if the damper never slips: ask the best scheme at the finest step.
      CoarseGrid probe(1);
      run(with(Scheme::implicit, HistoryEngine::direct, finest), {nullptr, &probe});
      stuck = probe.all_stuck;
    }
    if (scene.model->mu == 0.0 || stuck) {
      const LinearReference exact(*scene.model, sine->u0(), sine->omega(), sine->k(), stuck);
      const std::size_t n = static_cast<std::size_t>(std::ceil(scene.solver.t_end / coarse * (1 - 1e-12))) + 1;
      analytic = true;
      for (std::size_t j = 0; j < n; ++j) {
        const LinearResponse r = exact.at(static_cast<double>(j) * coarse);
        if (stuck && std::abs(r.q) >= scene.model->mu) analytic = false;  // the exact solution slips
        ref.x1.push_back(r.x1);
        ref.x2.push_back(r.x2);
      }
      ref.description = stuck ? "analytic: exact solution with the damper stuck throughout (Laplace inversion)"
                              : "analytic: exact solution without damper (Laplace inversion)";
    }
  }
  if (!analytic) {
    const double h_ref = finest / options.reference_factor;
    CoarseGrid grid(stride_of(coarse, h_ref));
    RunSpec s = with(Scheme::implicit, HistoryEngine::fft, h_ref);
    Report r;
    try {
      r = run(s, {nullptr, &grid});
    } catch (const InputError&) {  // no fft engine in this build: fall back to direct
      s.solver.history = HistoryEngine::direct;
      r = run(s, {nullptr, &grid});
    }
    ref.x1 = grid.x1;
    ref.x2 = grid.x2;
    ref.has_summary = true;
    ref.peak_x1 = r.two_block->peaks.x1.max_abs;
    ref.min_gap = r.two_block->pounding->min_gap;
    ref.friction = r.two_block->energy->friction;
    ref.report = r;
    // In the scene's time unit (seconds for an SI scene), as the ladder's steps are printed.
    ref.description = "a finer run: implicit/" + to_string(s.solver.history) + " at h = " + number(h_ref * scene.scales.time) +
                      (scene.scales.si ? " s" : "");
  }
  ref.scale = 0.0;
  for (std::size_t j = 0; j < ref.x1.size(); ++j) ref.scale = std::max({ref.scale, std::abs(ref.x1[j]), std::abs(ref.x2[j])});
  if (ref.scale == 0.0) ref.scale = 1.0;

  // ---- the ladders ----
  ConvergenceResult result;
  result.reference = ref.description;
  for (Scheme scheme : options.schemes) {
    for (HistoryEngine engine : options.engines) {
      double previous = kNaN;
      std::vector<QuantityError> previous_quantities;
      for (double h : steps) {
        ConvergenceRow row;
        row.scheme = to_string(scheme);
        row.history = to_string(engine);
        row.h = h;
        CoarseGrid grid(stride_of(coarse, h));
        try {
          const RunSpec s = with(scheme, engine, h);
          row.steps = s.solver.steps();
          const Report r = run(s, {nullptr, &grid});
          row.wall_seconds = r.solver.wall_seconds;
          double e = 0.0;
          const std::size_t n = std::min(grid.x1.size(), ref.x1.size());
          for (std::size_t j = 0; j < n; ++j)
            e = std::max({e, std::abs(grid.x1[j] - ref.x1[j]), std::abs(grid.x2[j] - ref.x2[j])});
          row.error = e / ref.scale;
          row.order = std::isnan(previous) ? kNaN : std::log(previous / row.error) / std::log(result.rows.back().h / h);
          previous = row.error;
          row.peak_x1 = ref.has_summary ? relative(r.two_block->peaks.x1.max_abs, ref.peak_x1) : kNaN;
          row.min_gap = ref.has_summary ? relative(r.two_block->pounding->min_gap, ref.min_gap) : kNaN;
          row.friction = ref.has_summary && ref.friction > 0.0 ? relative(r.two_block->energy->friction, ref.friction) : kNaN;
          if (ref.has_summary) {
            row.switches_differ = !same_phases(r, ref.report);
            const auto mine = reported_quantities(r), theirs = reported_quantities(ref.report);
            for (std::size_t i = 0; i < mine.size() && i < theirs.size(); ++i) {
              if (mine[i].name != theirs[i].name || (row.switches_differ && mine[i].name.rfind("switch", 0) == 0)) continue;
              QuantityError q = mine[i];
              q.error = q.instant ? std::abs(mine[i].error - theirs[i].error) : relative(mine[i].error, theirs[i].error);
              for (const auto& p : previous_quantities)
                if (p.name == q.name && p.error > 0.0 && q.error > 0.0)
                  q.order = std::log(p.error / q.error) / std::log(result.rows.back().h / h);
              row.quantities.push_back(q);
            }
            previous_quantities = row.quantities;
          }
        } catch (const NumericalError& e) {
          row.failed = true;
          row.message = e.what();
          row.error = row.order = row.peak_x1 = row.min_gap = row.friction = kNaN;
          previous = kNaN;
          previous_quantities.clear();
        }
        result.rows.push_back(row);
      }
    }
  }
  return result;
}

}  // namespace adjoin
