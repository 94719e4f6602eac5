#include "adjoin/study/builder.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/ground/processing.hpp"
#include "adjoin/ground/record_motion.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/structure/modal.hpp"

namespace adjoin {
namespace {

std::string number(double v, int precision = 6) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

// The buildings' fundamental periods: the shortest, and the longest period of the structure
// (a building's, or the coupled system's with the links free) [s].
struct Periods {
  double shortest_fundamental = INFINITY, longest = 0.0;
};
Periods periods_of(const structure::Structure& structure) {
  // The elastic periods (K0): P-Delta can make a tangent's period infinite (a diverging storey).
  structure::Structure s = structure;
  s.a.p_delta = false;
  if (s.b) s.b->p_delta = false;
  Periods p;
  for (const structure::Building* b : {&s.a, s.b ? &*s.b : nullptr}) {
    if (!b) continue;
    const double fundamental = structure::building_modes(*b).periods[0];
    p.longest = std::max(p.longest, fundamental);
    p.shortest_fundamental = std::min(p.shortest_fundamental, fundamental);
  }
  if (s.b) p.longest = std::max(p.longest, structure::coupled_modes(s).periods_free[0]);
  return p;
}

}  // namespace

// ---- grounds ----

std::shared_ptr<const GroundMotion> record_ground(const std::filesystem::path& file, std::optional<double> scale_pga,
                                                  const RecordFormat& format) {
  Record record = read_record(file, format);  // InputError names the file and line
  Processing processing;
  // The scale is in g; processing takes the target in m/s^2 and checks it against the record.
  if (scale_pga) processing.target_pga = *scale_pga * kStandardGravity;
  if (const auto problem = check_processing(processing, record, 0.8 * physical_memory_bytes()))
    throw FieldError("ground.scale_pga", problem->message + " (record " + file.string() + ")");
  record = process(record, processing);  // as a scene's record is, processed or not
  // A building run's ground: times in s (time scale 1 s), a_g in g.
  return std::make_shared<RecordMotion>(std::move(record), 1.0, kStandardGravity);
}

std::shared_ptr<const GroundMotion> decaying_sine_ground(double u0, double omega, double k) {
  for (auto [field, value] : {std::pair{"ground.u0", u0}, {"ground.omega", omega}, {"ground.k", k}})
    if (!std::isfinite(value)) throw FieldError(field, "must be a finite number");
  if (!(k >= 0.0)) throw FieldError("ground.k", number(k, 12) + " must be zero or positive (decay rate)");
  // a_g in g: the displacement amplitude in units of g x 1 s^2.
  return std::make_shared<DecayingSine>(u0 / kStandardGravity, omega, k,
                                        "decaying-sine u0=" + number(u0, 12) + " m omega=" + number(omega, 12) +
                                            " rad/s k=" + number(k, 12) + " 1/s");
}

// ---- the run-level rules ----

std::string tolerance_rule(double tolerance, bool given) {
  if (given) return "chosen for solver.tolerance = " + number(tolerance, 12);
  return "chosen for solver.tolerance = " + number(tolerance) + " (the default: 3 significant digits of the peaks)";
}

Chosen default_building_step(const structure::Structure& s, double record_dt, const std::string& tolerance_rule) {
  // The ladder's first rung, and the step of a sweep's rows, which do not climb the ladder.
  Chosen h;
  h.value = periods_of(s).shortest_fundamental / 200.0;
  if (record_dt > 0.0) h.value = std::min(h.value, record_dt);
  h.rule = tolerance_rule + ", from h = the shortest fundamental period / 200" +
           std::string(record_dt > 0.0 ? ", no coarser than the record's dt" : "") + " = " + number(h.value) + " s";
  return h;
}

Chosen default_building_horizon(const structure::Structure& s, double duration) {
  const double longest = periods_of(s).longest;
  if (std::isfinite(duration)) {
    const double t_end = duration + 5.0 * longest;
    return {t_end, "the motion's duration + 5 x the longest period (" + number(longest) + " s) = " + number(t_end) + " s"};
  }
  const double t_end = 20.0 * longest;
  return {t_end, "20 x the longest period (" + number(longest) + " s) = " + number(t_end) + " s"};
}

// ---- a run ----

RunSpec building_run_spec(structure::Structure structure, std::shared_ptr<const GroundMotion> ground,
                                  const BuildingRunOptions& o) {
  if (!ground) throw FieldError("ground", "missing: give the run a ground motion");
  if (o.h && o.tolerance) throw FieldError("solver.tolerance", "give solver.h or solver.tolerance, not both (the tolerance chooses the step)");
  if (o.tolerance && !(*o.tolerance >= 1e-12 && *o.tolerance <= 0.1))
    throw FieldError("solver.tolerance", number(*o.tolerance, 12) + " must lie in [1e-12, 0.1] (relative error of the reported peaks)");
  RunSpec spec;
  spec.name = o.name;
  spec.structure = std::move(structure);
  spec.scales = Scales::SI(1.0, 1.0);
  spec.ground = std::move(ground);
  spec.output = o.output;
  AccuracyOptions& a = spec.accuracy;
  a.error_estimate = o.error_estimate;
  const double dt = spec.ground->sample_interval();  // s
  if (o.h) {
    spec.solver.h = *o.h;
    a.h_rule = "given";
  } else {
    a.tolerance = o.tolerance.value_or(kBuildingDefaultTolerance);
    a.tolerance_given = o.tolerance.has_value();
    const Chosen h = default_building_step(spec.structure, dt, tolerance_rule(*a.tolerance, a.tolerance_given));
    spec.solver.h = h.value;
    a.h_rule = h.rule;
  }
  if (o.t_end) {
    spec.solver.t_end = *o.t_end;
    a.t_end_rule = "given";
  } else {
    const Chosen t_end = default_building_horizon(spec.structure, spec.ground->duration());
    spec.solver.t_end = t_end.value;
    a.t_end_rule = t_end.rule;
  }
  spec.solver.history = o.history;
  spec.solver.restart = o.restart;
  if (o.restart == StructureSolverOptions::Restart::always) spec.solver.scheme = Scheme::implicit_damped;
  std::string error;
  if (!spec.solver.IsValid(&error)) {
    // "solver.h must be ...": the field, then the problem.
    const bool named = error.rfind("solver.", 0) == 0;
    throw FieldError(named ? error.substr(0, error.find(' ')) : "solver", named ? error.substr(error.find(' ') + 1) : error);
  }
  if (dt > 0.0 && spec.solver.h > dt * (1 + 1e-9))
    spec.warnings.push_back("solver.h = " + number(spec.solver.h) + " s is coarser than the record's sampling interval " +
                            number(dt) + " s: the record's peaks between steps are not seen");
  return spec;
}

}  // namespace adjoin
