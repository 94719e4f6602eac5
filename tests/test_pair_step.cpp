// The structure stepper's pair step (src/solver/pair_step.hpp): two one-floor buildings joined
// by one friction damper are stepped by a step written for them, which must give the general
// step's trajectory bit for bit (StructureSolverOptions::pair_step = false forces the general
// step), for each scheme and through many stick-slip switches; and which structures take it.
#include <catch2/catch.hpp>
#include <cstring>
#include <string>
#include <vector>

#include "../src/solver/pair_step.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "scene_helpers.hpp"
#include "state_recorder.hpp"

using namespace adjoin;
using adjoin::structure::Structure;

namespace {

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every reported field of the two states, bit for bit (NaN switch times included).
bool same_state(const StructureState& a, const StructureState& b) {
  return same_bits(a.t, b.t) && same_bits(a.ag, b.ag) && same_bits(a.x, b.x) && same_bits(a.v, b.v) && same_bits(a.a_abs, b.a_abs) &&
         same_bits(a.storey_force, b.storey_force) && same_bits(a.hyst, b.hyst) && same_bits(a.hyst_yield, b.hyst_yield) &&
         same_bits(a.link_force, b.link_force) && same_bits(a.link_stroke, b.link_stroke) &&
         same_bits(a.link_velocity, b.link_velocity) && a.link_phase == b.link_phase && same_bits(a.link_switch, b.link_switch) &&
         same_bits(a.contact_gap, b.contact_gap) && same_bits(a.contact_force, b.contact_force);
}

struct Compared {
  std::size_t points = 0, first_difference = 0;
  int switches = 0;
  bool same = false;
};

// The run with the pair step and with the general step, state by state.
Compared compare(StructureSolverOptions o, const Structure& s, const GroundMotion& ground) {
  test::StateRecorder pair, general;
  o.pair_step = true;
  simulate_structure(o, s, ground, pair);
  o.pair_step = false;
  simulate_structure(o, s, ground, general);
  Compared c;
  c.points = pair.states.size();
  c.same = pair.states.size() == general.states.size();
  for (std::size_t i = 0; c.same && i < pair.states.size(); ++i) {
    c.same = same_state(pair.states[i], general.states[i]);
    c.first_difference = i;
    if (i > 0 && pair.states[i].link_phase[0] != pair.states[i - 1].link_phase[0]) ++c.switches;
  }
  return c;
}

StructureSolverOptions options_of(const Scene& scene, Scheme scheme) {
  StructureSolverOptions o;
  o.h = scene.solver.h;
  o.t_end = scene.solver.t_end;
  o.history = scene.solver.history;
  return with_scheme(o, scheme);
}

Scene scene_file(const std::string& name, std::vector<std::string> overrides = {}) {
  return load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/" + name, overrides);
}

}  // namespace

TEST_CASE("the pair step: the strong scene's trajectory is the general step's bit for bit, each scheme", "[pair_step]") {
  for (Scheme scheme : {Scheme::implicit, Scheme::implicit_damped, Scheme::implicit_gl}) {
    const Scene scene = test::paper_scene("strong", {"solver.history=fft"});
    const Structure s = structure_of(scene);
    const ScaledGround ground(*scene.ground, 1.0 / kStandardGravity);
    const StructureSolverOptions o = options_of(scene, scheme);
    const detail::StructureModel model(o, s);
    REQUIRE(detail::takes_pair_step(model));
    const Compared c = compare(o, s, ground);
    INFO("scheme " << static_cast<int>(scheme) << ": first difference at point " << c.first_difference << " of " << c.points);
    CHECK(c.same);
    CHECK(c.switches >= 4);  // (stick-slip switches taken on both paths)
  }
}

TEST_CASE("the pair step: a record scene with many switches and restarts gives the general step's trajectory bit for bit", "[pair_step]") {
  // The synthetic EC8 record (SI frames, fractional rods) with a quarter of the scene's slip
  // force: hundreds of switches, the backward-Euler restart after each (implicit-damped),
  // soe histories.
  const Scene scene = scene_file("si-record.toml", {"solver.history=soe", "model.slip_force=5e4"});
  const Structure s = structure_of(scene);  // (in SI: the ground in g, as simulate_structure takes it)
  const GroundMotion& ground = *scene.ground;
  const Compared c = compare(options_of(scene, Scheme::implicit_damped), s, ground);
  INFO("first difference at point " << c.first_difference << " of " << c.points << ", " << c.switches << " switches");
  CHECK(c.same);
  CHECK(c.switches >= 50);
}

TEST_CASE("the pair step: the weak scene, stuck throughout, is the general step's bit for bit", "[pair_step]") {
  // Every step stuck: each decided at the step's end by the stuck force's margin
  // (PairStepper::decide_at_end), none by the trial.
  for (const char* engine : {"fft", "soe"}) {
    const Scene scene = test::paper_scene("weak", {std::string("solver.history=") + engine});
    const Structure s = structure_of(scene);
    const ScaledGround ground(*scene.ground, 1.0 / kStandardGravity);
    const Compared c = compare(options_of(scene, Scheme::implicit), s, ground);
    INFO(engine << ": first difference at point " << c.first_difference << " of " << c.points);
    CHECK(c.same);
    CHECK(c.points == scene.solver.steps() + 1);
  }
}

TEST_CASE("the pair step: a pair with inherent damping and a storey dashpot gives the general step's trajectory bit for bit", "[pair_step]") {
  // Not the plain two-block pair (PairSlots<false>: the slots read from the constants): the
  // strong scene's structure with 5 % modal damping in A (C's diagonal in the trial and the
  // stick's correction) and a linear dashpot in B's storey (its storey force).
  const Scene scene = test::paper_scene("strong", {"solver.history=fft"});
  Structure s = structure_of(scene);
  s.a.damping.model = structure::DampingModel::modal;
  s.a.damping.ratio = 0.05;
  structure::StoreyDevice dashpot;
  dashpot.type = structure::DeviceType::dashpot;
  dashpot.storeys = {1};
  dashpot.c = 0.05;  // (the scene's units: B's mass 1 / rho, its stiffness eps)
  s.b->devices.push_back(dashpot);
  const ScaledGround ground(*scene.ground, 1.0 / kStandardGravity);
  for (Scheme scheme : {Scheme::implicit, Scheme::implicit_damped}) {
    const StructureSolverOptions o = options_of(scene, scheme);
    const detail::StructureModel model(o, s);
    REQUIRE(detail::takes_pair_step(model));
    REQUIRE(model.dashpots_b);
    const Compared c = compare(o, s, ground);
    INFO("scheme " << static_cast<int>(scheme) << ": first difference at point " << c.first_difference << " of " << c.points);
    CHECK(c.same);
    CHECK(c.switches >= 4);
  }
}

TEST_CASE("the pair step is taken by one-floor pairs joined by one friction damper only", "[pair_step]") {
  const Scene scene = test::paper_scene("strong");
  Structure s = structure_of(scene);
  StructureSolverOptions o = options_of(scene, Scheme::implicit);
  CHECK(detail::takes_pair_step(detail::StructureModel(o, s)));
  o.pair_step = false;  // forced off
  CHECK_FALSE(detail::takes_pair_step(detail::StructureModel(o, s)));
  o.pair_step = true;
  Structure two = s;  // a second friction damper between the floors: the general step
  two.links.push_back(two.links.front());
  CHECK_FALSE(detail::takes_pair_step(detail::StructureModel(o, two)));
}
