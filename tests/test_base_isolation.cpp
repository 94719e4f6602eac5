// Isolated bases (SPEC §7): a base floor sliding on the ground with Coulomb friction mu W
// (flat slider), or on a friction pendulum that adds the restoring stiffness W / R.
//  - A rigid block on a flat slider under a sine ground motion against its closed form (written
//    here): the stick/slip instants and the slip of each episode.
//  - A block on a friction pendulum sliding freely with small friction: its reversals half a
//    period pi sqrt(R / g) apart, its amplitude falling by 2 mu R per half cycle.
//  - The energy balance with an isolated building (isolator term) closes at order 2.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <cmath>
#include <functional>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "cli_helpers.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/observe/energy.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/structure/two_block.hpp"
#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/study/run.hpp"
#include "state_recorder.hpp"

using namespace adjoin;
using namespace adjoin::structure;

namespace {

constexpr double g = kStandardGravity;

// a_g(t) = A sin(W t) [m/s^2] (the solver reads it in g; a_g is what drives x'' = a_g - ...).
class Sine final : public GroundMotion {
 public:
  Sine(double a, double omega, double duration) : a_(a), w_(omega), d_(duration) {}
  double ag(double t) const override { return t < d_ ? a_ * std::sin(w_ * t) / g : 0.0; }
  std::string describe() const override { return "sine"; }
  double duration() const override { return d_; }

 private:
  double a_, w_, d_;
};

// A dimensionless ground read by the structure solver (which reads a_g in g and multiplies by
// g): the two-block runs' own scaling (solver/two_block_structure.cpp).
class ScaledGroundForTest final : public GroundMotion {
 public:
  explicit ScaledGroundForTest(const GroundMotion& inner) : inner_(inner) {}
  double ag(double t) const override { return inner_.ag(t) / g; }
  std::string describe() const override { return inner_.describe(); }
  double duration() const override { return inner_.duration(); }

 private:
  const GroundMotion& inner_;
};

class NoGround final : public GroundMotion {
 public:
  double ag(double) const override { return 0.0; }
  std::string describe() const override { return "none"; }
  double duration() const override { return 0.0; }
};

using Recorder = adjoin::test::StateRecorder;

// A rigid block of mass m_b on an isolated base: the base carries a one-storey superstructure
// of a millionth of its mass on a 20 Hz storey, so the block is the base to 1e-6.
Structure block(BaseModel model, double mu, double radius = 0.0) {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::VectorXd::Constant(1, 0.01);
  s.a.springs = Eigen::VectorXd::Constant(1, 0.01 * std::pow(2.0 * M_PI * 20.0, 2));
  s.a.base = Base{1e4, model, mu, radius};
  return s;
}

Recorder run(const Structure& s, double h, double t_end, const GroundMotion& ground, double v0 = 0.0) {
  StructureSolverOptions o;
  o.h = h;
  o.t_end = t_end;
  if (v0 != 0.0) o.v0 = Eigen::VectorXd::Constant(s.dofs(), v0);
  Recorder r;
  simulate_structure(o, s, ground, r);
  return r;
}

double bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if ((f(mid) > 0.0) == (f(lo) > 0.0)) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

// The slider's located switch instants (the state's link arrays: the base's slider after the
// links, here the only one).
std::vector<double> switches(const Recorder& r) {
  std::vector<double> out;
  for (std::size_t k = 1; k < r.states.size(); ++k)
    if (r.states[k].link_phase[0] != r.states[k - 1].link_phase[0])
      out.push_back(std::isnan(r.states[k].link_switch[0]) ? r.states[k].t : r.states[k].link_switch[0]);
  return out;
}

}  // namespace

// The closed form. Stuck, the block moves with the ground while |M a_g| <= mu M g; with
// A = 1.5 mu g it starts to slip forward at W t1 = asin(mu g / A); slipping forward,
// x'' = A sin(W t) - mu g, so v(t) = -(A / W)(cos W t - cos W t1) - mu g (t - t1), until v = 0 at
// t2 (W t2 = 190.4 deg, where |A sin W t2| = 0.27 mu g < mu g: it sticks), having slipped
//   D = -(A / W)((sin W t2 - sin W t1) / W - (t2 - t1) cos W t1) - mu g (t2 - t1)^2 / 2.
// Half a period later the same backwards: onsets at t1 + k T/2, stops at t2 + k T/2, the base
// at D after each forward slip and back at 0 after each backward one.
TEST_CASE("a rigid block on a flat slider under a sine ground motion follows its closed form", "[base]") {
  const double mu = 0.1, a = 1.5 * mu * g, w = 2.0 * M_PI, period = 1.0;
  const double t1 = std::asin(mu * g / a) / w;
  auto v = [&](double t) { return -(a / w) * (std::cos(w * t) - std::cos(w * t1)) - mu * g * (t - t1); };
  const double t2 = bisect(v, t1 + 0.1, t1 + 0.6);
  REQUIRE(std::abs(a * std::sin(w * t2)) < mu * g);  // it sticks there
  const double slip = -(a / w) * ((std::sin(w * t2) - std::sin(w * t1)) / w - (t2 - t1) * std::cos(w * t1)) -
                      0.5 * mu * g * (t2 - t1) * (t2 - t1);
  const Structure s = block(BaseModel::flat_slider, mu);
  const int base = s.base_dof('A');
  REQUIRE(base == 1);
  const Sine ground(a, w, 10.0);
  std::vector<double> instant_errors, slip_errors;
  for (double h : {2e-3, 1e-3}) {
    const Recorder r = run(s, h, 2.4, ground);
    const std::vector<double> located = switches(r);
    REQUIRE(located.size() == 9);  // onsets and stops, forward and backward, to t = 2.4 (the fifth slip stops at 2.53)
    double e = 0.0;
    for (std::size_t k = 0; k < located.size(); ++k) {
      const double exact = (k % 2 == 0 ? t1 : t2) + 0.5 * period * static_cast<double>(k / 2);
      e = std::max(e, std::abs(located[k] - exact));
    }
    instant_errors.push_back(e);
    // While stuck the base moves with the ground: its x0 is D after a forward slip, 0 after a
    // backward one, bit for bit constant.
    double es = 0.0;
    for (const auto& st : r.states) {
      const double phase = std::fmod(st.t, 0.5 * period);
      if (st.t < t2 + 1e-2 || phase < t2 - 0.5 * period + 1e-2 || phase > t1 - 1e-2) continue;  // inside a stick
      const int k = static_cast<int>(std::floor((st.t - t2) / (0.5 * period)));
      es = std::max(es, std::abs(st.x[base] - (k % 2 == 0 ? slip : 0.0)));
      CHECK(st.v[base] == 0.0);
      CHECK(st.link_phase[0] == Phase::stick);
    }
    slip_errors.push_back(es);
  }
  INFO("slip per episode " << slip << " m, instants' errors " << instant_errors[0] << " " << instant_errors[1] << " s, slips' errors "
                           << slip_errors[0] << " " << slip_errors[1] << " m");
  CHECK(instant_errors[1] < 2e-5);
  CHECK(slip_errors[1] < 5e-5 * slip);  // (2.2e-5 at h = 1 ms, 1.1e-6 s on the instants)
  CHECK(instant_errors[0] / instant_errors[1] > 3.0);  // order 2
  CHECK(slip_errors[0] / slip_errors[1] > 3.0);
}

// Free sliding on a friction pendulum: x'' + (g / R) x = -mu g sign(x'). Between reversals a
// harmonic oscillation about -+mu R, so the reversals come half a period pi sqrt(R / g) apart
// (friction does not change the period) and each half cycle the amplitude falls by 2 mu R,
// until a reversal within |x| <= mu R, where the pendulum's pull no longer beats the friction:
// it stops there for good.
TEST_CASE("a block on a friction pendulum reverses every half period pi sqrt(R / g) and loses 2 mu R per half cycle", "[base]") {
  const double mu = 0.002, radius = 2.0, v0 = 0.3;
  const double omega = std::sqrt(g / radius), half = M_PI / omega;
  const Structure s = block(BaseModel::friction_pendulum, mu, radius);
  const int base = s.base_dof('A');
  const NoGround ground;
  const Recorder r = run(s, 1e-3, 12.0, ground, v0);
  std::vector<double> located = switches(r);
  REQUIRE(!located.empty());
  CHECK(located[0] <= 1e-3);  // launched: stuck at t = 0, slipping from the first step
  located.erase(located.begin());
  REQUIRE(located.size() >= 6);
  // Reversals: the first at W t = atan2(v0 W, mu g) (x = -mu R + mu R cos W t + v0/W sin W t).
  const double first = std::atan2(v0 * omega, mu * g) / omega;
  CHECK(located[0] == Approx(first).margin(1e-5));
  for (std::size_t k = 1; k < 6; ++k) CHECK(located[k] - located[k - 1] == Approx(half).margin(2e-5));
  // The turning points' amplitudes: |x| at each reversal (the grid extreme nearest it).
  std::vector<double> turns;
  for (std::size_t k = 1; k + 1 < r.states.size(); ++k)
    if (r.states[k].v[base] * r.states[k + 1].v[base] < 0.0 || (r.states[k].v[base] != 0.0 && r.states[k + 1].v[base] == 0.0)) {
      // the parabola through three samples
      const double x0 = r.states[k - 1].x[base], x1 = r.states[k].x[base], x2 = r.states[k + 1].x[base];
      const double d = x0 - 2.0 * x1 + x2;
      turns.push_back(std::abs(d != 0.0 ? x1 - (x2 - x0) * (x2 - x0) / (8.0 * d) : x1));
    }
  REQUIRE(turns.size() >= 4);
  // About the centre -+mu R: amplitudes about the centre fall by 4 mu R per half cycle, so
  // |x| at successive turns falls by 2 mu R.
  for (std::size_t k = 1; k < 4; ++k) CHECK(turns[k - 1] - turns[k] == Approx(2.0 * mu * radius).epsilon(2e-3));
}

namespace {

// The two-frame example with B on friction pendulums, under a decaying sine (smooth: see the
// scene's note on records).
const std::string kIsolated = std::string(ADJOIN_SOURCE_DIR) + "/tests/data/isolated-two-frames.toml";

void check_energy_closes(const BuildingScene& given) {
  BuildingScene scene = given;
  std::vector<double> residuals;
  for (double h : {0.004, 0.002, 0.001}) {
    scene.solver.h = h;
    const Report r = run(scene);
    INFO("h = " << h << ": input " << r.energy.input << " J, residual " << r.energy.residual << " J");
    residuals.push_back(std::abs(r.energy.residual) / r.energy.input);
  }
  INFO("relative residuals " << residuals[0] << " " << residuals[1] << " " << residuals[2]);
  CHECK(residuals[2] < 1e-5);
  // Order 2 over the ladder (the flat slider's last halving is 1.63: its many stick onsets,
  // each located on the parabola through three grid stuck forces, make the error less regular).
  CHECK(0.5 * std::log2(residuals[0] / residuals[2]) > 1.8);
  CHECK(std::log2(residuals[0] / residuals[1]) > 1.5);
  CHECK(std::log2(residuals[1] / residuals[2]) > 1.5);
}

}  // namespace

TEST_CASE("the energy balance closes at order 2 with building B on friction pendulums", "[base][energy]") {
  BuildingScene scene = load_building_scene(kIsolated, {"solver.t_end=15", "output.timeseries=false"});
  REQUIRE(scene.structure.b->base);
  check_energy_closes(scene);
  scene.solver.h = 0.002;
  const Report r = run(scene);
  REQUIRE(r.bases.size() == 1);
  CHECK(r.bases[0].building == 'B');
  CHECK(r.bases[0].switches > 0);
  CHECK(r.bases[0].max_abs > 0.0);
  CHECK(r.bases[0].energy > 0.0);  // the slider dissipates
  // The isolator's work is its slider's dissipation plus the pendulum's stored 1/2 k x0^2.
  const double k = scene.structure.b->base_stiffness();
  CHECK(r.energy.buildings[1].isolator == Approx(r.bases[0].energy + 0.5 * k * r.bases[0].residual * r.bases[0].residual).epsilon(1e-3));
  bool peak = false;
  for (const auto& p : r.peaks) peak = peak || (p.channel == "B.x0" && p.peak.max_abs == r.bases[0].max_abs);
  CHECK(peak);
}

TEST_CASE("the energy balance closes at order 2 with building A alone on a flat slider", "[base][energy]") {
  BuildingScene scene = load_building_scene(kIsolated, {"solver.t_end=15", "output.timeseries=false"});
  scene.structure.b.reset();
  scene.structure.links.clear();
  scene.structure.contacts.clear();
  scene.structure.a.base = Base{45e3, BaseModel::flat_slider, 0.08, 0.0};
  check_energy_closes(scene);
}

TEST_CASE("an isolated building's channels: X.x0, and storey 1's drift against the base", "[base]") {
  Structure s = block(BaseModel::flat_slider, 0.1);
  const auto x0 = find_channel(s, "A.x0");
  REQUIRE(x0);
  CHECK(x0->dof == s.base_dof('A'));
  CHECK(s.dofs() == 2);
  CHECK(s.below('A', 1) == 1);
  // A fixed base has no X.x0.
  s.a.base.reset();
  CHECK(!find_channel(s, "A.x0"));
}

// ---- the two-block scene's model.base_friction (SPEC §7) ----

namespace {

// A half-sine pulse a_g = A sin(pi t / td) for t < td, then nothing (dimensionless).
class Pulse final : public GroundMotion {
 public:
  Pulse(double a, double td) : a_(a), td_(td) {}
  double ag(double t) const override { return t < td_ ? a_ * std::sin(M_PI * t / td_) : 0.0; }
  std::string describe() const override { return "pulse"; }
  double duration() const override { return td_; }

 private:
  double a_, td_;
};

}  // namespace

// The paper's suggestion: "to stop the system in a finite time it is necessary to introduce
// the dry friction". With mu_b = 0.2 the blocks, shaken by a pulse that ends at t = 3, come to
// rest for good at a finite time: from then on both velocities are 0 bit for bit (the sliders
// stuck, stick exact), and the instant is located inside its step (the last slider's stick).
// The energy balance, with the base friction's work, still closes.
TEST_CASE("with base friction the two blocks come to rest at a finite, located time after the ground motion ends", "[base][two_block]") {
  Model model = Model::Paper();
  model.base_friction = 0.2;
  const Pulse ground(1.0, 3.0);
  SolverOptions o;
  o.h = 0.002;
  o.t_end = 60.0;
  Recorder r;  // the run's 1 + 1 structure's states: link 1 the damper, then the base sliders
  simulate_as_structure(o, model, ground, r);
  // The energy of the same run, watched as its 1 + 1 structure.
  EnergyObserver energy;
  simulate_as_structure(o, model, ground, energy);
  // The last grid point at which a block moved.
  double last_moving = 0.0;
  for (const StructureState& s : r.states)
    if (s.v[0] != 0.0 || s.v[1] != 0.0) last_moving = s.t;
  INFO("last moving at t = " << last_moving);
  CHECK(last_moving > 3.0);
  CHECK(last_moving < 0.5 * o.t_end);  // at rest for the second half of the run
  const Eigen::VectorXd& q = r.states.back().link_force;  // the damper's, then the sliders' (A's, B's)
  REQUIRE(q.size() == 3);
  CHECK(q[1] != 0.0);  // held by its friction, a rod force below mu_b m1 g
  CHECK(std::abs(q[1]) <= 0.2 + 1e-12);
  CHECK(std::abs(q[2]) <= 0.2 / model.rho + 1e-12);
  INFO("energy: input " << energy.terms().total_input() << ", base friction " << (energy.terms().base[0] + energy.terms().base[1]) << ", residual "
                        << energy.terms().residual);
  CHECK((energy.terms().base[0] + energy.terms().base[1]) > 0.0);
  CHECK(std::abs(energy.terms().residual) < 1e-3 * energy.terms().total_input());
  // The same structure on the structure solver: the last stick of a base slider is located
  // inside the step that ends at its first grid point of rest. (The instant itself is not
  // compared with the run above: how long the blocks creep while a rod force hovers near mu_b
  // m g is ill-conditioned, and the direct and fft engines, equal to rounding, already stop
  // 0.04 s apart.)
  const Structure s = two_block_structure(model);
  REQUIRE(s.ground_sliders().size() == 2);
  StructureSolverOptions so;
  so.h = o.h;
  so.t_end = o.t_end;
  Recorder sr;
  const ScaledGroundForTest scaled(ground);
  simulate_structure(so, s, scaled, sr);
  double stop = std::nan(""), first_rest = std::nan("");
  for (std::size_t k = 1; k < sr.states.size(); ++k)
    for (std::size_t l = s.links.size(); l < s.links.size() + 2; ++l)
      if (sr.states[k].link_phase[l] == Phase::stick && sr.states[k - 1].link_phase[l] != Phase::stick) {
        stop = sr.states[k].link_switch[l];
        first_rest = sr.states[k].t;
      }
  INFO("located stop " << stop << " in the step ending at " << first_rest);
  REQUIRE(!std::isnan(stop));
  CHECK(stop <= first_rest);
  CHECK(stop >= first_rest - so.h - 1e-12);
  CHECK(stop > 3.0);
  CHECK(stop < 0.5 * so.t_end);
  // From then on the blocks rest: both sliders stuck to the end.
  for (std::size_t l = s.links.size(); l < s.links.size() + 2; ++l) CHECK(sr.states.back().link_phase[l] == Phase::stick);
}

TEST_CASE("base friction is refused with the paper scheme", "[base][two_block]") {
  Model model = Model::Paper();
  model.base_friction = 0.1;
  SolverOptions o;
  o.scheme = Scheme::paper;
  Recorder r;
  CHECK_THROWS_AS(simulate_as_structure(o, model, Pulse(1.0, 3.0), r), InputError);
}

// The outputs (SPEC §7): summary.json's `base`, the energy's `isolator`, X.x0 in `peaks`,
// `residual` and timeseries.csv; the terminal's base line.
TEST_CASE("adjoin run writes an isolated base's outputs", "[base][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "isolated-run";
  std::filesystem::remove_all(dir);
  const auto r = test::run_cli("run '" + kIsolated + "' --set solver.t_end=3 --set output.timeseries=true --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("base B (friction-pendulum): x0 max") != std::string::npos);
  const auto j = nlohmann::json::parse(test::slurp(dir / "summary.json"));
  const auto& base = j["base"]["B"];
  for (const char* key : {"max_abs", "t", "residual", "switches", "energy"}) CHECK(base.contains(key));
  CHECK(base["max_abs"].get<double>() == j["peaks"]["B.x0"]["max_abs"].get<double>());
  CHECK(base["residual"].get<double>() == j["residual"]["B.x0"].get<double>());
  CHECK(base["switches"].get<int>() > 0);
  CHECK(j["energy"]["B"]["isolator"].get<double>() >= base["energy"].get<double>());  // (+ the pendulum's stored energy)
  CHECK_FALSE(j["energy"]["A"].contains("isolator"));
  CHECK_FALSE(j["base"].contains("A"));
  const std::string header = test::slurp(dir / "timeseries.csv").substr(0, 200);
  CHECK(header.find("B.x0,B.x1") != std::string::npos);
}
