// solver/structure_solver: the step for structures of any size (the two-block implicit schemes
// run on it: tests/test_two_block_outputs.cpp), a light block through its restarts, a linear building's steady
// state against its frequency response (a complex linear solve), its order 2, and the friction
// dampers' box QP against its optimality conditions.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <random>

#include <unsupported/Eigen/MatrixFunctions>

#include "../src/solver/banded.hpp"
#include "../src/solver/box_qp.hpp"
#include "../src/solver/dense_product.hpp"
#include "../src/solver/step_kernels.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/ground/record_motion.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/study/run.hpp"
#include "scene_helpers.hpp"
#include "state_recorder.hpp"

using namespace adjoin;
using namespace adjoin::structure;

namespace {

using Recorder = adjoin::test::StateRecorder;

}  // namespace

namespace {

// A 3-storey frame with 5 % Rayleigh damping, a Zener device in its first storey and a
// dashpot in its second.
Structure frame() {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::Vector3d(60e3, 60e3, 50e3);
  s.a.springs = Eigen::Vector3d(3e7, 2.5e7, 2e7);
  s.a.damping = {DampingModel::rayleigh, 0.05, 1, 2};
  StoreyDevice z;
  z.type = DeviceType::zener;
  z.storeys = {1};
  z.zener = {5e6, 0.5, 0.3, 0.01};
  StoreyDevice d;
  d.type = DeviceType::dashpot;
  d.storeys = {2};
  d.c = 2e5;
  s.a.devices = {z, d};
  return s;
}

class RoofPeak final : public StructureObserver {
 public:
  explicit RoofPeak(double from) : from_(from) {}
  void observe(const StructureState& s) override {
    if (s.t >= from_) peak = std::max(peak, std::abs(s.x[s.x.size() - 1]));
    roof.push_back(s.x[s.x.size() - 1]);
  }
  double peak = 0.0;
  std::vector<double> roof;

 private:
  double from_;
};

}  // namespace

TEST_CASE("a damped frame with a Zener storey reaches the steady state of its frequency response", "[structure_solver]") {
  const Structure s = frame();
  const double omega = 2 * M_PI / 0.7, u0 = 0.002;  // a_g = u0 omega^2 sin(omega t) [g]
  const DecayingSine ground(u0, omega, 0.0);
  StructureSolverOptions o;
  o.h = 0.0005;
  o.t_end = 60.0;
  RoofPeak peak(60.0 - 2 * 0.7);
  simulate_structure(o, s, ground, peak);
  // Steady state: X = (-w^2 M + i w C + K*(w))^-1 M 1 A, the Zener storey at its complex stiffness.
  const Eigen::MatrixXd m = mass_matrix(s.a);
  const Eigen::MatrixXd c = inherent_damping_matrix(s.a) + dashpot_matrix(s.a);
  const Eigen::MatrixXcd dyn = -omega * omega * m.cast<std::complex<double>>() +
                               std::complex<double>(0.0, omega) * c.cast<std::complex<double>>() + complex_stiffness_matrix(s.a, omega);
  const Eigen::VectorXcd force = (m * Eigen::Vector3d::Ones() * u0 * omega * omega * kStandardGravity).cast<std::complex<double>>();
  const Eigen::VectorXcd x = dyn.partialPivLu().solve(force);
  INFO("steady-state roof amplitude " << std::abs(x[2]) << ", simulated " << peak.peak);
  // The fractional device's transient decays as a power of t, not exponentially: 1e-3 after 60 s.
  CHECK(peak.peak == Approx(std::abs(x[2])).epsilon(2e-3));
}

TEST_CASE("two buildings joined by two friction links: second order, both dampers switching", "[structure_solver]") {
  Structure s = frame();
  s.b = s.a;
  s.b->name = "B";
  s.b->masses *= 1.5;
  s.b->devices.clear();
  for (int floor : {2, 3}) {
    Link l;
    l.type = LinkType::friction;
    l.floor_a = l.floor_b = floor;
    l.slip_force = floor == 2 ? 8e3 : 5e3;
    s.links.push_back(l);
  }
  const DecayingSine ground(0.05, 2 * M_PI / 0.8, 0.3);
  auto roof = [&](double h, std::vector<int>* switches) {
    StructureSolverOptions o;
    o.h = h;
    o.t_end = 8.0;
    class Obs final : public StructureObserver {
     public:
      void observe(const StructureState& st) override {
        x.push_back(st.x[2]);
        for (std::size_t l = 0; l < st.link_phase.size(); ++l) {
          if (count.size() < st.link_phase.size()) { count.assign(st.link_phase.size(), 0); last = st.link_phase; }
          if (st.link_phase[l] != last[l]) ++count[l];
        }
        last = st.link_phase;
      }
      std::vector<double> x;
      std::vector<int> count;
      std::vector<Phase> last;
    } obs;
    simulate_structure(o, s, ground, obs);
    if (switches) *switches = obs.count;
    return obs.x;
  };
  std::vector<int> fine_switches;
  const auto ref = roof(0.002 / 32, &fine_switches);
  REQUIRE(fine_switches.size() == 2);
  CHECK(fine_switches[0] >= 4);  // both dampers stick and slip repeatedly
  CHECK(fine_switches[1] >= 4);
  std::vector<double> errors;
  for (double h : {0.002, 0.001, 0.0005}) {
    std::vector<int> sw;
    const auto x = roof(h, &sw);
    CHECK(sw == fine_switches);
    const std::size_t stride = static_cast<std::size_t>(std::lround(h / (0.002 / 32)));
    double e = 0.0;
    for (std::size_t i = 0; i < x.size() && i * stride < ref.size(); ++i) e = std::max(e, std::abs(x[i] - ref[i * stride]));
    errors.push_back(e);
  }
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2]);
  CHECK(std::log2(errors[0] / errors[1]) > 1.8);
  CHECK(std::log2(errors[1] / errors[2]) > 1.8);
}

TEST_CASE("the dampers' box QP meets its optimality conditions", "[structure_solver][box_qp]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 8;  // up to 8 dampers
    Eigen::MatrixXd g(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) g(i, j) = u(random);
    const Eigen::MatrixXd s = g * g.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd w0(n), limit(n);
    for (int i = 0; i < n; ++i) {
      w0[i] = 3.0 * u(random);
      limit[i] = 0.05 + std::abs(u(random));
    }
    const auto r = detail::solve_box_qp(s, w0, limit);
    // Brute force over all 3^n stick/slip patterns: exactly one satisfies the inclusion, and it
    // is the active set's.
    int patterns = 1, found = 0;
    for (int i = 0; i < n; ++i) patterns *= 3;
    for (int code = 0; code < patterns; ++code) {
      std::vector<int> kind(n);
      for (int i = 0, c = code; i < n; ++i, c /= 3) kind[i] = c % 3;  // 0 stick, 1 +F, 2 -F
      Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
      std::vector<int> stuck;
      for (int i = 0; i < n; ++i) {
        if (kind[i] == 0) stuck.push_back(i);
        else q[i] = kind[i] == 1 ? limit[i] : -limit[i];
      }
      if (!stuck.empty()) {
        const int m = static_cast<int>(stuck.size());
        Eigen::MatrixXd a(m, m);
        Eigen::VectorXd b(m);
        for (int i = 0; i < m; ++i) {
          b[i] = w0[stuck[i]] - s.row(stuck[i]).dot(q);
          for (int j = 0; j < m; ++j) a(i, j) = s(stuck[i], stuck[j]);
        }
        const Eigen::VectorXd x = a.llt().solve(b);
        for (int i = 0; i < m; ++i) q[stuck[i]] = x[i];
      }
      const Eigen::VectorXd w = w0 - s * q;
      bool ok = true;
      for (int i = 0; i < n; ++i) {
        if (kind[i] == 0) ok = ok && std::abs(q[i]) <= limit[i];
        if (kind[i] == 1) ok = ok && w[i] >= 0.0;
        if (kind[i] == 2) ok = ok && w[i] <= 0.0;
      }
      if (!ok) continue;
      ++found;
      CHECK((q - r.q).cwiseAbs().maxCoeff() <= 1e-10 * limit.maxCoeff());
    }
    CHECK(found == 1);
    const Eigen::VectorXd w = w0 - s * r.q;
    for (int k = 0; k < n; ++k) {
      INFO("trial " << trial << ", damper " << k);
      CHECK(std::abs(r.q[k]) <= limit[k] * (1 + 1e-12));
      if (r.state[k] == detail::DamperState::stick) CHECK(std::abs(w[k]) <= 1e-10);
      if (r.state[k] == detail::DamperState::slip_positive) { CHECK(r.q[k] == limit[k]); CHECK(w[k] >= -1e-10); }
      if (r.state[k] == detail::DamperState::slip_negative) { CHECK(r.q[k] == -limit[k]); CHECK(w[k] <= 1e-10); }
    }
    if (n == 1) {  // the closed form
      const double stuck = w0[0] / s(0, 0);
      CHECK(r.q[0] == Approx(std::clamp(stuck, -limit[0], limit[0])).epsilon(1e-14));
    }
  }
}

TEST_CASE("one damper's held solve equals the held sets' general path bit for bit", "[structure_solver][box_qp]") {
  // solve_held with one unknown and no candidate list takes S_00^-1 w0 (SubsetInverses::single);
  // with the candidate list {0} it goes through the sets' lists and lookup: the same numbers.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::MatrixXd s = Eigen::MatrixXd::Constant(1, 1, 0.1 + std::abs(u(random)) * std::pow(10.0, 3.0 * u(random)));
    detail::BoxQp single(s), general(s);
    const std::vector<int> candidates{0};
    for (const char held : {char{1}, char{0}}) {
      const Eigen::VectorXd w0 = Eigen::VectorXd::Constant(1, 5.0 * u(random));
      const Eigen::VectorXd fixed = Eigen::VectorXd::Constant(1, held ? 0.0 : u(random));
      Eigen::VectorXd q_single(1), q_general(1);
      single.solve_held(w0, {held}, fixed, &q_single);
      general.solve_held(w0, {held}, fixed, &q_general, &candidates);
      INFO("trial " << trial << ", held " << int{held});
      CHECK(q_single[0] == q_general[0]);
      if (held) CHECK(q_single[0] == Approx(w0[0] / s(0, 0)).epsilon(1e-14));
      else CHECK(q_single[0] == fixed[0]);
    }
  }
}

TEST_CASE("held-set inverses updated by bordering equal those inverted from scratch", "[structure_solver][box_qp]") {
  // A walk over index sets, each one or two elements from the last (as sticking dampers and
  // yielding storeys change them), on a symmetric positive definite matrix and on one with
  // negative diagonal entries (slipping bilinear elements' rows); each set's inverse against
  // a direct inversion of its submatrix.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 30;
  Eigen::MatrixXd g(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g(i, j) = u(random);
  const Eigen::MatrixXd spd = g * g.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd indefinite = spd;
  for (int i = 0; i < n; i += 5) indefinite(i, i) = -indefinite(i, i);
  const std::array<const Eigen::MatrixXd*, 2> matrices = {&spd, &indefinite};
  for (const Eigen::MatrixXd* s : matrices) {
    detail::SubsetInverses inverses(*s);
    std::vector<char> in(n, 1);
    int updated = 0;
    for (int step = 0; step < 300; ++step) {
      const int changes = 1 + step % 2;
      for (int c = 0; c < changes; ++c) in[static_cast<std::size_t>(random() % n)] ^= 1;
      std::vector<int> set;
      for (int i = 0; i < n; ++i)
        if (in[i]) set.push_back(i);
      if (set.empty()) continue;
      const auto& sys = inverses.of(set);
      if (sys.generation > 0) ++updated;
      const int m = static_cast<int>(set.size());
      Eigen::MatrixXd a(m, m);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) a(i, j) = (*s)(set[i], set[j]);
      const Eigen::MatrixXd direct = a.partialPivLu().inverse();
      INFO("step " << step << ", generation " << sys.generation);
      CHECK((sys.inverse - direct).cwiseAbs().maxCoeff() <= 1e-9 * direct.cwiseAbs().maxCoeff());
      CHECK((a * sys.inverse - Eigen::MatrixXd::Identity(m, m)).cwiseAbs().maxCoeff() <= 1e-9);
    }
    // Most new sets came from the last by an update (the walk revisits few sets).
    CHECK(updated > 150);
  }
}

TEST_CASE("small held sets are updated by bordering only when they hold a slipping bilinear element", "[structure_solver][box_qp]") {
  // Small sets (below kMinUpdateSize) of dampers (0..4, positive diagonal) and bilinear
  // elements (5..9, negative diagonal, after the dampers): a set holding an element is the
  // last one's update (up to kMaxChanges changes, kMaxGeneration in a row), accurate; a
  // dampers-only set is inverted from scratch (its rounding that of the inversion).
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 10;
  Eigen::MatrixXd g(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g(i, j) = u(random);
  Eigen::MatrixXd s = g * g.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
  for (int i = 5; i < n; ++i) s(i, i) = -10.0 * s(i, i);
  detail::SubsetInverses inverses(s);
  std::vector<char> in(n, 0);
  in[0] = in[5] = 1;
  int updated = 0, generation = 0;
  for (int step = 0; step < 400; ++step) {
    const int changes = 1 + step % detail::SubsetInverses::kMaxChanges;
    for (int c = 0; c < changes; ++c) in[static_cast<std::size_t>(random() % n)] ^= 1;
    std::vector<int> set;
    for (int i = 0; i < n; ++i)
      if (in[i]) set.push_back(i);
    if (set.empty() || set.size() >= detail::SubsetInverses::kMinUpdateSize) continue;
    const auto& sys = inverses.of(set);
    const bool holds_element = set.back() >= 5;
    INFO("step " << step << ", generation " << sys.generation);
    if (!holds_element) CHECK(sys.generation == 0);
    if (sys.generation > 0) ++updated;
    generation = std::max(generation, sys.generation);
    const int m = static_cast<int>(set.size());
    Eigen::MatrixXd a(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) a(i, j) = s(set[i], set[j]);
    const Eigen::MatrixXd direct = a.partialPivLu().inverse();
    CHECK((sys.inverse - direct).cwiseAbs().maxCoeff() <= 1e-10 * direct.cwiseAbs().maxCoeff());
  }
  CHECK(updated > 20);
  CHECK(generation <= detail::SubsetInverses::kMaxGeneration);
}

namespace {

// The exact response of one mode, q'' + 2 z w q' + w^2 q = p(t) with p piecewise linear
// between grid points (the same input the step sees), by the exponential of the augmented
// system [q, q', p, p'] over one step: exact to rounding (the recursion the spectra use).
std::vector<double> exact_mode(double w, double z, const std::vector<double>& p, double h) {
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a(0, 1) = 1.0;
  a(1, 0) = -w * w;
  a(1, 1) = -2.0 * z * w;
  a(1, 2) = 1.0;
  a(2, 3) = 1.0;
  const Eigen::Matrix4d e = (a * h).exp();
  std::vector<double> q(p.size(), 0.0);
  Eigen::Vector4d y(0.0, 0.0, p[0], 0.0);
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    y[2] = p[i];
    y[3] = (p[i + 1] - p[i]) / h;
    y = e * y;
    q[i + 1] = y[0];
  }
  return q;
}

}  // namespace

TEST_CASE("a linear building equals exact modal superposition and converges at order 2", "[structure_solver][modal]") {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::Vector4d(50e3, 50e3, 50e3, 40e3);
  s.a.springs = Eigen::Vector4d(4e7, 3.5e7, 3e7, 2.5e7);
  s.a.damping = {DampingModel::modal, 0.05, 1, 2};
  const DecayingSine ground(0.02, 2 * M_PI / 0.6, 0.4);  // a_g in g
  const Modes modes = building_modes(s.a);
  const Eigen::VectorXd gamma = modes.shapes.transpose() * s.a.masses;  // participation (phi' M 1)
  std::vector<double> errors;
  for (double h : {0.004, 0.002, 0.001, 0.0005, 0.00025, 0.000125, 0.0000625}) {
    StructureSolverOptions o;
    o.h = h;
    o.t_end = 6.0;
    RoofPeak roof(0.0);
    simulate_structure(o, s, ground, roof);
    std::vector<double> p(roof.roof.size());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = kStandardGravity * ground.ag(static_cast<double>(i) * h);
    std::vector<double> exact(p.size(), 0.0);
    for (int n = 0; n < 4; ++n) {
      std::vector<double> pn(p.size());
      for (std::size_t i = 0; i < p.size(); ++i) pn[i] = gamma[n] * p[i];
      const auto q = exact_mode(modes.omega[n], 0.05, pn, h);
      for (std::size_t i = 0; i < p.size(); ++i) exact[i] += modes.shapes(3, n) * q[i];
    }
    double e = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      e = std::max(e, std::abs(roof.roof[i] - exact[i]));
      scale = std::max(scale, std::abs(exact[i]));
    }
    errors.push_back(e / scale);
  }
  INFO("relative errors " << errors[0] << " ... " << errors.back());
  for (std::size_t i = 1; i < errors.size(); ++i) CHECK(std::log2(errors[i - 1] / errors[i]) == Approx(2.0).margin(0.1));
  CHECK(errors.back() < 1e-6);  // at h = 6.25e-5
}

TEST_CASE("friction limits: no slip force leaves the buildings apart, a huge one joins the floors", "[structure_solver]") {
  Structure apart;
  apart.a.name = "A";
  apart.a.masses = Eigen::VectorXd::Constant(1, 1e5);
  apart.a.springs = Eigen::VectorXd::Constant(1, 4e6);
  apart.a.damping = {DampingModel::modal, 0.02, 1, 2};
  Building b = apart.a;
  b.name = "B";
  b.masses[0] = 3e5;
  b.springs[0] = 2e6;
  apart.b = b;
  const DecayingSine ground(0.05, 2 * M_PI / 1.2, 0.3);
  StructureSolverOptions o;
  o.h = 0.002;
  o.t_end = 10.0;
  auto roofs = [&](const Structure& st) {
    Recorder r;
    simulate_structure(o, st, ground, r);
    return r.states;
  };
  const auto free = roofs(apart);
  Structure tiny = apart, huge = apart;
  Link l;
  l.type = LinkType::friction;
  l.slip_force = 1e-9;  // N
  tiny.links.push_back(l);
  l.slip_force = 1e12;
  huge.links.push_back(l);
  const auto t = roofs(tiny);
  double d = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < free.size(); ++i) {
    d = std::max({d, std::abs(t[i].x[0] - free[i].x[0]), std::abs(t[i].x[1] - free[i].x[1])});
    scale = std::max(scale, std::abs(free[i].x[0]));
  }
  CHECK(d < 1e-12 * scale);
  // Rigidly joined: one mass m_A + m_B on k_A + k_B, with damping c_A + c_B.
  Structure one;
  one.a.name = "A";
  one.a.masses = Eigen::VectorXd::Constant(1, 4e5);
  one.a.springs = Eigen::VectorXd::Constant(1, 6e6);
  StoreyDevice dash;
  dash.type = DeviceType::dashpot;
  dash.storeys = {1};
  dash.c = 2 * 0.02 * std::sqrt(4e6 * 1e5) + 2 * 0.02 * std::sqrt(2e6 * 3e5);
  one.a.devices = {dash};
  const auto joined = roofs(one);
  const auto h = roofs(huge);
  double dj = 0.0;
  for (std::size_t i = 0; i < joined.size(); ++i) {
    dj = std::max({dj, std::abs(h[i].x[0] - joined[i].x[0]), std::abs(h[i].x[1] - joined[i].x[0])});
    CHECK(h[i].link_phase[0] == Phase::stick);
  }
  CHECK(dj < 1e-10 * scale);
}

TEST_CASE("three friction dampers on two 20-storey buildings under a record: finite, within their limits", "[structure_solver]") {
  // A damper whose slip ends while another slips (this once produced NaN: a held damper
  // started from its last slipping bound, which was infinite).
  Structure s;
  auto building = [&](const char* name, double mass, double k) {
    Building b;
    b.name = name;
    b.masses = Eigen::VectorXd::Constant(20, mass);
    b.springs = Eigen::VectorXd::Constant(20, k);
    b.damping = {DampingModel::modal, 0.05, 1, 2};
    StoreyDevice d;
    d.type = DeviceType::zener;
    for (int i = 1; i <= 20; ++i) d.storeys.push_back(i);
    d.zener = {0.2 * k, 0.5, 0.2, 0.01};
    b.devices.push_back(d);
    return b;
  };
  s.a = building("A", 5e5, 8e8);
  s.b = building("B", 4e5, 6e8);
  for (int floor : {6, 13, 20}) {
    Link l;
    l.type = LinkType::friction;
    l.floor_a = l.floor_b = floor;
    l.slip_force = 2e5;
    s.links.push_back(l);
  }
  const RecordMotion ground(read_record(std::string(ADJOIN_REAL_RECORDS) + "/peer/RSN1044_DirRot2.AT2"), 1.0, kStandardGravity);
  StructureSolverOptions o;
  o.h = 0.005;
  o.t_end = 8.0;
  Recorder r;
  simulate_structure(o, s, ground, r);
  std::vector<int> switches(3, 0);
  for (std::size_t i = 1; i < r.states.size(); ++i)
    for (int l = 0; l < 3; ++l) {
      REQUIRE(std::isfinite(r.states[i].link_force[l]));
      CHECK(std::abs(r.states[i].link_force[l]) <= 2e5 * (1 + 1e-12));
      if (r.states[i].link_phase[l] == Phase::stick) CHECK(r.states[i].link_velocity[l] == 0.0);  // stick exact
      if (r.states[i].link_phase[l] != r.states[i - 1].link_phase[l]) ++switches[l];
    }
  for (int l = 0; l < 3; ++l) CHECK(switches[l] >= 2);
}

TEST_CASE("the structure step's kernels equal the Eigen expressions they replace bit for bit, on both processor paths", "[structure_solver][kernels]") {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vec = [&](Eigen::Index n) {
    Eigen::VectorXd v(n);
    for (auto& x : v) x = u(random) * std::pow(10.0, 3.0 * u(random));
    return v;
  };
  for (const detail::StepKernels* k : {&detail::baseline_step_kernels(), &detail::step_kernels()}) {
    for (Eigen::Index n : {3, 4, 7, 20, 41}) {
      INFO("n = " << n);
      const Eigen::VectorXd m = vec(n).cwiseAbs(), x = vec(n), v = vec(n), cv = vec(n), p0 = vec(n), off = vec(n);
      const Eigen::VectorXd lo = vec(n - 1), di = vec(n), up = vec(n - 1);
      const detail::Tridiagonal band{lo.data(), di.data(), up.data()};
      Eigen::MatrixXd kd = Eigen::MatrixXd::Zero(n, n);
      kd.diagonal() = di;
      kd.diagonal(-1) = lo;
      kd.diagonal(1) = up;
      const double c = 0.0025, s = 1.7;
      // The free step: x1 = x + c v, p = K x1 (each row summed as a dense row is: left to right),
      // rhs = m v + c (m s - cv - p0 - p - off).
      Eigen::VectorXd x1(n), p(n), rhs(n);
      k->free_rhs(n, m.data(), x.data(), v.data(), cv.data(), p0.data(), off.data(), band, c, s, x1.data(), p.data(), rhs.data());
      const Eigen::VectorXd x1_e = x + c * v;
      Eigen::VectorXd p_e(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        double sum = 0.0;
        bool first = true;
        for (Eigen::Index j = std::max<Eigen::Index>(i - 1, 0); j <= std::min(i + 1, n - 1); ++j) {
          sum = first ? kd(i, j) * x1_e[j] : sum + kd(i, j) * x1_e[j];
          first = false;
        }
        p_e[i] = sum;
      }
      CHECK(x1 == x1_e);
      CHECK(p == p_e);
      CHECK(rhs == m.cwiseProduct(v) + c * (m * s - cv - p0 - p_e - off));
      Eigen::VectorXd pb(n);
      k->band(n, band, x1_e.data(), pb.data());
      CHECK(pb == p_e);
      // The end of the step.
      const Eigen::VectorXd rv = vec(n), rc = vec(n);
      Eigen::VectorXd v1(n), cv1(n), x2(n), a(n), f = Eigen::VectorXd::Zero(n), y = cv;
      k->end_velocities(n, v.data(), cv.data(), rv.data(), rc.data(), 0.005, v1.data(), cv1.data());
      CHECK(v1 == v - 0.005 * rv);
      CHECK(cv1 == cv - 0.005 * rc);
      k->trapezoid(n, x.data(), v.data(), v1.data(), c, x2.data());
      CHECK(x2 == x + c * (v + v1));
      const Eigen::VectorXd inv_m = m.cwiseInverse();
      k->accelerations(n, m.data(), inv_m.data(), cv.data(), p0.data(), s, a.data());
      CHECK(a == (m * s - cv - p0).cwiseProduct(inv_m) - Eigen::VectorXd::Constant(n, s));
      k->drifts(n, m.data(), di.data(), x.data(), v.data(), f.data());
      CHECK(f.tail(n - 1) == m.tail(n - 1).cwiseProduct(x.tail(n - 1) - x.head(n - 1)) +
                                 di.tail(n - 1).cwiseProduct(v.tail(n - 1) - v.head(n - 1)));
      k->axpy(n, 0.37, rv.data(), y.data());
      CHECK(y == cv + rv * 0.37);
      CHECK_FALSE(k->out_of_range(n, x.data(), v.data(), x.cwiseAbs().maxCoeff()));
      CHECK(k->out_of_range(n, x.data(), v.data(), 0.999 * x.cwiseAbs().maxCoeff()));
      Eigen::VectorXd bad = v;
      bad[n / 2] = std::numeric_limits<double>::infinity();
      CHECK(k->out_of_range(n, x.data(), bad.data(), 1e300));
      bad[n / 2] = std::numeric_limits<double>::quiet_NaN();
      CHECK(k->out_of_range(n, bad.data(), v.data(), 1e300));
      // m q summed in column order from the first product, as a row of the matrix alone.
      for (Eigen::Index cols : {1, 3, 6}) {
        Eigen::MatrixXd mm(n, cols);
        for (auto& e : mm.reshaped()) e = u(random);
        const Eigen::VectorXd q = vec(cols);
        Eigen::VectorXd out(n), out_e(n);
        k->columns(n, cols, mm.data(), q.data(), out.data());
        for (Eigen::Index r = 0; r < n; ++r) out_e[r] = mm.row(r).dot(q);
        CHECK(out == out_e);
      }
      // The listed columns of a taller matrix (its first n rows), as the solver summed them
      // with Eigen: from zero, q_k times column k added in the list's order (fewer than four,
      // and four at a time with the rest after; none: zeros).
      Eigen::MatrixXd tall(n + 5, 10);
      for (auto& e : tall.reshaped()) e = u(random);
      const Eigen::VectorXd q = vec(10);
      for (const std::vector<int>& which : {std::vector<int>{}, std::vector<int>{7}, std::vector<int>{1, 2, 4}, std::vector<int>{2, 0, 9, 3},
                                            std::vector<int>{0, 1, 3, 4, 6, 7, 8, 9, 5}}) {
        Eigen::VectorXd out = Eigen::VectorXd::Constant(n, 3.0), out_e = Eigen::VectorXd::Zero(n);
        k->some_columns(n, tall.rows(), static_cast<Eigen::Index>(which.size()), which.data(), tall.data(), q.data(), out.data());
        for (int col : which) out_e.noalias() += q[col] * tall.col(col).head(n);
        CHECK(out == out_e);
      }
    }
  }
  // The dense product against Eigen's, across the row blocks (16, 4, the last 1 to 3 rows in
  // masked lanes) and the switch to Eigen itself from 128 columns.
  for (Eigen::Index rows : {1, 2, 3, 5, 6, 7, 20, 37, 80})
    for (Eigen::Index cols : {1, 3, 20, 130}) {
      Eigen::MatrixXd a(rows, cols);
      for (auto& e : a.reshaped()) e = u(random);
      const Eigen::VectorXd x = vec(cols);
      const detail::DenseProduct product(a);
      Eigen::VectorXd y(rows);
      product.apply(x.data(), y.data());
      const Eigen::VectorXd y_e = a * x;
      INFO(rows << " x " << cols);
      CHECK(y == y_e);
      if (rows > 2) {
        // (Two places past the rows asked for: the masked lanes write nothing there.)
        Eigen::VectorXd part = Eigen::VectorXd::Constant(rows, 7.0);
        product.apply(x.data(), part.data(), 1, rows - 2);
        // (From 128 columns it is Eigen's product of those rows, which for one row is a dot
        // product summed in another order than the whole product's.)
        const Eigen::VectorXd part_e = cols < 128 ? Eigen::VectorXd(y_e.segment(1, rows - 2))
                                                  : Eigen::VectorXd(a.middleRows(1, rows - 2) * x);
        CHECK(part.head(rows - 2) == part_e);
        CHECK(part.tail(2) == Eigen::VectorXd::Constant(2, 7.0));
      }
      if (rows % 2 == 0) {  // both halves in one call: each half's rows as apply() gives them
        const Eigen::Index half = rows / 2;
        Eigen::VectorXd top(half), bottom(half), top_e(half), bottom_e(half);
        product.apply_halves(x.data(), top.data(), bottom.data());
        product.apply(x.data(), top_e.data(), 0, half);
        product.apply(x.data(), bottom_e.data(), half, half);
        CHECK(top == top_e);
        CHECK(bottom == bottom_e);
        if (cols < 128) CHECK(bottom == Eigen::VectorXd(y_e.tail(half)));
      }
    }
}

TEST_CASE("the banded stiffness product equals the dense product bit for bit, one to six floors", "[structure_solver][kernels]") {
  // (Two floors take a path of their own, the two-block scene's; three and more the band
  // kernel, with entries right of the band; an entry left of it, the general loops.)
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 1; n <= 6; ++n)
    for (const bool left : {false, true}) {
      Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
      for (int i = 0; i < n; ++i) {
        k(i, i) = 2.0 + u(random);
        if (i + 1 < n) {
          k(i, i + 1) = u(random);
          k(i + 1, i) = u(random);
        }
      }
      if (n >= 4) k(0, n - 1) = u(random);  // right of the band (a link's entry)
      if (n >= 4 && left) k(n - 1, 0) = u(random);
      Eigen::VectorXd x(n), p(n);
      for (int i = 0; i < n; ++i) x[i] = u(random);
      detail::Banded(k).apply(x, p);
      INFO(n << " floors" << (left ? ", an entry left of the band" : ""));
      CHECK(p == Eigen::VectorXd(k * x));
    }
}

namespace {

// Counts the friction links' switches (phase changes between grid points) and keeps the
// roof's peak |x| of building A.
class Switches final : public StructureObserver {
 public:
  void observe(const StructureState& s) override {
    if (!last_.empty())
      for (std::size_t l = 0; l < last_.size(); ++l) count += s.link_phase[l] != last_[l] ? 1 : 0;
    last_ = s.link_phase;
    peak = std::max(peak, std::abs(s.x[roof]));
  }
  int roof = 0;
  int count = 0;
  double peak = 0.0;

 private:
  std::vector<Phase> last_;
};

using Restart = StructureSolverOptions::Restart;

}  // namespace

TEST_CASE("the paper's system with a light block: the restart after a switch keeps the true switches", "[structure_solver][restart]") {
  // rho = 1e5: block 2's mode has omega h = 6.3 at h = 0.002, unresolved. The implicit scheme
  // takes a backward-Euler step after each switch there (10 switches, the true count), whether
  // the two-block scene runs it or the structure solver is called directly (the same step: to
  // rounding). Without the restart the motion departs from it. (The implicit schemes' two-block
  // outputs before they ran on the structure solver: tests/test_two_block_outputs.cpp.)
  const double h = 0.002;
  const Scene scene =
      test::paper_scene("strong", {"solver.scheme=implicit", "solver.history=fft", "model.rho=1e5", "solver.h=0.002"});
  Recorder two_block;  // the scene's run: its 1 + 1 structure's states (A.x1, B.x1, link 1)
  run(scene, {&two_block});
  const Structure s = structure_of(scene);
  const ScaledGround ground(*scene.ground, 1.0 / kStandardGravity);
  StructureSolverOptions o;
  o.h = h;
  o.t_end = scene.solver.t_end;
  Recorder general;
  simulate_structure(o, s, ground, general);
  REQUIRE(general.states.size() == two_block.states.size());
  double dx = 0.0, dq = 0.0, scale_x = 0.0;
  int switches = 0;
  for (std::size_t i = 0; i < general.states.size(); ++i) {
    const auto& a = general.states[i];
    const auto& b = two_block.states[i];
    scale_x = std::max({scale_x, std::abs(b.x[0]), std::abs(b.x[1])});
    dx = std::max({dx, std::abs(a.x[0] - b.x[0]), std::abs(a.x[1] - b.x[1])});
    dq = std::max(dq, std::abs(a.link_force[0] - b.link_force[0]));
    if (i > 0 && a.link_phase[0] != general.states[i - 1].link_phase[0]) ++switches;
  }
  INFO("dx " << dx << " dq " << dq);
  CHECK(dx < 1e-12 * scale_x);
  CHECK(dq < 1e-12 * two_block_model(scene).mu);
  CHECK(switches == 10);
  o.restart = Restart::never;
  Recorder trapezoidal;
  simulate_structure(o, s, ground, trapezoidal);
  double dx_trapezoidal = 0.0;
  for (std::size_t i = 0; i < trapezoidal.states.size(); ++i)
    dx_trapezoidal = std::max(dx_trapezoidal, std::abs(trapezoidal.states[i].x[1] - two_block.states[i].x[1]));
  INFO("without the restart: dx " << dx_trapezoidal);
  CHECK(dx_trapezoidal > 1e-6 * scale_x);
}

namespace {

// Building A's second floor is light (20 kg between storeys of 2e7 and 1.8e7 N/m: a local mode
// at 1378 rad/s, omega h = 6.9 at h = 5 ms) and carries the friction damper to building B.
Structure light_floor() {
  Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::Vector3d(5e4, 20.0, 4e4);
  s.a.springs = Eigen::Vector3d(2e7, 2e7, 1.8e7);
  s.a.damping = {DampingModel::modal, 0.01, 1, 2};
  Building b;
  b.name = "B";
  b.masses = Eigen::Vector2d(6e4, 5e4);
  b.springs = Eigen::Vector2d(1.5e7, 1.2e7);
  b.damping = {DampingModel::modal, 0.01, 1, 2};
  s.b = b;
  Link l;
  l.type = LinkType::friction;
  l.floor_a = l.floor_b = 2;
  l.slip_force = 5e3;
  s.links.push_back(l);
  return s;
}

}  // namespace

TEST_CASE("a building with a mode unresolved by the step: the restart after a switch removes the spurious switches", "[structure_solver][restart]") {
  const Structure s = light_floor();
  const DecayingSine ground(0.05, 2 * M_PI / 0.8, 0.3);
  auto switches = [&](double h, Restart restart) {
    StructureSolverOptions o;
    o.h = h;
    o.t_end = 8.0;
    o.restart = restart;
    Switches c;
    c.roof = 2;
    simulate_structure(o, s, ground, c);
    return c.count;
  };
  // omega h = 0.17: resolved, no restart applies; the count is settled (the same at half the step).
  const int truth = switches(0.000125, Restart::automatic);
  CHECK(truth == switches(0.0000625, Restart::automatic));
  CHECK(truth == 51);
  // Trapezoidal throughout at h = 5 ms: the light floor rings after each switch and drives the
  // damper through hundreds of spurious switches.
  const int chatter = switches(0.005, Restart::never);
  INFO("trapezoidal: " << chatter << " switches, true: " << truth);
  CHECK(chatter > 5 * truth);
  // With the restart (automatic: omega h > 1), the true count at every unresolved step.
  for (double h : {0.005, 0.0025, 0.002, 0.001}) {
    INFO("h = " << h);
    CHECK(switches(h, Restart::automatic) == truth);
  }
}

TEST_CASE("with the restart after every switch a resolved building's peaks and motion still converge at order 2", "[structure_solver][restart]") {
  // The two-friction-link frames of the test above (every mode resolved) with Restart::always:
  // one backward-Euler step per switch adds finitely many O(h^2) local errors.
  Structure s = frame();
  s.b = s.a;
  s.b->name = "B";
  s.b->masses *= 1.5;
  s.b->devices.clear();
  for (int floor : {2, 3}) {
    Link l;
    l.type = LinkType::friction;
    l.floor_a = l.floor_b = floor;
    l.slip_force = floor == 2 ? 8e3 : 5e3;
    s.links.push_back(l);
  }
  const DecayingSine ground(0.05, 2 * M_PI / 0.8, 0.3);
  auto run = [&](double h, Restart restart, std::vector<double>* roof) {
    StructureSolverOptions o;
    o.h = h;
    o.t_end = 8.0;
    o.restart = restart;
    class Obs final : public StructureObserver {
     public:
      void observe(const StructureState& st) override {
        x.push_back(st.x[2]);
        peak = std::max(peak, std::abs(st.x[2]));
      }
      std::vector<double> x;
      double peak = 0.0;
    } obs;
    simulate_structure(o, s, ground, obs);
    if (roof) *roof = obs.x;
    return obs.peak;
  };
  std::vector<double> ref;
  const double ref_peak = run(0.002 / 32, Restart::always, &ref);
  std::vector<double> errors, peak_errors, trapezoidal;
  for (double h : {0.002, 0.001, 0.0005}) {
    std::vector<double> x;
    peak_errors.push_back(std::abs(run(h, Restart::always, &x) - ref_peak));
    const std::size_t stride = static_cast<std::size_t>(std::lround(h / (0.002 / 32)));
    double e = 0.0;
    for (std::size_t i = 0; i < x.size() && i * stride < ref.size(); ++i) e = std::max(e, std::abs(x[i] - ref[i * stride]));
    errors.push_back(e);
    std::vector<double> t;
    run(h, Restart::never, &t);
    double d = 0.0;
    for (std::size_t i = 0; i < t.size() && i * stride < ref.size(); ++i) d = std::max(d, std::abs(t[i] - ref[i * stride]));
    trapezoidal.push_back(d);
  }
  INFO("roof errors " << errors[0] << " " << errors[1] << " " << errors[2] << ", peak errors " << peak_errors[0] << " "
                      << peak_errors[1] << " " << peak_errors[2] << ", trapezoidal throughout " << trapezoidal[0] << " "
                      << trapezoidal[1] << " " << trapezoidal[2]);
  CHECK(std::log2(errors[0] / errors[1]) > 1.8);
  CHECK(std::log2(errors[1] / errors[2]) > 1.8);
  CHECK(std::log2(peak_errors[0] / peak_errors[2]) > 2 * 1.8);
}
