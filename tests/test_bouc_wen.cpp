// Bouc-Wen storeys and devices in the structure step (SPEC §7): a one-storey Bouc-Wen
// oscillator under a sine ground motion against an independent high-accuracy integration
// written here (adaptive Dormand-Prince RK45, tolerance 1e-12, on x, v, z and the hysteretic
// work), order 2 of the displacement, z and the plastic work, for n = 1 and n = 2; the energy
// balance closing at order 2 with Bouc-Wen storeys beside a friction damper, and with a
// Bouc-Wen device.
#include <catch2/catch.hpp>
#include <array>
#include <fstream>
#include <sstream>
#include <cmath>
#include <vector>

#include "../src/study/yield_observer.hpp"
#include "cli_helpers.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/ground/ground_motion.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/study/run.hpp"

using namespace adjoin;
using namespace adjoin::structure;

namespace {

// a_g(t) = A sin(W t) [m/s^2] (the solver reads it in g).
class Sine final : public GroundMotion {
 public:
  Sine(double a, double w, double duration) : a_(a), w_(w), duration_(duration) {}
  double ag(double t) const override { return a_ * std::sin(w_ * t) / kStandardGravity; }
  std::string describe() const override { return "sine"; }
  double duration() const override { return duration_; }

 private:
  double a_, w_, duration_;
};

// Keeps the grid states and passes them on to the run's own yield report (study/run.cpp's).
class Recorder final : public StructureObserver {
 public:
  explicit Recorder(const Structure& s) : yielding(s) {}
  void observe(const StructureState& s) override {
    states.push_back(s);
    yielding.observe(s);
  }
  std::vector<StructureState> states;
  detail::YieldObserver yielding;
};

// The oscillator: mass m, initial stiffness k (period T), hardening b, yield force k u_y,
// 5 % damping on the initial stiffness, the Bouc-Wen law (n, beta, gamma).
struct Oscillator {
  double m = 1e4, period = 0.5, uy = 0.004, b = 0.05, zeta = 0.05, n = 2.0, beta = 0.5, gamma = 0.5;
  double k() const { return m * std::pow(2.0 * M_PI / period, 2); }
  Structure structure() const {
    Structure s;
    s.a.name = "A";
    s.a.masses = Eigen::VectorXd::Constant(1, m);
    s.a.springs = Eigen::VectorXd::Constant(1, k());
    s.a.hysteresis.model = HysteresisModel::bouc_wen;
    s.a.hysteresis.yield_forces = Eigen::VectorXd::Constant(1, k() * uy);
    s.a.hysteresis.hardening = b;
    s.a.hysteresis.n = n;
    s.a.hysteresis.beta = beta;
    s.a.hysteresis.gamma = gamma;
    s.a.damping = {DampingModel::modal, zeta, 1, 2};
    return s;
  }
};

// The reference, independent of the solver: x'' = a_g - c x' - (b k x + (1 - b) k z) / m,
// z' = x' - beta' |x'| |z|^(n-1) z - gamma' x' |z|^n, W' = z x' (the hysteretic work's
// integral), by Dormand-Prince 5(4) with a relative and absolute tolerance of 1e-12,
// stepping exactly to each requested instant.
class Reference {
 public:
  using State = std::array<double, 4>;  // x, v, z, W
  Reference(const Oscillator& o, double a, double w) : o_(o), a_(a), w_(w) {
    const double scale = std::pow(o.uy, o.n);
    beta_ = o.beta / scale;
    gamma_ = o.gamma / scale;
    c_ = 2.0 * o.zeta * std::sqrt(o.k() / o.m) * o.m;
  }
  // The states at t = 0, dt, 2 dt, ..., t_end.
  std::vector<State> run(double dt, std::size_t steps) const {
    std::vector<State> out{State{0.0, 0.0, 0.0, 0.0}};
    State y{0.0, 0.0, 0.0, 0.0};
    double t = 0.0, step = dt / 4.0;
    for (std::size_t i = 1; i <= steps; ++i) {
      const double target = static_cast<double>(i) * dt;
      while (t < target) {
        const double try_step = std::min(step, target - t);
        State next, error;
        dopri(t, y, try_step, next, error);
        double norm = 0.0;
        for (int j = 0; j < 4; ++j) {
          const double sc = 1e-12 + 1e-12 * std::max(std::abs(y[j]), std::abs(next[j])) + 1e-12 * scale_[j];
          norm = std::max(norm, std::abs(error[j]) / sc);
        }
        if (norm <= 1.0) {
          t = (try_step == target - t) ? target : t + try_step;
          y = next;
        }
        step = try_step * std::clamp(0.9 * std::pow(std::max(norm, 1e-10), -0.2), 0.2, 5.0);
      }
      out.push_back(y);
    }
    return out;
  }

 private:
  State rhs(double t, const State& y) const {
    const double x = y[0], v = y[1], z = y[2], kk = o_.k();
    const double az = std::pow(std::abs(z), o_.n), sz = z > 0.0 ? 1.0 : (z < 0.0 ? -1.0 : 0.0);
    const double dz = v - beta_ * std::abs(v) * az * sz - gamma_ * v * az;
    const double acc = a_ * std::sin(w_ * t) - (c_ * v + o_.b * kk * x + (1.0 - o_.b) * kk * z) / o_.m;
    return {v, acc, dz, z * v};
  }
  void dopri(double t, const State& y, double h, State& out, State& err) const {
    static constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
    static constexpr double a21 = 1.0 / 5, a31 = 3.0 / 40, a32 = 9.0 / 40, a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9,
                            a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729,
                            a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176, a65 = -5103.0 / 18656,
                            b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84,
                            e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200, e6 = 22.0 / 525,
                            e7 = -1.0 / 40;
    auto add = [&](std::initializer_list<std::pair<double, const State*>> terms) {
      State r = y;
      for (const auto& [c, k] : terms)
        for (int j = 0; j < 4; ++j) r[j] += h * c * (*k)[j];
      return r;
    };
    const State k1 = rhs(t, y);
    const State k2 = rhs(t + c2 * h, add({{a21, &k1}}));
    const State k3 = rhs(t + c3 * h, add({{a31, &k1}, {a32, &k2}}));
    const State k4 = rhs(t + c4 * h, add({{a41, &k1}, {a42, &k2}, {a43, &k3}}));
    const State k5 = rhs(t + c5 * h, add({{a51, &k1}, {a52, &k2}, {a53, &k3}, {a54, &k4}}));
    const State k6 = rhs(t + h, add({{a61, &k1}, {a62, &k2}, {a63, &k3}, {a64, &k4}, {a65, &k5}}));
    out = add({{b1, &k1}, {b3, &k3}, {b4, &k4}, {b5, &k5}, {b6, &k6}});
    const State k7 = rhs(t + h, out);
    for (int j = 0; j < 4; ++j) err[j] = h * (e1 * k1[j] + e3 * k3[j] + e4 * k4[j] + e5 * k5[j] + e6 * k6[j] + e7 * k7[j]);
  }
  Oscillator o_;
  double a_, w_, beta_ = 0.0, gamma_ = 0.0, c_ = 0.0;
  State scale_{1e-3, 1e-2, 1e-3, 1e-6};  // (absolute floors of the error's scale: m, m/s, m, m^2)
};

struct Errors {
  double x = 0.0, z = 0.0, work = 0.0;
  double work_value = 0.0, peak = 0.0;
  bool yielded = false;
};

// The structure step at h against the reference sampled at the step's grid.
Errors errors_at(const Oscillator& o, double a, double w, double t_end, double h) {
  const Sine ground(a, w, t_end);
  StructureSolverOptions options;
  options.h = h;
  options.t_end = t_end;
  const Structure s = o.structure();
  Recorder r(s);
  simulate_structure(options, s, ground, r);
  const auto ref = Reference(o, a, w).run(h, r.states.size() - 1);
  Errors e;
  for (std::size_t i = 0; i < r.states.size(); ++i) {
    e.x = std::max(e.x, std::abs(r.states[i].x[0] - ref[i][0]));
    e.z = std::max(e.z, std::abs(r.states[i].hyst[0] - ref[i][2]));
    e.peak = std::max(e.peak, std::abs(ref[i][0]));
  }
  const double kh = (1.0 - o.b) * o.k(), z_end = ref.back()[2];
  const double exact_work = kh * ref.back()[3] - 0.5 * kh * z_end * z_end;
  const auto report = r.yielding.report();
  e.work_value = report[0].storeys[0].plastic_work;
  e.work = std::abs(e.work_value - exact_work);
  e.yielded = report[0].storeys[0].yielded;
  return e;
}

void check_order_two(const Oscillator& o) {
  const double a = 3.0, w = 2.0 * M_PI / 0.6, t_end = 3.0;
  std::vector<Errors> e;
  for (double h : {4e-4, 2e-4, 1e-4}) e.push_back(errors_at(o, a, w, t_end, h));
  INFO("x errors " << e[0].x << " " << e[1].x << " " << e[2].x);
  INFO("z errors " << e[0].z << " " << e[1].z << " " << e[2].z);
  INFO("plastic work " << e[2].work_value << " J, errors " << e[0].work << " " << e[1].work << " " << e[2].work);
  CHECK(e[2].yielded);
  CHECK(e[2].work_value > 0.0);
  for (int i = 0; i < 2; ++i) {
    CHECK(e[i].x / e[i + 1].x == Approx(4.0).epsilon(0.2));
    CHECK(e[i].z / e[i + 1].z == Approx(4.0).epsilon(0.2));
    CHECK(e[i].work / e[i + 1].work == Approx(4.0).epsilon(0.2));
  }
  // Well past u_y (ductility > 2), and the errors small against the response.
  INFO("peak " << e[2].peak << " m");
  CHECK(e[2].peak > 2.0 * o.uy);
  CHECK(e[2].x < 1e-4 * e[2].peak);
}

}  // namespace

TEST_CASE("a Bouc-Wen oscillator (n = 2) converges at order 2 to an adaptive Runge-Kutta reference", "[bouc-wen]") {
  check_order_two(Oscillator{});
}

TEST_CASE("a Bouc-Wen oscillator (n = 1, beta 0.7, gamma 0.3) converges at order 2 to an adaptive Runge-Kutta reference", "[bouc-wen]") {
  Oscillator o;
  o.n = 1.0;
  o.beta = 0.7;
  o.gamma = 0.3;
  check_order_two(o);
}

TEST_CASE("a Bouc-Wen building beside a friction damper to a second building converges at order 2", "[bouc-wen]") {
  // A: the Bouc-Wen oscillator (2 storeys); B: an elastic one-storey building (T = 0.3 s); a
  // friction link at floor 1 slipping at 8 kN: stick, slip and reversals with the law yielding.
  Oscillator o;
  Structure s = o.structure();
  s.a.masses = Eigen::VectorXd::Constant(2, o.m);
  s.a.springs = Eigen::VectorXd::Constant(2, o.k());
  s.a.hysteresis.yield_forces = Eigen::VectorXd::Constant(2, o.k() * o.uy);
  s.a.damping = {DampingModel::modal, 0.05, 1, 2};
  Building b;
  b.name = "B";
  b.masses = Eigen::VectorXd::Constant(1, 8e3);
  b.springs = Eigen::VectorXd::Constant(1, 8e3 * std::pow(2.0 * M_PI / 0.3, 2));
  b.damping = {DampingModel::modal, 0.05, 1, 2};
  s.b = b;
  Link link;
  link.type = LinkType::friction;
  link.slip_force = 8e3;
  s.links.push_back(link);
  const Sine ground(3.0, 2.0 * M_PI / 0.6, 3.0);
  auto roof = [&](double h) {
    StructureSolverOptions options;
    options.h = h;
    options.t_end = 3.0;
    Recorder r(s);
    simulate_structure(options, s, ground, r);
    std::size_t switches = 0;
    std::vector<double> out;
    for (std::size_t i = 0; i < r.states.size(); ++i) {
      out.push_back(r.states[i].x[1]);
      if (i > 0 && r.states[i].link_phase[0] != r.states[i - 1].link_phase[0]) ++switches;
    }
    return std::make_pair(out, switches);
  };
  const double h0 = 1e-3;
  const auto [reference, switches] = roof(h0 / 32.0);
  INFO("the damper's switches: " << switches);
  CHECK(switches >= 4);
  std::vector<double> errors;
  for (int level = 0; level < 3; ++level) {
    const std::size_t div = std::size_t{1} << level;
    const auto run = roof(h0 / static_cast<double>(div)).first;
    double e = 0.0;
    for (std::size_t n = 0; n * div < run.size(); ++n) e = std::max(e, std::abs(run[n * div] - reference[n * div * 32 / div]));
    errors.push_back(e);
  }
  INFO("roof errors " << errors[0] << " " << errors[1] << " " << errors[2]);
  CHECK(errors[0] / errors[1] == Approx(4.0).epsilon(0.25));
  CHECK(errors[1] / errors[2] == Approx(4.0).epsilon(0.25));
}

namespace {

const std::string kTwoFrames = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";

// The energy balance's relative residual at h = 0.004, 0.002, 0.001 s: it closes at order 2.
void check_energy_closes(const BuildingScene& given, double at_finest = 1e-5) {
  BuildingScene scene = given;
  std::vector<double> residuals;
  for (double h : {0.004, 0.002, 0.001}) {
    scene.solver.h = h;
    const Report r = run(scene);
    INFO("h = " << h << ": input " << r.energy.input << " J, residual " << r.energy.residual << " J");
    residuals.push_back(std::abs(r.energy.residual) / r.energy.input);
  }
  INFO("relative residuals " << residuals[0] << " " << residuals[1] << " " << residuals[2]);
  CHECK(residuals[2] < at_finest);
  CHECK(std::log2(residuals[0] / residuals[1]) > 1.7);
  CHECK(std::log2(residuals[1] / residuals[2]) > 1.7);
}

}  // namespace

TEST_CASE("the energy balance closes at order 2 with Bouc-Wen storeys beside a friction damper", "[bouc-wen][energy]") {
  BuildingScene scene = load_building_scene(kTwoFrames, {"solver.t_end=15", "output.timeseries=false"});
  REQUIRE(!scene.structure.links.empty());
  scene.structure.a.hysteresis.model = HysteresisModel::bouc_wen;
  scene.structure.a.hysteresis.yield_forces = Eigen::VectorXd::Constant(5, 80e3);
  scene.structure.a.hysteresis.hardening = 0.03;
  check_energy_closes(scene);
  scene.solver.h = 0.002;
  const Report r = run(scene);
  REQUIRE(r.yield.size() == 1);
  REQUIRE(r.energy.buildings[0].hysteretic.size() == 5);
  CHECK(r.yield[0].storeys[0].yielded);
  CHECK(r.yield[0].storeys[0].ductility_max > 1.0);
  for (std::size_t i = 0; i < 5; ++i) {
    const double plastic = r.energy.buildings[0].hysteretic[i];
    CHECK(plastic >= 0.0);
    CHECK(plastic <= r.energy.buildings[0].storeys[i] + 1e-6 * r.energy.input);  // the rest is stored
  }
}

TEST_CASE("the energy balance closes at order 2 with a Bouc-Wen device", "[bouc-wen][energy]") {
  BuildingScene scene = load_building_scene(kTwoFrames, {"solver.t_end=15", "output.timeseries=false"});
  StoreyDevice damper;
  damper.type = DeviceType::bouc_wen;
  damper.storeys = {1, 2};
  damper.k = 2e7;
  damper.yield_force = 40e3;
  damper.hardening = 0.02;
  damper.n = 1.0;
  scene.structure.b->devices.push_back(damper);
  check_energy_closes(scene);
  // The device yields: its storeys' work exceeds what the elastic device's storeys store.
  scene.solver.h = 0.002;
  const Report with = run(scene);
  scene.structure.b->devices.back().type = DeviceType::spring;
  const Report elastic = run(scene);
  CHECK(with.energy.buildings[1].storeys[0] > 0.0);
  CHECK(with.energy.buildings[1].storeys[0] != Approx(elastic.energy.buildings[1].storeys[0]).epsilon(1e-3));
}

TEST_CASE("the energy balance closes at order 2 with Bouc-Wen storeys beside a nonlinear viscous damper", "[bouc-wen][energy]") {
  // (The Bouc-Wen passes take the viscous dampers' own passes as their local solve.)
  BuildingScene scene = load_building_scene(kTwoFrames, {"solver.t_end=15", "output.timeseries=false"});
  scene.structure.a.hysteresis.model = HysteresisModel::bouc_wen;
  scene.structure.a.hysteresis.yield_forces = Eigen::VectorXd::Constant(5, 80e3);
  StoreyDevice fluid;
  fluid.type = DeviceType::dashpot;
  fluid.storeys = {1};
  fluid.c = 2e5;
  fluid.alpha = 0.4;
  scene.structure.a.devices.push_back(fluid);
  check_energy_closes(scene, 1e-3);  // (the alpha = 0.4 damper's own error constant: 1.2e-4 at h = 1 ms without Bouc-Wen)
}

namespace {

// The two-frame scene, in the scratch folder, with A's storeys on `hysteresis` and (if not
// empty) a device in B with the keys `device`.
std::string two_frames_with(const std::string& hysteresis, const std::string& device) {
  std::ifstream in(kTwoFrames);
  std::stringstream text;
  text << in.rdbuf();
  std::string scene_text = text.str();
  const std::string a_damping = "damping = { model = \"modal\", ratio = 0.05 }\n";
  REQUIRE(scene_text.find(a_damping) != std::string::npos);
  scene_text.replace(scene_text.find(a_damping), a_damping.size(), a_damping + "hysteresis = " + hysteresis + "\n");
  const std::string link = "[[link]]";
  if (!device.empty()) scene_text.replace(scene_text.find(link), link.size(), "[[building.B.device]]\n" + device + "\n[[link]]");
  const std::string record = "../../real/", absolute = std::string(ADJOIN_SOURCE_DIR) + "/records/real/";
  scene_text.replace(scene_text.find(record), record.size(), absolute);
  static int count = 0;
  const std::string path = ADJOIN_TEST_TMP + "/bouc-wen-" + std::to_string(++count) + ".toml";
  std::ofstream(path) << scene_text;
  return path;
}

}  // namespace

TEST_CASE("a Bouc-Wen storey law and a Bouc-Wen device in a scene file are read, defaults and all", "[bouc-wen]") {
  const std::string path = two_frames_with("{ model = \"bouc-wen\", yield_force = 9.0e4, hardening = 0.03, n = 3 }",
                                           "storeys = [1]\ntype = \"bouc-wen\"\nstiffness = 2.0e7\nyield_force = 4.0e4\nbeta = 0.9\n"
                                           "gamma = 0.1\n");
  const BuildingScene scene = load_building_scene(path, {"solver.t_end=2", "output.timeseries=false"});
  const StoreyHysteresis& y = scene.structure.a.hysteresis;
  CHECK(y.model == HysteresisModel::bouc_wen);
  CHECK(y.yield_forces[4] == 9.0e4);
  CHECK(y.hardening == 0.03);
  CHECK(y.n == 3.0);
  CHECK(y.beta == 0.5);  // (the defaults)
  CHECK(y.gamma == 0.5);
  const StoreyDevice& d = scene.structure.b->devices.back();
  CHECK(d.type == DeviceType::bouc_wen);
  CHECK(d.k == 2.0e7);
  CHECK(d.yield_force == 4.0e4);
  CHECK(d.n == 2.0);
  CHECK(d.beta == 0.9);
  CHECK(d.gamma == 0.1);
  // ... and runs: the channel A.hyst1 is z, within its saturation u_y (beta + gamma)^(-1/n).
  const Report r = run(scene);
  bool found = false;
  for (const auto& peak : r.peaks)
    if (peak.channel == "A.hyst1") {
      found = true;
      CHECK(peak.peak.max_abs > 0.0);
      CHECK(peak.peak.max_abs <= 9.0e4 / 5.482e6 * (1.0 + 1e-9));
    }
  CHECK(found);
  // --set edits the law's keys.
  const BuildingScene edited = load_building_scene(path, {"building.A.hysteresis.n=1", "building.A.hysteresis.gamma=0.2"});
  CHECK(edited.structure.a.hysteresis.n == 1.0);
  CHECK(edited.structure.a.hysteresis.gamma == 0.2);
}

TEST_CASE("a Bouc-Wen law whose implicit step has no solution stops with exit 3 naming the time and storey", "[bouc-wen][cli]") {
  // beta < |gamma|: unloading drives z away from zero (z' = w (1 + (beta' - gamma') z^n) changes
  // sign), until z's implicit equation has no root: a numerical failure, not a crash.
  const std::string path = two_frames_with("{ model = \"bouc-wen\", yield_force = 8.0e4, beta = -0.3, gamma = 0.5 }", "");
  const adjoin::test::CliResult r = adjoin::test::run_cli("run '" + path + "' --out '" + ADJOIN_TEST_TMP + "/bouc-wen-out'");
  INFO(r.err);
  CHECK(r.status == 3);
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK(r.err.find("the Bouc-Wen law of building A's storey") != std::string::npos);
  CHECK(r.err.find(" s; reduce solver.h (now 0.002 s)") != std::string::npos);
  CHECK(r.err.find("from t = ") != std::string::npos);
}
