// structure/ and the modal analysis: closed-form frequencies of a uniform shear building, the
// stiffness found for a period, damping ratios against the complex eigenvalues of the damped
// system (an independent computation), the Zener storeys' equivalent ratio, the coupled
// system's periods with links free and locked, building scenes read with their errors, and
// participation factors and effective masses (closed form; `adjoin modes` prints them).
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>

#include <Eigen/Eigenvalues>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/structure/modal.hpp"
#include "cli_helpers.hpp"
#include "scene_helpers.hpp"

using namespace adjoin;
using namespace adjoin::structure;

namespace {

Building uniform(int n, double m, double k) {
  Building b;
  b.name = "A";
  b.masses = Eigen::VectorXd::Constant(n, m);
  b.springs = Eigen::VectorXd::Constant(n, k);
  return b;
}

// Damping ratios from the eigenvalues s of M s^2 + C s + K = 0 (state-space form), sorted by
// |s|: zeta = -Re(s) / |s|. Independent of the modal formulas in the library.
std::vector<double> ratios_from_complex_eigenvalues(const Eigen::MatrixXd& m, const Eigen::MatrixXd& c, const Eigen::MatrixXd& k) {
  const int n = static_cast<int>(m.rows());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  const Eigen::MatrixXd m_inv = m.inverse();
  a.topRightCorner(n, n) = Eigen::MatrixXd::Identity(n, n);
  a.bottomLeftCorner(n, n) = -m_inv * k;
  a.bottomRightCorner(n, n) = -m_inv * c;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(a);
  std::vector<std::complex<double>> s;
  for (int i = 0; i < 2 * n; ++i)
    if (solver.eigenvalues()[i].imag() > 0.0) s.push_back(solver.eigenvalues()[i]);
  std::sort(s.begin(), s.end(), [](auto x, auto y) { return std::abs(x) < std::abs(y); });
  std::vector<double> zeta;
  for (auto v : s) zeta.push_back(-v.real() / std::abs(v));
  return zeta;
}

}  // namespace

TEST_CASE("a uniform shear building has the closed-form frequencies", "[modal]") {
  const int n = 5;
  const double m = 45e3, k = 5.482e6;
  const Modes modes = building_modes(uniform(n, m, k));
  for (int j = 1; j <= n; ++j) {
    const double exact = 2.0 * std::sqrt(k / m) * std::sin((2 * j - 1) * M_PI / (2.0 * (2 * n + 1)));
    CHECK(modes.omega[j - 1] == Approx(exact).epsilon(1e-12));
    CHECK(modes.periods[j - 1] == Approx(2 * M_PI / exact).epsilon(1e-12));
  }
  // Mass-normalised, positive at the roof.
  const Eigen::MatrixXd phi = modes.shapes;
  CHECK((phi.transpose() * Eigen::MatrixXd(Eigen::VectorXd::Constant(n, m).asDiagonal()) * phi - Eigen::MatrixXd::Identity(n, n)).norm() < 1e-10);
  for (int j = 0; j < n; ++j) CHECK(phi(n - 1, j) > 0.0);
}

TEST_CASE("the storey stiffness found for a period gives that period", "[modal]") {
  Eigen::VectorXd masses(3);
  masses << 60e3, 60e3, 50e3;
  const double k = stiffness_for_period(masses, 0.5);
  Building b;
  b.masses = masses;
  b.springs = Eigen::VectorXd::Constant(3, k);
  CHECK(building_modes(b).periods[0] == Approx(0.5).epsilon(1e-12));
  // One storey: k = m (2 pi / T)^2 exactly.
  CHECK(stiffness_for_period(Eigen::VectorXd::Constant(1, 2.0), 1.0) == Approx(2.0 * 4 * M_PI * M_PI).epsilon(1e-14));
}

TEST_CASE("inherent damping ratios agree with the damped system's complex eigenvalues", "[modal]") {
  Building b = uniform(4, 1e5, 8e7);
  b.springs[3] = 5e7;  // not uniform
  SECTION("modal: every mode at the ratio") {
    b.damping = {DampingModel::modal, 0.05, 1, 2};
    const Modes modes = building_modes(b);
    const auto exact = ratios_from_complex_eigenvalues(mass_matrix(b), inherent_damping_matrix(b), stiffness_matrix(b.static_stiffness()));
    for (int j = 0; j < 4; ++j) {
      CHECK(modes.inherent_ratio[j] == Approx(0.05).epsilon(1e-10));
      CHECK(exact[j] == Approx(0.05).epsilon(1e-8));
    }
  }
  SECTION("rayleigh: the ratio at the two chosen modes, a0/(2w) + a1 w/2 at the others") {
    b.damping = {DampingModel::rayleigh, 0.05, 1, 3};
    const Modes modes = building_modes(b);
    const auto exact = ratios_from_complex_eigenvalues(mass_matrix(b), inherent_damping_matrix(b), stiffness_matrix(b.static_stiffness()));
    CHECK(modes.inherent_ratio[0] == Approx(0.05).epsilon(1e-10));
    CHECK(modes.inherent_ratio[2] == Approx(0.05).epsilon(1e-10));
    CHECK(modes.inherent_ratio[1] < 0.05);  // between the fitted modes Rayleigh damps less
    CHECK(modes.inherent_ratio[3] > 0.05);  // above them more
    for (int j = 0; j < 4; ++j) CHECK(exact[j] == Approx(modes.inherent_ratio[j]).epsilon(1e-8));
  }
}

TEST_CASE("a Zener storey's equivalent damping ratio is its loss at the mode's frequency", "[modal]") {
  Building b = uniform(1, 2e5, 0.0);
  StoreyDevice d;
  d.type = DeviceType::zener;
  d.storeys = {1};
  d.zener = {8e6, 0.4, 0.5, 0.02};
  b.devices.push_back(d);
  const Modes modes = building_modes(b);
  const double w = std::sqrt(8e6 / 2e5);
  CHECK(modes.omega[0] == Approx(w).epsilon(1e-12));
  // K*(w) = k (1 + tau_x (i w)^a) / (1 + tau_f (i w)^a), from exp(a log(i w)).
  const std::complex<double> iwa = std::exp(0.4 * std::log(std::complex<double>(0.0, w)));
  const std::complex<double> kstar = 8e6 * (1.0 + 0.5 * iwa) / (1.0 + 0.02 * iwa);
  CHECK(modes.device_ratio[0] == Approx(kstar.imag() / (2.0 * 8e6)).epsilon(1e-12));
  CHECK(modes.zener_stiffening[0] == Approx(kstar.real() / 8e6).epsilon(1e-12));
  // A dashpot storey: c / (2 m w) for one storey.
  StoreyDevice dash;
  dash.type = DeviceType::dashpot;
  dash.storeys = {1};
  dash.c = 1e5;
  b.devices = {dash};
  b.springs[0] = 8e6;
  CHECK(building_modes(b).device_ratio[0] == Approx(1e5 / (2.0 * 2e5 * w)).epsilon(1e-12));
}

TEST_CASE("coupled periods: links free are the buildings' own, locked friction links join the floors", "[modal]") {
  Structure s;
  s.a = uniform(1, 1e5, 4e6);
  s.b = uniform(1, 3e5, 2e6);
  s.b->name = "B";
  Link l;
  l.type = LinkType::friction;
  l.slip_force = 1e4;
  s.links.push_back(l);
  std::string error;
  REQUIRE(s.IsValid(&error));
  const CoupledModes c = coupled_modes(s);
  REQUIRE(c.periods_free.size() == 2);
  CHECK(c.periods_free[0] == Approx(2 * M_PI * std::sqrt(3e5 / 2e6)).epsilon(1e-12));
  CHECK(c.periods_free[1] == Approx(2 * M_PI * std::sqrt(1e5 / 4e6)).epsilon(1e-12));
  REQUIRE(c.periods_locked.size() == 1);
  CHECK(c.periods_locked[0] == Approx(2 * M_PI * std::sqrt(4e5 / 6e6)).epsilon(1e-12));
  // A spring link stiffens the free system: the 2x2 problem by hand.
  s.links[0].type = LinkType::spring;
  s.links[0].k = 1e6;
  const CoupledModes sp = coupled_modes(s);
  const double a = 5e6 / 1e5, d = 3e6 / 3e5, bc = (1e6 / 1e5) * (1e6 / 3e5);
  const double lmax = 0.5 * (a + d + std::sqrt((a - d) * (a - d) + 4 * bc)), lmin = 0.5 * (a + d - std::sqrt((a - d) * (a - d) + 4 * bc));
  CHECK(sp.periods_free[0] == Approx(2 * M_PI / std::sqrt(lmin)).epsilon(1e-12));
  CHECK(sp.periods_free[1] == Approx(2 * M_PI / std::sqrt(lmax)).epsilon(1e-12));
}

TEST_CASE("the paper's two blocks are the smallest structure", "[modal][scene]") {
  const Scene scene = test::paper_scene("strong");
  const Structure s = structure_of(scene);
  REQUIRE(s.b);
  CHECK(s.a.floors() == 1);
  CHECK(s.links.size() == 1);
  CHECK(s.links[0].slip_force == Approx(two_block_model(scene).mu));
  CHECK(s.contacts[0].gap == Approx(two_block_model(scene).gap0));
  // Relaxed periods: 2 pi sqrt(m1/k1) = 2 pi in T0, and block 2 sqrt((1/rho)/eps).
  CHECK(building_modes(s.a).periods[0] == Approx(2 * M_PI).epsilon(1e-12));
  CHECK(building_modes(*s.b).periods[0] == Approx(2 * M_PI * std::sqrt(1.0 / (two_block_model(scene).rho * two_block_model(scene).eps))).epsilon(1e-12));
}

TEST_CASE("the example building scene reads, with the period and the slip ratio resolved", "[modal][scene]") {
  const Structure s = read_structure(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml");
  CHECK(s.a.floors() == 5);
  REQUIRE(s.b);
  CHECK(building_modes(*s.b).periods[0] == Approx(0.5).epsilon(1e-12));
  REQUIRE(s.links.size() == 1);
  CHECK(s.links[0].slip_force == Approx(0.05 * 170e3 * 9.80665).epsilon(1e-12));
  CHECK(s.a.devices.size() == 1);
  CHECK(s.a.static_stiffness()[0] == Approx(5.482e6 + 1e6));
  CHECK(s.a.static_stiffness()[2] == Approx(5.482e6));
}

TEST_CASE("a period given with storey devices is the building's period with them", "[modal][scene]") {
  const Structure s = read_structure(std::string(ADJOIN_SOURCE_DIR) + "/examples/buildings/zener-building.toml");
  // The uniform spring is found so that springs plus the devices' relaxed stiffness give 0.8 s.
  CHECK(building_modes(s.a).periods[0] == Approx(0.8).epsilon(1e-10));
  CHECK(s.a.static_stiffness()[0] == Approx(s.a.springs[0] + 2.0e7));
  CHECK(s.a.static_stiffness()[5] == Approx(s.a.springs[5]));
}

TEST_CASE("participation factors and effective masses of a 2-storey shear building are the closed form", "[modal]") {
  // m1 = m2 = m, k1 = k2 = k: omega^2 = (3 -+ sqrt 5)/2 k/m, shapes scaled to 1 at the roof
  // psi_1 = [(sqrt5 - 1)/2, 1], psi_2 = [-(sqrt5 + 1)/2, 1]. Gamma = psi' M 1 / psi' M psi,
  // effective mass (psi' M 1)^2 / psi' M psi: by hand 1.1708 and -0.1708, 94.72 % and 5.28 %.
  const double m = 2.0e5, k = 3.0e8, r5 = std::sqrt(5.0);
  const Modes modes = building_modes(uniform(2, m, k));
  const double psi1 = (r5 - 1.0) / 2.0, psi2 = -(r5 + 1.0) / 2.0;
  CHECK(modes.omega[0] == Approx(std::sqrt((3.0 - r5) / 2.0 * k / m)).epsilon(1e-12));
  CHECK(modes.omega[1] == Approx(std::sqrt((3.0 + r5) / 2.0 * k / m)).epsilon(1e-12));
  const double gamma1 = (psi1 + 1.0) / (psi1 * psi1 + 1.0), gamma2 = (psi2 + 1.0) / (psi2 * psi2 + 1.0);
  CHECK(gamma1 == Approx(1.1708).epsilon(1e-4));  // the hand values
  CHECK(gamma2 == Approx(-0.1708).epsilon(1e-3));
  CHECK(modes.participation[0] == Approx(gamma1).epsilon(1e-12));
  CHECK(modes.participation[1] == Approx(gamma2).epsilon(1e-12));
  const double mass1 = m * (psi1 + 1.0) * (psi1 + 1.0) / (psi1 * psi1 + 1.0);
  const double mass2 = m * (psi2 + 1.0) * (psi2 + 1.0) / (psi2 * psi2 + 1.0);
  CHECK(mass1 / (2.0 * m) == Approx(0.9472).epsilon(1e-4));
  CHECK(modes.effective_mass[0] == Approx(mass1).epsilon(1e-12));
  CHECK(modes.effective_mass[1] == Approx(mass2).epsilon(1e-12));
  CHECK(modes.effective_mass.sum() == Approx(2.0 * m).epsilon(1e-12));
}

TEST_CASE("effective masses of any shear building sum to its total mass", "[modal]") {
  Building b;
  b.name = "A";
  b.masses = (Eigen::VectorXd(8) << 9e4, 8e4, 8e4, 7e4, 7e4, 6e4, 5e4, 3e4).finished();
  b.springs = (Eigen::VectorXd(8) << 2e8, 1.8e8, 1.6e8, 1.4e8, 1.2e8, 1e8, 8e7, 5e7).finished();
  const Modes modes = building_modes(b);
  CHECK(modes.effective_mass.sum() == Approx(b.masses.sum()).epsilon(1e-12));
  for (int j = 0; j < 8; ++j) {
    CHECK(modes.effective_mass[j] > 0.0);
    // Gamma^2 psi' M psi is the effective mass too (psi the roof-scaled shape).
    const Eigen::VectorXd psi = modes.shapes.col(j) / modes.shapes(7, j);
    CHECK(modes.participation[j] * modes.participation[j] * psi.dot(b.masses.cwiseProduct(psi)) ==
          Approx(modes.effective_mass[j]).epsilon(1e-10));
  }
  CHECK(modes.effective_mass[0] > 0.5 * b.masses.sum());  // the fundamental mode dominates
}

TEST_CASE("adjoin modes prints every mode's shape, participation and effective mass, with units", "[modal][cli]") {
  // An 8-storey frame (more modes than the 6 shapes once printed) and a 2-storey one with the
  // closed form above.
  const auto scene = test::write_temp("modes-eight.toml", R"(name = "eight"
[model]
units = "SI"
[building.A]
storeys = 8
mass = 5.0e5
period = 1.0
[building.B]
storeys = 2
mass = 2.0e5
stiffness = 3.0e8
)");
  const test::CliResult r = test::run_cli("modes " + scene.string());
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("total mass 4e+06 kg") != std::string::npos);
  CHECK(r.out.find("total mass 400000 kg") != std::string::npos);
  CHECK(r.out.find("period [s]") != std::string::npos);
  CHECK(r.out.find("eff. mass [kg]") != std::string::npos);
  CHECK(r.out.find("mode shapes [-]") != std::string::npos);
  // Building B's rows: Gamma 1.1708 / -0.1708, 94.72 % / 5.28 %, cumulated to 100 %.
  const std::size_t b = r.out.find("building B");
  REQUIRE(b != std::string::npos);
  const std::string tail = r.out.substr(b);
  CHECK(tail.find("1.1708") != std::string::npos);
  CHECK(tail.find("-0.1708") != std::string::npos);
  CHECK(tail.find("94.72") != std::string::npos);
  CHECK(tail.find("5.28") != std::string::npos);
  CHECK(tail.find("100.00") != std::string::npos);
  CHECK(tail.find("  2     -1.618          1") != std::string::npos);  // mode 2's shape
  // Building A: eight shape rows, the last mode's included.
  const std::string a = r.out.substr(0, b);
  const std::size_t shapes = a.find("mode shapes");
  REQUIRE(shapes != std::string::npos);
  int rows = 0;
  for (std::size_t at = a.find('\n', shapes); at != std::string::npos && at + 1 < a.size(); at = a.find('\n', at + 1)) ++rows;
  CHECK(rows == 8);
  CHECK(a.find("100.00") != std::string::npos);
  // --modes limits the table and the shapes; a count below 1 is refused.
  const test::CliResult two = test::run_cli("modes " + scene.string() + " --modes 2");
  CHECK(two.status == 0);
  CHECK(two.out.find("2 of 8 modes shown") != std::string::npos);
  const test::CliResult zero = test::run_cli("modes " + scene.string() + " --modes 0");
  CHECK(zero.status == 2);
  CHECK(zero.err.find("--modes") != std::string::npos);
}

TEST_CASE("an isolated building's period on friction pendulums: 2 pi sqrt(R/g), and the flexible storeys' two-mass closed form",
          "[modal][base]") {
  // One storey (m1, k1) on a base m_b on the pendulum's W/R: the 2-dof closed form
  // m_b m1 w^4 - (m_b k1 + m1 (k_p + k1)) w^2 + k_p k1 = 0, its smaller root.
  Building b = uniform(1, 4.0e4, 3.0e7);
  b.base = Base{6.0e4, BaseModel::friction_pendulum, 0.05, 2.0};
  const double g = 9.80665, mb = 6.0e4, m1 = 4.0e4, k1 = 3.0e7, kp = (mb + m1) * g / 2.0;
  CHECK(b.base_stiffness() == Approx(kp).epsilon(1e-15));
  const double p = mb * k1 + m1 * (kp + k1), w2 = (p - std::sqrt(p * p - 4.0 * mb * m1 * kp * k1)) / (2.0 * mb * m1);
  const IsolatedPeriod t = isolated_period(b);
  CHECK(t.rigid == Approx(2.0 * M_PI * std::sqrt(2.0 / g)).epsilon(1e-14));  // 2.8375 s, whatever the masses
  CHECK(t.flexible == Approx(2.0 * M_PI / std::sqrt(w2)).epsilon(1e-10));
  CHECK(t.flexible > t.rigid);
  // Storeys a thousand times stiffer: the superstructure is rigid, the period 2 pi sqrt(R/g).
  b.springs *= 1e3;
  CHECK(isolated_period(b).flexible == Approx(t.rigid).epsilon(1e-5));
  // A flat slider and a fixed base have no isolated period.
  b.base->model = BaseModel::flat_slider;
  CHECK(std::isnan(isolated_period(b).rigid));
  b.base.reset();
  CHECK(std::isnan(isolated_period(b).flexible));
}

TEST_CASE("adjoin modes states an isolated building's friction-pendulum period, or that a flat slider has none", "[modal][cli][base]") {
  const std::string scene = std::string(ADJOIN_SOURCE_DIR) + "/examples/buildings/yielding-frames-b-isolated.toml";
  const test::CliResult r = test::run_cli("modes '" + scene + "'");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  const std::size_t b = r.out.find("building B");
  REQUIRE(b != std::string::npos);
  CHECK(r.out.substr(0, b).find("isolated base") == std::string::npos);  // A stands on the ground
  const std::string tail = r.out.substr(b);
  // R = 2.5 m: 2 pi sqrt(2.5 / 9.80665) = 3.17241 s, beside the fixed-base 0.5 s.
  CHECK(tail.find("isolated base (friction-pendulum, mu = 0.06, base mass 60000 kg)") != std::string::npos);
  CHECK(tail.find("isolated period 2 pi sqrt(R/g) = 3.17241 s (R = 2.5 m") != std::string::npos);
  CHECK(tail.find("the periods below are the fixed-base superstructure's") != std::string::npos);
  CHECK(tail.find("     1          0.5            2") != std::string::npos);  // the fixed-base mode 1 still shown
  // mu W = 0.06 x (60 t + 170 t) x g = 135332 N.
  CHECK(tail.find("mu W = 135332 N") != std::string::npos);

  const test::CliResult flat = test::run_cli("modes '" + scene + "' --set building.B.base.model='\"flat-slider\"' --unset building.B.base.radius");
  INFO(flat.out << flat.err);
  REQUIRE(flat.status == 0);
  CHECK(flat.out.find("isolated base (flat-slider") != std::string::npos);
  CHECK(flat.out.find("no isolated period: a flat slider has no restoring force") != std::string::npos);
  CHECK(flat.out.find("isolated period 2 pi") == std::string::npos);
}
