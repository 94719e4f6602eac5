// Storey heights, drift ratios, P-Delta and collapse (SPEC §7), against closed forms:
//  - an SDOF with P-Delta vibrates at omega^2 = (k - m g / h) / m: the modal report and the
//    run's free vibration;
//  - an SDOF whose P-Delta tangent is negative (k < m g / h) diverges as x0 cosh(lambda t),
//    lambda^2 = (m g / h - k) / m; its collapse at |x| = c h is located at
//    t* = acosh(c h / x0) / lambda to the scheme's accuracy, converging at order 2;
//  - the drift ratio channel is drift / h exactly; summary.json's residual is the time series'
//    last row; the run stops at a collapse with exit 0.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/ground/decaying_sine.hpp"
#include "adjoin/observe/channel_values.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/builder.hpp"
#include "adjoin/structure/channels.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;

namespace {

constexpr double kMass = 1.0e4, kHeight = 3.0;

structure::Structure sdof(double k, bool p_delta, double collapse = 0.10) {
  structure::StructureBuilder s;
  s.building('A', 1).mass(kMass).stiffness(k).height(kHeight).p_delta(p_delta).collapse_drift_ratio(collapse);
  return s.build();
}

// Keeps every grid point's time and displacement of floor 1.
class Trace final : public StructureObserver {
 public:
  void observe(const StructureState& st) override {
    t.push_back(st.t);
    x.push_back(st.x[0]);
  }
  std::vector<double> t, x;
};

// A run of the SDOF from rest at x0, no ground motion, to t_end with step h.
Report free_run(const structure::Structure& s, double x0, double h, double t_end, Trace* trace = nullptr) {
  BuildingRunOptions o;
  o.h = h;
  o.t_end = t_end;
  RunSpec spec = building_run_spec(s, std::make_shared<DecayingSine>(0.0, 1.0, 0.0), o);
  spec.solver.x0 = Eigen::VectorXd::Constant(1, x0);
  return run(spec, {trace});
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) out.push_back(cell);
  return out;
}

}  // namespace

TEST_CASE("P-Delta lowers an SDOF's frequency to omega^2 = (k - m g / h) / m, in the modes and in the run", "[p_delta]") {
  const double k = 1.0e5;
  const double omega = std::sqrt((k - kMass * kStandardGravity / kHeight) / kMass);
  const structure::Structure s = sdof(k, true);
  const structure::Modes modes = structure::building_modes(s.a);
  CHECK(modes.p_delta);
  CHECK(modes.periods[0] == Approx(2.0 * M_PI / omega).epsilon(1e-12));
  // Without P-Delta, the elastic period.
  CHECK(structure::building_modes(sdof(k, false).a).periods[0] == Approx(2.0 * M_PI * std::sqrt(kMass / k)).epsilon(1e-12));

  // Free vibration from x0: x0 cos(omega t), to the trapezoidal rule's phase error
  // omega t (omega h)^2 / 12 (about 7e-6 x0 over two periods at h = 1 ms).
  const double x0 = 0.01, h = 1e-3, t_end = 2.0 * 2.0 * M_PI / omega;
  Trace trace;
  free_run(s, x0, h, t_end, &trace);
  REQUIRE(trace.t.size() > 1000);
  double worst = 0.0;
  for (std::size_t i = 0; i < trace.t.size(); ++i) worst = std::max(worst, std::abs(trace.x[i] - x0 * std::cos(omega * trace.t[i])));
  const double phase = omega * t_end * (omega * h) * (omega * h) / 12.0;
  CHECK(worst < 1.5 * phase * x0);
  CHECK(worst > 0.5 * phase * x0);  // the scheme's own error, not a looser agreement
}

TEST_CASE("with P-Delta the storey force carries -P/h x drift and the energy balance closes at order 2", "[p_delta][energy]") {
  // A 3-storey frame with P-Delta under a decaying sine: the storeys' work includes the
  // gravity load's (negative) potential energy, so input = kinetic + storeys + inherent.
  structure::StructureBuilder b;
  b.building('A', 3).mass(2.0e4).stiffness(2.0e6).height(3.0).p_delta(true).modal_damping(0.05);
  const structure::Structure s = b.build();
  std::vector<double> residuals;
  for (const double h : {0.004, 0.002}) {
    BuildingRunOptions o;
    o.h = h;
    o.t_end = 8.0;
    const Report r = run(building_run_spec(s, std::make_shared<DecayingSine>(0.01, 3.0, 0.3), o));
    REQUIRE_FALSE(r.collapse);
    REQUIRE(r.energy.input > 0.0);
    residuals.push_back(std::abs(r.energy.residual) / r.energy.input);
  }
  INFO("relative residuals " << residuals[0] << " " << residuals[1]);
  CHECK(residuals[1] < 1e-6);
  CHECK(residuals[0] / residuals[1] == Approx(4.0).epsilon(0.25));
}

TEST_CASE("a negative P-Delta tangent diverges as x0 cosh(lambda t) and collapses at the located t*", "[p_delta][collapse]") {
  const double k = 2.0e4;  // m g / h = 32 688.8 N/m > k
  const double lambda = std::sqrt((kMass * kStandardGravity / kHeight - k) / kMass);
  const double x0 = 1e-3, c = 0.10;
  const double t_star = std::acosh(c * kHeight / x0) / lambda;
  const structure::Structure s = sdof(k, true, c);
  // The modal report: the mode is unstable (infinite period, no damping ratio).
  const structure::Modes modes = structure::building_modes(s.a);
  CHECK(std::isinf(modes.periods[0]));
  CHECK(std::isnan(modes.inherent_ratio[0]));

  std::vector<double> errors;
  for (const double h : {0.02, 0.01, 0.005}) {
    Trace trace;
    const Report r = free_run(s, x0, h, 2.0 * t_star, &trace);
    REQUIRE(r.collapse);
    CHECK(r.collapse->building == 'A');
    CHECK(r.collapse->storey == 1);
    CHECK(r.collapse->drift_ratio == c);
    // The run stopped at the end of the step the crossing lies in.
    const double t_last = trace.t.back();
    CHECK(r.solver.steps + 1 == trace.t.size());
    CHECK(r.collapse->t <= t_last);
    CHECK(r.collapse->t > t_last - h);
    CHECK(trace.x.back() > c * kHeight);
    CHECK(trace.x[trace.x.size() - 2] <= c * kHeight);
    // On the grid the trapezoidal rule's solution is x0 cosh(lambda_h t), lambda_h =
    // (2/h) atanh(lambda h / 2); located between grid points its crossing is that of the
    // cubic through the step (error O(h^4)): the located time is the scheme's, to 1e-6 s.
    const double lambda_h = 2.0 / h * std::atanh(lambda * h / 2.0);
    CHECK(r.collapse->t == Approx(std::acosh(c * kHeight / x0) / lambda_h).margin(1e-6));
    // The residual: the drift and drift ratio at the last grid point.
    REQUIRE(r.residual.size() == 2);
    CHECK(r.residual[0].channel == "A.drift1");
    CHECK(r.residual[0].value == trace.x.back());
    CHECK(r.residual[1].channel == "A.drift_ratio1");
    CHECK(r.residual[1].value == trace.x.back() / kHeight);
    errors.push_back(std::abs(r.collapse->t - t_star));
  }
  // Second order: the error of the located time falls 4-fold when h halves.
  INFO("errors " << errors[0] << " " << errors[1] << " " << errors[2]);
  CHECK(errors[0] / errors[1] == Approx(4.0).epsilon(0.05));
  CHECK(errors[1] / errors[2] == Approx(4.0).epsilon(0.05));
  CHECK(errors[1] < t_star * (lambda * 0.01) * (lambda * 0.01) / 12.0 * 1.1);
}

TEST_CASE("a building without heights has no drift ratio channel and no collapse check", "[p_delta][collapse]") {
  structure::StructureBuilder b;
  b.building('A', 1).mass(kMass).stiffness(2.0e4);
  const structure::Structure s = b.build();
  for (const auto& ch : structure::channels(s)) CHECK(ch.quantity != structure::Quantity::drift_ratio);
  const Report r = free_run(s, 1.0, 0.01, 5.0);  // a drift of 1 m / 3 m would collapse with heights
  CHECK_FALSE(r.collapse);
  CHECK(r.solver.steps == 500);
  REQUIRE(r.residual.size() == 1);
  CHECK(r.residual[0].channel == "A.drift1");
}

TEST_CASE("the drift ratio channel is the drift over the storey height, exactly", "[p_delta][channels]") {
  structure::StructureBuilder b;
  b.building('A', 2).mass(kMass).stiffness(1e6).heights({3.5, 3.0});
  const structure::Structure s = b.build();
  const auto r1 = structure::find_channel(s, "A.drift_ratio1");
  const auto r2 = structure::find_channel(s, "A.drift_ratio2");
  REQUIRE(r1);
  REQUIRE(r2);
  CHECK(structure::info(r2->quantity).unit == std::string("-"));
  StructureState st;
  st.x = Eigen::Vector2d(0.0123, -0.0456);
  CHECK(channel_value(s, *r1, st) == 0.0123 / 3.5);
  CHECK(channel_value(s, *r2, st) == (-0.0456 - 0.0123) / 3.0);
}

TEST_CASE("the builder refuses bad heights by field", "[p_delta][builder]") {
  auto field_of = [](auto&& make) -> std::string {
    try {
      make();
    } catch (const FieldError& e) {
      return e.field();
    }
    return "";
  };
  CHECK(field_of([] { structure::BuildingBuilder('A', 2).height(-1.0); }) == "building.A.height");
  CHECK(field_of([] { structure::BuildingBuilder('A', 2).heights({3.0}); }) == "building.A.heights");
  CHECK(field_of([] { structure::BuildingBuilder('A', 2).heights({3.0, 0.0}); }) == "building.A.heights[2]");
  CHECK(field_of([] { structure::BuildingBuilder('A', 2).collapse_drift_ratio(0.0); }) == "building.A.collapse_drift_ratio");
  CHECK(field_of([] { structure::BuildingBuilder('A', 2).mass(1e4).stiffness(1e6).p_delta(true).build(); }) ==
        "building.A.p_delta");
  CHECK(field_of([] { structure::BuildingBuilder('A', 2).mass(1e4).stiffness(1e6).collapse_drift_ratio(0.05).build(); }) ==
        "building.A.collapse_drift_ratio");
}

TEST_CASE("adjoin run stops at a collapse with exit 0: summary.json's collapse and residual, the time series up to it",
          "[p_delta][collapse][cli]") {
  namespace fs = std::filesystem;
  const fs::path scene = test::write_temp("collapse.toml", R"(name = "collapse"
[model]
units = "SI"
[building.A]
storeys = 2
mass = 1.0e4
stiffness = 2.0e4
heights = [3.0, 3.0]
p_delta = true
collapse_drift_ratio = 0.05
[ground]
source = "decaying-sine"
u0 = 0.01
omega = 2.0
k = 0.5
[solver]
h = 0.005
t_end = 60.0
[output]
timeseries = true
every = 7
)");
  const fs::path out = fs::path(ADJOIN_TEST_TMP) / "collapse_out";
  fs::remove_all(out);
  const auto r = test::run_cli("run '" + scene.string() + "' --out '" + out.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("COLLAPSE: storey") != std::string::npos);
  CHECK(r.out.find("building A: T1 unstable with P-Delta") != std::string::npos);
  CHECK(r.out.find("peak drift ratio A: ") != std::string::npos);
  const auto j = nlohmann::json::parse(test::slurp(out / "summary.json"));
  REQUIRE(j.contains("collapse"));
  CHECK(j["collapse"]["building"] == "A");
  const int storey = j["collapse"]["storey"];
  const double t = j["collapse"]["t"];
  CHECK(j["collapse"]["drift_ratio_limit"].get<double>() == Approx(0.05).epsilon(1e-15));
  CHECK(j["structure"]["A"]["p_delta"] == true);
  CHECK(j["structure"]["A"]["periods"][0].is_null());  // both storeys lean: the first mode is unstable
  const std::size_t steps = j["solver"]["steps"];
  CHECK(t < 60.0);
  // The error estimate's companion at 2h collapses too: the located time's Richardson error
  // is its actual error (against a run at h/4, whose own error is 1/16 of it).
  REQUIRE(j["error_estimate"]["available"] == true);
  REQUIRE(j["error_estimate"]["collapse_t"].is_number());
  const fs::path fine_out = out / "fine";
  REQUIRE(test::run_cli("run '" + scene.string() + "' --set solver.h=0.00125 --out '" + fine_out.string() + "' --quiet").status == 0);
  const double t_fine = nlohmann::json::parse(test::slurp(fine_out / "summary.json"))["collapse"]["t"];
  CHECK(j["error_estimate"]["collapse_t"].get<double>() == Approx(std::abs(t - t_fine) * 16.0 / 15.0).epsilon(0.05));
  CHECK(t <= steps * 0.005 + 1e-12);
  CHECK(t > (steps - 1) * 0.005 - 1e-12);
  // The time series ends at the last grid point (written although it is not every 7th), and
  // the residual drifts are its last row's.
  std::ifstream csv(out / "timeseries.csv");
  std::string line, last;
  std::getline(csv, line);
  const auto header = split(line);
  while (std::getline(csv, line)) last = line;
  const auto row = split(last);
  REQUIRE(row.size() == header.size());
  auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return std::stod(row[i]);
    FAIL("no column " << name);
    return 0.0;
  };
  CHECK(column("t") == Approx(steps * 0.005).epsilon(1e-12));
  const double x1 = column("A.x1"), x2 = column("A.x2");
  CHECK(j["residual"]["A.drift1"].get<double>() == x1);
  CHECK(j["residual"]["A.drift2"].get<double>() == x2 - x1);
  CHECK(j["residual"]["A.drift_ratio1"].get<double>() == x1 / 3.0);
  CHECK(j["residual"]["A.drift_ratio2"].get<double>() == (x2 - x1) / 3.0);
  const double at_collapse = storey == 1 ? x1 : x2 - x1;
  CHECK(std::abs(at_collapse) > 0.05 * 3.0);
  // The peaks include the drift ratios.
  CHECK(j["peaks"]["A.drift_ratio1"]["max_abs"].get<double>() ==
        Approx(j["peaks"]["A.drift1"]["max_abs"].get<double>() / 3.0).epsilon(1e-14));
}

TEST_CASE("adjoin modes says what it shows with P-Delta", "[p_delta][cli]") {
  const auto scene = test::write_temp("p_delta_modes.toml", "[model]\nunits = \"SI\"\n[building.A]\nstoreys = 1\nmass = 1e4\n"
                                                              "stiffness = 1e5\nheight = 3.0\np_delta = true\n");
  const auto r = test::run_cli("modes '" + scene.string() + "'");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("with P-Delta: periods and shapes of K0 + K_G") != std::string::npos);
  // T = 2 pi / sqrt((k - m g / h) / m) = 2.42179 s.
  CHECK(r.out.find("2.42179") != std::string::npos);
}

TEST_CASE("a building sweep reports each row's collapse time and largest drift ratio", "[p_delta][collapse][sweep][cli]") {
  namespace fs = std::filesystem;
  // Storey 1 carries 2 x 1e4 kg: P/h = 65 378 N/m. k = 2e4 leans on and collapses; k = 1e5 stands.
  const fs::path base = test::write_temp("sweep_base.toml", R"(name = "lean"
[model]
units = "SI"
[building.A]
storeys = 2
mass = 1.0e4
stiffness = 1.0e5
height = 3.0
p_delta = true
collapse_drift_ratio = 0.05
[ground]
source = "decaying-sine"
u0 = 0.01
omega = 2.0
k = 0.5
[solver]
h = 0.005
t_end = 10.0
)");
  const fs::path file = test::write_temp("lean_sweep.toml", "base = \"" + base.string() +
                                                              "\"\n[[axis]]\nkey = \"building.A.stiffness\"\nvalues = [2.0e4, 1.0e5]\n");
  const fs::path out = fs::path(ADJOIN_TEST_TMP) / "lean_sweep";
  fs::remove_all(out);
  const auto r = test::run_cli("sweep '" + file.string() + "' --out '" + out.string() + "' --quiet --jobs 1");
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::ifstream csv(out / "sweep.csv");
  std::string line;
  std::getline(csv, line);
  const auto header = split(line);
  auto at = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  REQUIRE(at("collapse_t") < header.size());
  REQUIRE(at("A.drift_ratio_max") < header.size());
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) {
    auto cells = split(line);
    cells.resize(header.size());  // (trailing empty cells)
    rows.push_back(cells);
  }
  REQUIRE(rows.size() == 2);
  // The leaning frame collapses: its time is the run's own (the same scene run alone).
  CHECK_FALSE(rows[0][at("collapse_t")].empty());
  CHECK(std::stod(rows[0][at("A.drift_ratio_max")]) > 0.05);
  const auto alone = test::run_cli("run '" + base.string() + "' --set building.A.stiffness=2e4 --out '" + (out / "alone").string() +
                                   "' --quiet");
  REQUIRE(alone.status == 0);
  const auto j = nlohmann::json::parse(test::slurp(out / "alone" / "summary.json"));
  CHECK(std::stod(rows[0][at("collapse_t")]) == j["collapse"]["t"].get<double>());
  // The stiff one stands: no collapse, a drift ratio below the limit.
  CHECK(rows[1][at("collapse_t")].empty());
  CHECK(std::stod(rows[1][at("A.drift_ratio_max")]) < 0.05);
}

TEST_CASE("an unstable P-Delta building beside a stable one: null periods, the other's modes, exit 0",
          "[p_delta][collapse][cli]") {
  namespace fs = std::filesystem;
  const fs::path scene = test::write_temp("lean_pair.toml", R"(name = "lean-pair"
[model]
units = "SI"
[building.A]
storeys = 2
mass = 1.0e4
stiffness = 2.0e4
height = 3.0
p_delta = true
[building.B]
storeys = 2
mass = 1.0e4
stiffness = 1.0e6
[[link]]
floors = [2, 2]
type = "dashpot"
c = 1e3
[ground]
source = "decaying-sine"
u0 = 0.01
omega = 2.0
k = 0.5
[solver]
t_end = 20.0
)");
  const fs::path out = fs::path(ADJOIN_TEST_TMP) / "lean_pair";
  fs::remove_all(out);
  const auto r = test::run_cli("run '" + scene.string() + "' --out '" + out.string() + "' --quiet");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(test::slurp(out / "summary.json"));
  // The step was chosen from the elastic periods (P-Delta's are infinite here).
  CHECK(j["solver"]["h"].get<double>() > 0.0);
  CHECK(j["structure"]["A"]["periods"][0].is_null());
  CHECK(j["structure"]["periods_free"][0].is_null());
  structure::StructureBuilder b;
  b.building('A', 2).mass(1e4).stiffness(1e6);
  CHECK(j["structure"]["B"]["periods"][0].get<double>() == Approx(structure::building_modes(b.build().a).periods[0]).epsilon(1e-12));
  CHECK(j["collapse"]["building"] == "A");
  CHECK_FALSE(j["residual"].contains("B.drift_ratio1"));  // B has no heights
  CHECK(j["residual"].contains("B.drift1"));
}
