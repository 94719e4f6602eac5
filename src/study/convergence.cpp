#include "adjoin/study/convergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/structure/link_kinds.hpp"
#include "adjoin/study/linear_reference.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every degree of freedom's displacement at every `stride`-th grid point: the coarsest grid of
// the ladder (a structure's floors; a two-block run's A.x1, B.x1). Also whether link 1 (a
// two-block run's damper) stuck throughout, and its largest |force| (the analytic reference's
// test).
class CoarseGrid final : public StructureObserver {
 public:
  explicit CoarseGrid(std::size_t stride) : stride_(stride) {}
  void begin(const structure::Structure& s, const StructureSolverOptions&) override {
    start();
    link_ = !s.links.empty();
  }
  void observe(const StructureState& s) override {
    if (link_) {
      if (s.link_phase[0] != Phase::stick) all_stuck = false;
      max_q = std::max(max_q, std::abs(s.link_force[0]));
    }
    if (count_++ % stride_ == 0) x.push_back(s.x);
  }
  std::vector<Eigen::VectorXd> x;
  bool all_stuck = true;
  double max_q = 0.0;

 private:
  void start() {
    count_ = 0;
    x.clear();
    all_stuck = true;
    max_q = 0.0;
  }
  std::size_t stride_;
  std::size_t count_ = 0;
  bool link_ = false;
};

// ---- the reported quantities, by the scene's presentation ----

// A two-block run's: its 1 + 1 structure's refined peaks, labelled by channel (io presents
// them under SPEC §3's names: io/two_block_names.hpp two_block_quantity_name), the contact
// pair's smallest gap, the friction link's work and last force, the phases' switches.
std::vector<QuantityError> two_block_quantities(const RunSpec& spec, const Report& r) {
  std::vector<QuantityError> out;
  auto value = [&](const std::string& name, double v) { out.push_back({name, false, v, kNaN}); };
  auto instant = [&](const std::string& name, double t) { out.push_back({name, true, t, kNaN}); };
  for (const char* channel : {"A.x1", "B.x1", "link1.stroke", "A.shear1", "B.shear1", "link1.force"}) {
    const Peak p = r.peak(channel);
    value(std::string("peak ") + channel, p.max_abs);
    instant(std::string("t peak ") + channel, p.t);
  }
  if (spec.output.pounding) {
    value("min gap", r.contacts.at(0).min_gap);
    instant("t min gap", r.contacts.at(0).t_min_gap);
  }
  if (spec.output.energy) value("friction", r.link_energy(0));
  value("final link1.force", r.last_value("link1.force"));
  for (std::size_t i = 1; i < r.phases.size(); ++i) instant("switch " + std::to_string(i), r.phases[i].t_start);
  return out;
}

// A structure run's, by its channels, links and contact pairs.
std::vector<QuantityError> structure_quantities(const RunSpec& spec, const Report& r) {
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
    if (structure::kind_of(spec.structure.links[l]).family(spec.structure.links[l]) == structure::LinkFamily::friction) {
      value(link + " energy", r.links[l].energy);
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

std::vector<QuantityError> reported_quantities(const RunSpec& spec, const Report& r) {
  return spec.two_block() ? two_block_quantities(spec, r) : structure_quantities(spec, r);
}

bool is_switch(const std::string& name) { return name.rfind("switch ", 0) == 0 || name.find(" switch ") != std::string::npos; }

// Whether a run switched as the reference did: a two-block run's sequence of phases, each
// friction link's number of switches.
bool same_switches(const RunSpec& spec, const Report& a, const Report& b) {
  if (spec.two_block()) {
    const auto &pa = a.phases, &pb = b.phases;
    if (pa.size() != pb.size()) return false;
    for (std::size_t i = 0; i < pa.size(); ++i)
      if (pa[i].state != pb[i].state) return false;
    return true;
  }
  for (std::size_t l = 0; l < a.links.size() && l < b.links.size(); ++l)
    if (a.links[l].switch_times.size() != b.links[l].switch_times.size()) return false;
  return true;
}

std::size_t stride_of(double coarse, double h) {
  const double ratio = coarse / h;
  const double rounded = std::round(ratio);
  if (std::abs(ratio - rounded) > 1e-9 * ratio)
    throw InputError("convergence steps must divide the largest one an integer number of times (" +
                     std::to_string(coarse) + " / " + std::to_string(h) + " is not an integer)");
  return static_cast<std::size_t>(rounded);
}

// Relative error; absolute against a zero reference.
double relative(double value, double reference) {
  return reference != 0.0 ? std::abs(value - reference) / std::abs(reference) : std::abs(value);
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// The order observed between the previous rung's error of the same quantity and this one's.
void set_order(QuantityError& q, const std::vector<QuantityError>& previous, double h_previous, double h) {
  for (const auto& p : previous)
    if (p.name == q.name && p.error > 0.0 && q.error > 0.0) q.order = std::log(p.error / q.error) / std::log(h_previous / h);
}

struct Reference {
  std::string description;
  std::vector<Eigen::VectorXd> x;  // on the coarsest grid
  double scale = 1.0;              // max |x_ref|
  std::optional<Report> report;    // a finer run's (not the analytic solution's)
};

// The exact solution on the coarsest grid, when a two-block scene's problem is linear under the
// decaying sine: no damper, or one that the best scheme's finest run (`finest_run`) shows stuck
// throughout (then |q| < mu is checked on the exact solution too). Empty otherwise.
std::optional<Reference> analytic_reference(const RunSpec& scene, double coarse, const RunSpec& finest_run) {
  const auto* sine = dynamic_cast<const DecayingSine*>(scene.ground.get());
  if (!scene.two_block() || !sine) return std::nullopt;
  const Model model = two_block_model(scene);
  bool stuck = false;
  if (model.mu > 0.0) {
    CoarseGrid probe(1);
    run(finest_run, {&probe});
    stuck = probe.all_stuck;
  }
  if (model.mu != 0.0 && !stuck) return std::nullopt;
  const LinearReference exact(model, sine->u0(), sine->omega(), sine->k(), stuck);
  const std::size_t n = static_cast<std::size_t>(std::ceil(scene.solver.t_end / coarse * (1 - 1e-12))) + 1;
  Reference ref;
  for (std::size_t j = 0; j < n; ++j) {
    const LinearResponse r = exact.at(static_cast<double>(j) * coarse);
    if (stuck && std::abs(r.link_force) >= model.mu) return std::nullopt;  // the exact solution slips
    ref.x.push_back(Eigen::Vector2d(r.x[0], r.x[1]));
  }
  ref.description = stuck ? "analytic: exact solution with the damper stuck throughout (Laplace inversion)"
                          : "analytic: exact solution without damper (Laplace inversion)";
  return ref;
}

}  // namespace

bool ConvergenceOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) { if (error) *error = m; return false; };
  for (double h : steps)
    if (!(std::isfinite(h) && h > 0.0)) return fail("every step must be a positive number (got " + number(h) + ")");
  if (!(reference_factor >= 2.0)) return fail("the reference run must be at least 2 times finer");
  return true;
}

ConvergenceResult run_convergence(const RunSpec& given, const ConvergenceOptions& asked) {
  std::string error;
  if (!asked.IsValid(&error)) throw InputError(error);
  ConvergenceOptions options = asked;
  RunSpec scene = given;
  const bool two_block = scene.two_block();
  if (options.engines.empty()) options.engines = {two_block ? HistoryEngine::direct : HistoryEngine::soe};
  if (two_block && options.schemes.empty()) options.schemes = {Scheme::paper, Scheme::implicit_gl, Scheme::implicit};
  if (!two_block) {
    // A structure runs one scheme: the structure step with one of its two restart rules.
    if (options.schemes.size() > 1) throw InputError("a building takes one scheme, implicit or implicit-damped");
    for (Scheme scheme : options.schemes) {
      if (scheme != Scheme::implicit && scheme != Scheme::implicit_damped)
        throw InputError(to_string(scheme) + ": a building runs the structure step, implicit or implicit-damped; the other "
                         "schemes are the two-block system's");
      scene.solver = with_scheme(scene.solver, scheme);
      scene.solver.restart = scheme == Scheme::implicit ? StructureSolverOptions::Restart::automatic
                                                        : StructureSolverOptions::Restart::always;
    }
    if (options.schemes.empty()) options.schemes = {scene.solver.scheme};
  }
  std::vector<double> steps = options.steps;
  if (steps.empty())
    for (double f : {4.0, 2.0, 1.0, 0.5, 0.25}) steps.push_back(scene.solver.h * f);
  std::sort(steps.rbegin(), steps.rend());
  const double coarse = steps.front(), finest = steps.back();
  for (double h : steps) stride_of(coarse, h);

  // A run of the ladder; spectra are not compared (they cost a history per signal).
  auto with = [&](Scheme scheme, HistoryEngine engine, double h) {
    RunSpec s = scene;
    if (two_block) s.solver.scheme = scheme;
    s.solver.history = engine;
    s.solver.h = h;
    s.output.spectra.reset();
    return s;
  };
  // The scheme's name in the table: a structure's says its restart rule.
  auto scheme_text = [&](Scheme scheme) { return two_block ? to_string(scheme) : std::string(scheme_name(scene.solver)); };

  // ---- the reference: the exact solution, else a finer run of the best scheme ----
  Reference ref;
  if (auto exact = analytic_reference(scene, coarse, with(Scheme::implicit, HistoryEngine::direct, finest))) {
    ref = std::move(*exact);
  } else {
    const double h_ref = finest / options.reference_factor;
    // A two-block scene's best scheme is implicit with the fft history (direct in a build
    // without fft); a structure's is its own step, fft unless only direct was asked for.
    const bool fft = std::find(options.engines.begin(), options.engines.end(), HistoryEngine::fft) != options.engines.end();
    const Scheme ref_scheme = two_block ? Scheme::implicit : options.schemes.front();
    const HistoryEngine ref_engine =
        two_block || fft || options.engines.size() > 1 ? HistoryEngine::fft : options.engines.front();
    CoarseGrid grid(stride_of(coarse, h_ref));
    RunSpec s = with(ref_scheme, ref_engine, h_ref);
    const auto observers = [&] { return RunObservers{&grid}; };
    try {
      ref.report = run(s, observers());
    } catch (const InputError&) {  // no fft engine in this build: fall back to direct
      if (!two_block) throw;
      s.solver.history = HistoryEngine::direct;
      ref.report = run(s, observers());
    }
    ref.x = grid.x;
    // In the scene's time unit (seconds for an SI scene), as the ladder's steps are printed.
    ref.description = "a finer run: " + scheme_text(ref_scheme) + "/" + to_string(s.solver.history) +
                      " at h = " + number(h_ref * scene.scales.time) + (scene.scales.si ? " s" : "");
  }
  ref.scale = 0.0;
  for (const auto& x : ref.x) ref.scale = std::max(ref.scale, x.cwiseAbs().maxCoeff());
  if (ref.scale == 0.0) ref.scale = 1.0;
  const std::vector<QuantityError> theirs = ref.report ? reported_quantities(scene, *ref.report) : std::vector<QuantityError>{};

  // ---- the ladders ----
  ConvergenceResult result;
  result.reference = ref.description;
  for (Scheme scheme : options.schemes) {
    for (HistoryEngine engine : options.engines) {
      double previous = kNaN;
      std::vector<QuantityError> previous_quantities;
      for (double h : steps) {
        ConvergenceRow row;
        row.scheme = scheme_text(scheme);
        row.history = to_string(engine);
        row.h = h;
        row.peak_a1 = row.min_gap = row.friction = kNaN;
        CoarseGrid grid(stride_of(coarse, h));
        try {
          const RunSpec s = with(scheme, engine, h);
          row.steps = s.solver.steps();
          const Report r = run(s, RunObservers{&grid});
          row.wall_seconds = r.solver.wall_seconds;
          double e = 0.0;
          for (std::size_t j = 0; j < grid.x.size() && j < ref.x.size(); ++j)
            e = std::max(e, (grid.x[j] - ref.x[j]).cwiseAbs().maxCoeff());
          row.error = e / ref.scale;
          const double h_previous = result.rows.empty() ? h : result.rows.back().h;
          row.order = std::isnan(previous) ? kNaN : std::log(previous / row.error) / std::log(h_previous / h);
          previous = row.error;
          if (ref.report) {
            if (two_block) {  // the summary's three values under SPEC §3's names
              const Report& fine = *ref.report;
              row.peak_a1 = relative(r.peak("A.x1").max_abs, fine.peak("A.x1").max_abs);
              row.min_gap = relative(r.contacts.at(0).min_gap, fine.contacts.at(0).min_gap);
              row.friction = fine.link_energy(0) > 0.0 ? relative(r.link_energy(0), fine.link_energy(0)) : kNaN;
            }
            row.switches_differ = !same_switches(s, r, *ref.report);
            for (const auto& m : reported_quantities(s, r)) {
              if (row.switches_differ && is_switch(m.name)) continue;
              const auto match = std::find_if(theirs.begin(), theirs.end(), [&](const QuantityError& q) { return q.name == m.name; });
              if (match == theirs.end()) continue;
              QuantityError q = m;
              q.error = q.instant ? std::abs(m.error - match->error) : relative(m.error, match->error);
              set_order(q, previous_quantities, h_previous, h);
              row.quantities.push_back(q);
            }
            if (!two_block) {
              // The balance's residual, relative to the input: an error in itself.
              QuantityError residual{"energy residual", false,
                                     r.energy.input != 0.0 ? std::abs(r.energy.residual / r.energy.input) : std::abs(r.energy.residual),
                                     kNaN};
              set_order(residual, previous_quantities, h_previous, h);
              row.quantities.push_back(residual);
            }
            previous_quantities = row.quantities;
          }
        } catch (const NumericalError& e) {
          row.failed = true;
          row.message = e.what();
          row.error = row.order = row.peak_a1 = row.min_gap = row.friction = kNaN;
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
