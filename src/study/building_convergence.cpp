#include "building_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every floor's displacement at every `stride`-th grid point: the coarsest grid of the ladder.
class CoarseFloors final : public StructureObserver {
 public:
  explicit CoarseFloors(std::size_t stride) : stride_(stride) {}
  void begin(const structure::Structure&, const StructureSolverOptions&) override { count_ = 0; x.clear(); }
  void observe(const StructureState& s) override {
    if (count_++ % stride_ == 0) x.push_back(s.x);
  }
  std::vector<Eigen::VectorXd> x;

 private:
  std::size_t stride_, count_ = 0;
};

std::size_t stride_of(double coarse, double h) {
  const double ratio = coarse / h, rounded = std::round(ratio);
  if (std::abs(ratio - rounded) > 1e-9 * ratio)
    throw InputError("convergence steps must divide the largest one an integer number of times (" + std::to_string(coarse) +
                     " / " + std::to_string(h) + " is not an integer)");
  return static_cast<std::size_t>(rounded);
}

double relative(double value, double reference) {
  return reference != 0.0 ? std::abs(value - reference) / std::abs(reference) : std::abs(value);
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// Every reported quantity of a building run, by name, its value (or instant) as reported.
std::vector<QuantityError> reported_quantities(const RunSpec& spec, const Report& r) {
  std::vector<QuantityError> out;
  auto value = [&](const std::string& name, double v) { out.push_back({name, false, v, kNaN}); };
  auto instant = [&](const std::string& name, double t) { out.push_back({name, true, t, kNaN}); };
  for (const auto& p : r.peaks) {
    value("peak " + p.channel, p.peak.max_abs);
    const auto channel = structure::find_channel(spec.structure, p.channel);
    if (channel && structure::info(channel->quantity).peak == structure::PeakRule::refined)
      instant("t peak " + p.channel, p.peak.t);
  }
  for (std::size_t l = 0; l < r.links.size(); ++l) {
    const std::string link = "link" + std::to_string(l + 1);
    value(link + " force_max", r.links[l].force_max);
    value(link + " stroke_max", r.links[l].stroke_max);
    if (spec.structure.links[l].type == structure::LinkType::friction) {
      value(link + " energy", r.links[l].friction_energy);
      for (std::size_t i = 0; i < r.links[l].switch_times.size(); ++i)
        instant(link + " switch " + std::to_string(i + 1), r.links[l].switch_times[i]);
    }
  }
  for (std::size_t k = 0; k < r.contacts.size(); ++k) {
    const std::string pair = "contact" + std::to_string(k + 1);
    value(pair + " min gap", r.contacts[k].min_gap);
    instant(pair + " t min gap", r.contacts[k].t_min_gap);
  }
  if (r.collapse) instant("collapse t", r.collapse->t);  // SPEC §7: the located crossing
  return out;
}

bool same_switches(const Report& a, const Report& b) {
  for (std::size_t l = 0; l < a.links.size() && l < b.links.size(); ++l)
    if (a.links[l].switch_times.size() != b.links[l].switch_times.size()) return false;
  return true;
}

bool is_switch(const std::string& name) { return name.find(" switch ") != std::string::npos; }

}  // namespace

ConvergenceResult detail::building_convergence(const RunSpec& given, const ConvergenceOptions& options) {
  if (options.schemes.size() > 1) throw InputError("a building takes one scheme, implicit or implicit-damped");
  RunSpec spec = given;
  for (Scheme scheme : options.schemes) {
    if (scheme != Scheme::implicit && scheme != Scheme::implicit_damped)
      throw InputError(to_string(scheme) + ": a building runs the structure step, implicit or implicit-damped; the other "
                       "schemes are the two-block system's");
    spec.solver = with_scheme(spec.solver, scheme);
    spec.solver.restart = scheme == Scheme::implicit ? StructureSolverOptions::Restart::automatic
                                                      : StructureSolverOptions::Restart::always;
  }
  std::vector<double> steps = options.steps;
  if (steps.empty())
    for (double f : {4.0, 2.0, 1.0, 0.5, 0.25}) steps.push_back(spec.solver.h * f);
  std::sort(steps.rbegin(), steps.rend());
  const double coarse = steps.front(), finest = steps.back();
  for (double h : steps) stride_of(coarse, h);

  auto with = [&](HistoryEngine engine, double h) {
    RunSpec s = spec;
    s.solver.history = engine;
    s.solver.h = h;
    s.output.spectra.reset();  // spectra are not compared; they cost a history per signal
    return s;
  };

  // ---- the reference: a finer run ----
  const double h_ref = finest / options.reference_factor;
  const bool fft = std::find(options.engines.begin(), options.engines.end(), HistoryEngine::fft) != options.engines.end();
  const HistoryEngine ref_engine = fft || options.engines.size() > 1 ? HistoryEngine::fft : options.engines.front();
  CoarseFloors ref_grid(stride_of(coarse, h_ref));
  const Report ref = run(with(ref_engine, h_ref), {&ref_grid});
  double scale = 0.0;
  for (const auto& x : ref_grid.x) scale = std::max(scale, x.cwiseAbs().maxCoeff());
  if (scale == 0.0) scale = 1.0;
  const std::vector<QuantityError> theirs = reported_quantities(spec, ref);

  ConvergenceResult result;
  result.reference = "a finer run: " + std::string(scheme_name(spec.solver)) + "/" + to_string(ref_engine) + " at h = " + number(h_ref) + " s";
  for (HistoryEngine engine : options.engines) {
    double previous = kNaN;
    std::vector<QuantityError> previous_quantities;
    for (double h : steps) {
      ConvergenceRow row;
      row.scheme = scheme_name(spec.solver);
      row.history = to_string(engine);
      row.h = h;
      row.peak_x1 = row.min_gap = row.friction = kNaN;  // two-block summaries
      CoarseFloors grid(stride_of(coarse, h));
      try {
        const RunSpec s = with(engine, h);
        row.steps = s.solver.steps();
        const Report r = run(s, {&grid});
        row.wall_seconds = r.solver.wall_seconds;
        double e = 0.0;
        for (std::size_t j = 0; j < grid.x.size() && j < ref_grid.x.size(); ++j)
          e = std::max(e, (grid.x[j] - ref_grid.x[j]).cwiseAbs().maxCoeff());
        row.error = e / scale;
        row.order = std::isnan(previous) ? kNaN : std::log(previous / row.error) / std::log(result.rows.back().h / h);
        previous = row.error;
        row.switches_differ = !same_switches(r, ref);
        const auto mine = reported_quantities(spec, r);
        for (const auto& m : mine) {
          if (row.switches_differ && is_switch(m.name)) continue;
          const auto match = std::find_if(theirs.begin(), theirs.end(), [&](const QuantityError& q) { return q.name == m.name; });
          if (match == theirs.end()) continue;
          QuantityError q = m;
          q.error = q.instant ? std::abs(m.error - match->error) : relative(m.error, match->error);
          for (const auto& p : previous_quantities)
            if (p.name == q.name && p.error > 0.0 && q.error > 0.0)
              q.order = std::log(p.error / q.error) / std::log(result.rows.back().h / h);
          row.quantities.push_back(q);
        }
        // The balance's residual, relative to the input: an error in itself.
        QuantityError residual{"energy residual", false,
                               r.energy.input != 0.0 ? std::abs(r.energy.residual / r.energy.input) : std::abs(r.energy.residual),
                               kNaN};
        for (const auto& p : previous_quantities)
          if (p.name == residual.name && p.error > 0.0 && residual.error > 0.0)
            residual.order = std::log(p.error / residual.error) / std::log(result.rows.back().h / h);
        row.quantities.push_back(residual);
        previous_quantities = row.quantities;
      } catch (const NumericalError& e) {
        row.failed = true;
        row.message = e.what();
        row.error = row.order = kNaN;
        previous = kNaN;
        previous_quantities.clear();
      }
      result.rows.push_back(row);
    }
  }
  return result;
}

}  // namespace adjoin
