#include "adjoin/solver/simulate.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/two_block.hpp"
#include "schemes.hpp"

namespace adjoin {

double estimated_history_bytes(const SolverOptions& options, const Model& model) {
  // Per rod with memory and per step: direct sums keep the weights and the past values (2
  // doubles); the fft engine also keeps its blocks' spectra (measured about 57 bytes; 64
  // allowed). Elastic rods keep nothing; soe keeps a constant few kilobytes (in the 4096).
  const double per_rod_step = options.history == HistoryEngine::fft ? 64.0 : options.history == HistoryEngine::soe ? 0.0 : 16.0;
  const int rods = (model.rod1.elastic ? 0 : 1) + (model.rod2.elastic ? 0 : 1);
  return rods * per_rod_step * (static_cast<double>(options.steps()) + 2.0) + 4096.0;
}

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 0.0;
}

std::string memory_problem(double need_bytes, const std::string& what) {
  const double have = physical_memory_bytes();
  if (have <= 0.0 || need_bytes <= 0.8 * have) return "";
  char text[160];
  std::snprintf(text, sizeof text, "would need about %.3g GB of memory (", need_bytes / 1e9);
  std::string out = text + what;
  std::snprintf(text, sizeof text, "), more than the %.3g GB this machine can give (80 %% of %.3g GB)", 0.8 * have / 1e9,
                have / 1e9);
  return out + text;
}

namespace {

// The paper scheme's States as the 1 + 1 structure's StructureStates (simulate_as_structure):
// the damper as link 1 (its force, stroke, relative velocity, phase and switch), contact pair 1
// at gap0 (the paper scheme has no contact law: its force and work are 0).
class PaperAsStructure final : public Observer {
 public:
  PaperAsStructure(StructureObserver& inner, const SolverOptions& options, const Model& model)
      : inner_(inner), structure_(structure::two_block_structure(model)), gap0_(model.gap0) {
    options_.h = options.h;
    options_.t_end = options.t_end;
    options_.history = options.history;
    options_.history_tolerance = options.history_tolerance;
    options_.scheme = Scheme::paper;
    options_.locate_switches = false;  // the paper scheme decides its phases on the grid
    const Eigen::Index links = static_cast<Eigen::Index>(structure_.links.size());
    for (auto* v : {&state_.x, &state_.v, &state_.a_abs, &state_.storey_force}) v->setZero(2);
    for (auto* v : {&state_.link_force, &state_.link_stroke, &state_.link_velocity}) v->setZero(links);
    state_.link_phase.assign(static_cast<std::size_t>(links), Phase::stick);
    state_.link_switch.assign(static_cast<std::size_t>(links), 0.0);
    for (auto* v : {&state_.contact_gap, &state_.contact_force, &state_.contact_work, &state_.contact_dissipated})
      v->setZero(1);
  }
  void begin(const RunInfo&) override { inner_.begin(structure_, options_); }
  void observe(const State& s) override {
    StructureState& o = state_;
    o.t = s.t;
    o.ag = s.ag;
    o.x[0] = s.x1;
    o.x[1] = s.x2;
    o.v[0] = s.v1;
    o.v[1] = s.v2;
    o.a_abs[0] = s.a1;
    o.a_abs[1] = s.a2;
    o.storey_force[0] = s.f1;
    o.storey_force[1] = s.f2;
    if (o.link_force.size() == 1) {
      o.link_force[0] = s.q;
      o.link_stroke[0] = s.x1 - s.x2;
      o.link_velocity[0] = s.v1 - s.v2;
      o.link_phase[0] = s.phase;
      o.link_switch[0] = s.t_switch;
    }
    o.contact_gap[0] = gap0_ + s.x2 - s.x1;
    inner_.observe(o);
  }
  void impact(const Impact& i) override { inner_.impact(i); }
  void end() override { inner_.end(); }

 private:
  StructureObserver& inner_;
  structure::Structure structure_;
  StructureSolverOptions options_;
  StructureState state_;
  double gap0_ = 0.0;
};

// The checks and the summary's names every two-block run shares.
void check_run(const SolverOptions& options, const Model& model) {
  std::string error;
  if (!model.IsValid(&error) || !options.IsValid(&error)) throw InputError(error);

  if (options.scheme == Scheme::paper && model.contact.model != structure::ContactModel::none)
    throw InputError("solver.scheme = \"paper\": a contact law (model.contact) runs on the implicit schemes only; use solver.scheme = \"implicit\"");
  if (options.scheme == Scheme::paper && model.base_friction > 0.0)
    throw InputError("solver.scheme = \"paper\": the base friction (model.base_friction) runs on the implicit schemes only; use solver.scheme = \"implicit\"");
}

SolverSummary named(SolverSummary summary, const SolverOptions& options) {
  summary.scheme = to_string(options.scheme);
  summary.history = to_string(options.history);
  summary.h = options.h;
  summary.steps = options.steps();
  return summary;
}

}  // namespace

// Each scheme is a stepper driven by the one time loop (time_loop.hpp), which also times the
// run (set-up included).
SolverSummary simulate(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                       Observer& observer) {
  check_run(options, model);
  if (options.scheme == Scheme::paper) return named(detail::run_paper_scheme(options, model, ground, observer), options);
  TwoBlockStates states(observer, options, model);
  return named(detail::run_two_block_on_structure(options, model, ground, states), options);
}

SolverSummary simulate_as_structure(const SolverOptions& options, const Model& model, const GroundMotion& ground,
                                    StructureObserver& observer) {
  check_run(options, model);
  if (options.scheme == Scheme::paper) {
    PaperAsStructure states(observer, options, model);
    return named(detail::run_paper_scheme(options, model, ground, states), options);
  }
  return named(detail::run_two_block_on_structure(options, model, ground, observer), options);
}

StructureSolverOptions with_scheme(StructureSolverOptions o, Scheme scheme) {
  o.scheme = scheme;
  if (scheme == Scheme::implicit_damped) o.restart = StructureSolverOptions::Restart::always;
  if (scheme == Scheme::implicit_gl) o.quadrature = StructureSolverOptions::Quadrature::grunwald_letnikov;
  return o;
}

}  // namespace adjoin
