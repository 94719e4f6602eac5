// What a two-block run reports about pounding (SPEC §6, issue 13 "Outputs"): the flags of a
// run without a contact law whose gap closes (summary, time series, terminal, sweep row), the
// unchanged outputs of a run that never pounds, and with a contact law impacts.csv, the
// summary's totals, the contact force in the time series and the contact term of the energy
// balance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "adjoin/io/energy_csv.hpp"
#include "adjoin/io/impacts_csv.hpp"
#include "adjoin/io/run_files.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/io/timeseries_csv.hpp"
#include "adjoin/observe/energy.hpp"
#include "adjoin/observe/pounding.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "adjoin/structure/two_block.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/sweep.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"

using namespace adjoin;
using adjoin::test::run_cli;
using adjoin::test::slurp;

namespace {

const std::string kStrong = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::size_t index_of(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  REQUIRE(it != header.end());
  return static_cast<std::size_t>(it - header.begin());
}

std::vector<std::string> keys_of(const nlohmann::ordered_json& j) {
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  return keys;
}

std::filesystem::path fresh(const std::string& name) {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / name;
  std::filesystem::remove_all(dir);
  return dir;
}

// Records the impacts the solver streams.
class ImpactRecorder final : public StructureObserver {
 public:
  void observe(const StructureState& /*s*/) override {}
  void impact(const Impact& i) override { impacts.push_back(i); }
  std::vector<Impact> impacts;
};

// A grid point of the 1 + 1 structure `s` (structure/two_block.hpp), at rest but for its floors'
// displacements x_A, x_B (link 1 stuck, no switch).
StructureState state_at(const structure::Structure& s, double t, double xa, double xb) {
  StructureState st;
  st.t = t;
  st.x = Eigen::Vector2d(xa, xb);
  for (auto* v : {&st.v, &st.a_abs, &st.storey_force}) v->setZero(2);
  const auto links = static_cast<Eigen::Index>(s.links.size());
  for (auto* v : {&st.link_force, &st.link_stroke, &st.link_velocity}) v->setZero(links);
  st.link_phase.assign(s.links.size(), Phase::stick);
  st.link_switch.assign(s.links.size(), std::numeric_limits<double>::quiet_NaN());
  for (auto* v : {&st.contact_gap, &st.contact_force, &st.contact_work, &st.contact_dissipated}) v->setZero(1);
  return st;
}

}  // namespace

TEST_CASE("no contact law and a closing gap: summary, time series and terminal flag the values after contact",
          "[pounding][outputs]") {
  // The paper's strong scene with a 0.3 joint: the gap closes at t = 1.607 and reaches -0.2519
  // at t = 2.231 (the blocks pass through each other).
  const auto dir = fresh("pounding-none");
  const auto r = run_cli("run '" + kStrong + "' --set model.gap0=0.3 --out '" + dir.string() + "'");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("CONTACT first at t = 1.607"));
  CHECK_THAT(r.out, Catch::Contains("WARNING: the gap closes at t = 1.6071 and the model has no contact law"));
  CHECK_THAT(r.out, Catch::Contains("outside the model (set [model.contact])"));
  CHECK_FALSE(std::filesystem::exists(dir / "impacts.csv"));

  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  const auto& p = j["pounding"];
  CHECK(p["contact"].get<bool>());
  CHECK(p["min_gap"].get<double>() == Approx(-0.251885).epsilon(1e-5));
  const double t_contact = p["t_first_contact"].get<double>();
  CHECK(t_contact == Approx(1.6071).margin(1e-4));
  CHECK(p["model"] == "none");
  CHECK(p["outside_model_from"].get<double>() == t_contact);
  CHECK(j["outside_model_from"].get<double>() == t_contact);
  REQUIRE(j["flags"].is_array());
  REQUIRE(j["flags"].size() == 1);
  CHECK_THAT(j["flags"][0].get<std::string>(), Catch::Contains("every value after that time is outside the model"));

  // The time series: outside_model before phase, 0 up to the first grid point with gap <= 0,
  // 1 from there on (even where the gap opens again).
  const auto lines = lines_of(slurp(dir / "timeseries.csv"));
  REQUIRE(lines.size() == 8002);
  CHECK(lines[0] == "t,x1,x2,v1,v2,f1,f2,q,ag,gap,outside_model,phase");
  std::size_t first_flag = 0, reopened = 0;
  bool seen = false;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = fields_of(lines[i]);
    REQUIRE(f.size() == 12);
    const double t = std::stod(f[0]), gap = std::stod(f[9]);
    if (gap <= 0.0 && !seen) {
      seen = true;
      first_flag = i;
      CHECK(t >= t_contact);
      CHECK(t - 0.002 < t_contact);
    }
    if (seen && gap > 0.0) ++reopened;
    REQUIRE(f[10] == (seen ? "1" : "0"));
  }
  CHECK(first_flag == 805);  // t = 1.608, the first grid point past t = 1.6071
  CHECK(reopened > 0);       // the gap opens again and the rows stay flagged

  // The flagged series is streamed from a second pass: its numbers are the run's, digit for digit.
  const Scene scene = load_scene(kStrong, {"model.gap0=0.3"});
  std::ostringstream plain;
  TimeSeriesCsvWriter writer(plain, scene.scales);
  run(scene, {&writer});
  const auto plain_lines = lines_of(plain.str());
  REQUIRE(plain_lines.size() == lines.size());
  CHECK(plain_lines[0] == "t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase");
  for (std::size_t i = 1; i < lines.size(); ++i) {
    auto f = fields_of(lines[i]);
    f.erase(f.begin() + 10);
    std::string joined;
    for (std::size_t k = 0; k < f.size(); ++k) joined += (k ? "," : "") + f[k];
    REQUIRE(joined == plain_lines[i]);
  }
}

TEST_CASE("no contact law: the flag stays when the pounding margin is not asked for", "[pounding][outputs]") {
  const auto dir = fresh("pounding-none-unasked");
  const auto r = run_cli("run '" + kStrong + "' --set model.gap0=0.3 --set output.pounding=false --set output.timeseries=false -q --out '" +
                         dir.string() + "'");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  CHECK(j["pounding"].is_null());
  CHECK(j["outside_model_from"].get<double>() == Approx(1.6071).margin(1e-4));
  REQUIRE(j["flags"].size() == 1);
  CHECK_THAT(j["flags"][0].get<std::string>(), Catch::Contains("t = 1.6071"));
}

TEST_CASE("a scene that never pounds keeps the outputs it had before contact laws", "[pounding][outputs]") {
  const auto dir = fresh("pounding-never");
  const auto r = run_cli("run '" + kStrong + "' --set output.energy_history=true --out '" + dir.string() + "'");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("pounding: min gap 1.44811 at t = 2.231, no contact\n"));
  CHECK_THAT(r.out, !Catch::Contains("WARNING"));
  CHECK_THAT(r.out, !Catch::Contains("contact "));
  CHECK_FALSE(std::filesystem::exists(dir / "impacts.csv"));
  CHECK(lines_of(slurp(dir / "timeseries.csv"))[0] == "t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase");
  CHECK(lines_of(slurp(dir / "energy.csv"))[0] == "t,input,kinetic,rod1,rod2,friction,residual");
  const auto j = nlohmann::ordered_json::parse(slurp(dir / "summary.json"));
  CHECK(keys_of(j["pounding"]) == std::vector<std::string>{"min_gap", "t_min_gap", "contact", "t_first_contact"});
  CHECK(keys_of(j["energy"]) == std::vector<std::string>{"input", "kinetic", "rod1", "rod2", "friction", "residual"});
  CHECK_FALSE(j.contains("flags"));
  CHECK_FALSE(j.contains("outside_model_from"));
  CHECK(j["pounding"]["min_gap"].get<double>() == Approx(1.44811).epsilon(1e-5));
}

TEST_CASE("sweep rows say when their values are outside the model", "[pounding][sweep]") {
  const auto file = test::write_temp("pounding-sweep.toml", "base = \"" + kStrong + "\"\n[[axis]]\nkey = \"model.gap0\"\nvalues = [2.0, 0.3]\n");
  const SweepSpec spec = load_sweep(file);
  const auto columns = sweep_columns(spec);
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  const std::size_t contact = index_of(names, "contact");
  REQUIRE(contact + 5 < names.size());
  CHECK(names[contact + 1] == "outside_model");
  CHECK(names[contact + 2] == "contact.impacts");
  CHECK(names[contact + 3] == "contact.force_max");
  CHECK(names[contact + 4] == "contact.penetration_max");
  CHECK(names[contact + 5] == "energy_input");

  const auto rows = run_sweep(spec, {});
  REQUIRE(rows.size() == 2);
  const auto never = sweep_cells(spec, rows[0]), pounds = sweep_cells(spec, rows[1]);
  CHECK(std::stod(pounds[index_of(names, "min_gap")]) == Approx(-0.251885).epsilon(1e-5));
  CHECK(never[contact] == "false");
  CHECK(never[contact + 1] == "false");
  CHECK(pounds[contact] == "true");
  CHECK(pounds[contact + 1] == "true");
  for (std::size_t k = 2; k <= 4; ++k) {
    CHECK(never[contact + k].empty());  // no contact law: nothing to report
    CHECK(pounds[contact + k].empty());
  }
  // The journal takes these rows back.
  std::size_t index = 0;
  CHECK(sweep_row_problem(spec, SweepShard{}, pounds, &index).empty());
  CHECK(index == 1);
}

TEST_CASE("the pounding observer's totals come from the impacts it is given", "[pounding][outputs]") {
  Model model;
  model.gap0 = 0.1;
  model.contact.model = structure::ContactModel::linear;
  model.contact.stiffness = 50.0;
  const structure::Structure pair = structure::two_block_structure(model);
  StructureSolverOptions options;
  options.h = 0.01;
  PoundingObserver observer;
  observer.begin(pair, options);
  observer.observe(state_at(pair, 0.0, 0.0, 0.0));
  observer.observe(state_at(pair, 0.01, 0.08, 0.0));
  StructureState s = state_at(pair, 0.02, 0.13, 0.0);  // penetration 0.03 at a grid point
  s.contact_force[0] = 1.5;
  s.contact_dissipated[0] = 0.004;
  observer.observe(s);
  Impact first;
  first.start = 0.014;
  first.duration = 0.02;
  first.force_max = 2.0;
  first.t_force_max = 0.021;
  first.penetration_max = 0.04;
  observer.impact(first);
  s = state_at(pair, 0.03, 0.05, 0.0);
  s.contact_dissipated[0] = 0.007;
  observer.observe(s);
  Impact second = first;
  second.start = 0.5;
  second.force_max = 3.0;
  second.t_force_max = 0.51;
  second.penetration_max = 0.035;
  second.complete = false;
  observer.impact(second);
  s = state_at(pair, 0.04, 0.11, 0.0);
  s.contact_dissipated[0] = 0.009;  // cumulative: the last state's value is the run's
  observer.observe(s);
  observer.end();
  const PoundingMargin& m = observer.margin();
  CHECK(m.has_law());
  CHECK_FALSE(m.outside_model());
  REQUIRE(m.impacts.size() == 2);
  CHECK(m.force_max == 3.0);
  CHECK(m.t_force_max == 0.51);
  CHECK(m.penetration_max == 0.04);
  CHECK(m.dissipated == 0.009);
  CHECK(m.contact);
  CHECK(*m.t_first_contact == 0.014);  // the impact's located start, not the gap's crossing
  CHECK(m.min_gap == Approx(-0.03));

  // Without impacts (a run whose law saw none reported): the sampled values.
  PoundingObserver sampled;
  sampled.begin(pair, options);
  sampled.observe(state_at(pair, 0.0, 0.0, 0.0));
  s = state_at(pair, 0.01, 0.13, 0.0);
  s.contact_force[0] = 1.5;
  sampled.observe(s);
  sampled.end();
  CHECK(sampled.margin().impacts.empty());
  CHECK(sampled.margin().force_max == 1.5);
  CHECK(sampled.margin().t_force_max == 0.01);
  CHECK(sampled.margin().penetration_max == Approx(0.03));
}

TEST_CASE("impacts.csv rows are in the scene's units", "[pounding][outputs]") {
  const Scales k = Scales::SI(2.0e5, 8.0e6);
  Impact i;
  i.start = 3.0;
  i.duration = 0.25;
  i.force_max = 4.0;
  i.t_force_max = 3.1;
  i.penetration_max = 0.02;
  i.approach_speed = 0.5;
  i.rebound_speed = 0.3;
  i.impulse = 0.7;
  i.complete = false;
  const auto f = fields_of(impact_csv_row(i, k));
  REQUIRE(f.size() == 9);
  CHECK(std::stod(f[0]) == Approx(3.0 * k.time).epsilon(1e-15));
  CHECK(std::stod(f[1]) == Approx(0.25 * k.time).epsilon(1e-15));
  CHECK(std::stod(f[2]) == Approx(4.0 * k.force).epsilon(1e-15));
  CHECK(std::stod(f[3]) == Approx(3.1 * k.time).epsilon(1e-15));
  CHECK(std::stod(f[4]) == Approx(0.02 * k.length).epsilon(1e-15));
  CHECK(std::stod(f[5]) == Approx(0.5 * k.velocity).epsilon(1e-15));
  CHECK(std::stod(f[6]) == Approx(0.3 * k.velocity).epsilon(1e-15));
  CHECK(std::stod(f[7]) == Approx(0.7 * k.force * k.time).epsilon(1e-15));  // N s
  CHECK(f[8] == "false");
  CHECK(std::string(kImpactsCsvHeader) ==
        "t_start,duration,force_max,t_force_max,penetration_max,approach_speed,rebound_speed,impulse,complete");
}

TEST_CASE("the energy balance subtracts the contact work only with a contact law", "[pounding][energy]") {
  Model model;
  model.rho = 0.5;
  const StructureSolverOptions options;
  const structure::Structure pair = structure::two_block_structure(model);
  const StructureState a = state_at(pair, 0.0, 0.0, 0.0);
  StructureState b = state_at(pair, 0.1, 0.0, 0.0);
  b.v[0] = 1.0;
  b.contact_work[0] = 0.25;
  b.contact_dissipated[0] = 0.05;
  EnergyObserver none;
  none.begin(pair, options);
  none.observe(a);
  none.observe(b);
  CHECK(none.terms().contact == 0.0);
  CHECK(none.terms().residual == Approx(-0.5));  // input 0 - kinetic 1/2
  model.contact.model = structure::ContactModel::hertz;
  model.contact.stiffness = 10.0;
  const structure::Structure with_law = structure::two_block_structure(model);
  EnergyObserver law;
  law.begin(with_law, options);
  law.observe(a);
  law.observe(b);
  CHECK(law.terms().contact == 0.25);
  CHECK(law.terms().contact_dissipated == 0.05);
  CHECK(law.terms().residual == Approx(-0.75));
}

TEST_CASE("adjoin plot run draws the gap and the contact force when the run has impacts.csv", "[pounding][plot]") {
  adjoin::test::needs_program("gnuplot");
  const auto dir = fresh("pounding-plot");
  auto r = run_cli("run '" + kStrong + "' --set solver.scheme=implicit --set model.gap0=0.3 --set model.contact.model=linear " +
                   "--set model.contact.stiffness=100 --set model.contact.restitution=0.65 -q --out '" + dir.string() + "'");
  REQUIRE(r.status == 0);
  REQUIRE(std::filesystem::exists(dir / "impacts.csv"));
  r = run_cli("plot run '" + dir.string() + "' --format svg");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("contact.svg"));
  const std::string svg = slurp(dir / "contact.svg");
  CHECK_THAT(svg, Catch::Contains("contact force"));
  CHECK_THAT(svg, Catch::Contains("impact"));
  // A run without a contact law has no such figure.
  const auto plain = fresh("pounding-plot-none");
  REQUIRE(run_cli("run '" + kStrong + "' -q --out '" + plain.string() + "'").status == 0);
  r = run_cli("plot run '" + plain.string() + "' --format svg");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, !Catch::Contains("contact.svg"));
}

namespace {

// The strong scene with a 0.3 joint and a linear contact law (e = 0.65): two impacts.
Scene linear_contact_scene(std::vector<std::string> more = {}) {
  std::vector<std::string> set{"solver.scheme=implicit", "model.gap0=0.3", "model.contact.model=linear",
                               "model.contact.stiffness=100", "model.contact.restitution=0.65"};
  set.insert(set.end(), more.begin(), more.end());
  return load_scene(kStrong, set);
}

}  // namespace

TEST_CASE("with a contact law: impacts.csv holds the impacts the solver streamed and the summary agrees",
          "[pounding][outputs]") {
  const Scene scene = linear_contact_scene({"output.energy_history=true"});
  ImpactRecorder recorded;
  run(scene, {&recorded});
  REQUIRE(recorded.impacts.size() >= 2);

  const auto dir = fresh("pounding-linear");
  const RunFiles files = run_to_folder(scene, dir);
  const auto lines = lines_of(slurp(dir / "impacts.csv"));
  REQUIRE(lines.size() == recorded.impacts.size() + 1);
  CHECK(lines[0] == kImpactsCsvHeader);
  double force_max = 0.0, t_force_max = 0.0, penetration_max = 0.0;
  for (std::size_t i = 0; i < recorded.impacts.size(); ++i) {
    CHECK(lines[i + 1] == impact_csv_row(recorded.impacts[i], scene.scales));
    const auto f = fields_of(lines[i + 1]);
    if (std::stod(f[2]) > force_max) force_max = std::stod(f[2]), t_force_max = std::stod(f[3]);
    penetration_max = std::max(penetration_max, std::stod(f[4]));
    CHECK(std::stod(f[1]) > 0.0);  // a compliant law's impact lasts
  }

  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  const auto& p = j["pounding"];
  CHECK(p["model"] == "linear");
  CHECK(p["impacts"].get<std::size_t>() == recorded.impacts.size());
  CHECK(p["contact"].get<bool>());
  CHECK(p["t_first_contact"].get<double>() == recorded.impacts.front().start);
  CHECK(p["t_first_contact"].get<double>() == Approx(1.6069).margin(1e-3));
  CHECK(p["force_max"].get<double>() == force_max);
  CHECK(p["t_force_max"].get<double>() == t_force_max);
  CHECK(p["penetration_max"].get<double>() == penetration_max);
  // The deepest penetration is the gap's minimum (located by the solver, refined by the margin).
  CHECK(-p["min_gap"].get<double>() == Approx(penetration_max).epsilon(1e-3));
  CHECK(p["energy"].get<double>() == j["energy"]["contact_dissipated"].get<double>());
  CHECK(p["energy"].get<double>() > 0.05);
  CHECK_FALSE(p.contains("outside_model_from"));
  CHECK_FALSE(j.contains("flags"));

  // The time series carries the contact force: 0 wherever the gap is open, and its sampled
  // peak just below the located one.
  const auto series = lines_of(slurp(dir / "timeseries.csv"));
  CHECK(series[0] == "t,x1,x2,v1,v2,f1,f2,q,ag,gap,fc,phase");
  double fc_max = 0.0;
  std::size_t pushing = 0;
  for (std::size_t i = 1; i < series.size(); ++i) {
    const auto f = fields_of(series[i]);
    REQUIRE(f.size() == 12);
    const double gap = std::stod(f[9]), fc = std::stod(f[10]);
    if (gap > 0.0) REQUIRE(fc == 0.0);
    if (fc > 0.0) ++pushing;
    fc_max = std::max(fc_max, fc);
  }
  CHECK(pushing > 100);
  CHECK(fc_max <= force_max * (1.0 + 1e-12));
  CHECK(fc_max > 0.99 * force_max);

  // The energy history has the contact terms, and its last row is the summary's.
  const auto energy = lines_of(slurp(dir / "energy.csv"));
  CHECK(energy[0] == "t,input,kinetic,rod1,rod2,friction,contact,contact_dissipated,residual");
  const auto last = fields_of(energy.back());
  REQUIRE(last.size() == 9);
  CHECK(std::stod(last[6]) == Approx(j["energy"]["contact"].get<double>()).epsilon(1e-14));
  CHECK(std::stod(last[8]) == Approx(std::stod(last[1]) - (std::stod(last[2]) + std::stod(last[3]) + std::stod(last[4]) +
                                                           std::stod(last[5]) + std::stod(last[6])))
                                  .margin(1e-12));

  // The terminal line.
  const std::string brief = brief_report(scene, files.report);
  CHECK_THAT(brief, Catch::Contains("pounding (linear): " + std::to_string(recorded.impacts.size()) + " impacts from t = 1.607"));
  CHECK_THAT(brief, Catch::Contains("max penetration"));
  CHECK_THAT(brief, !Catch::Contains("WARNING"));
}

TEST_CASE("with a contact law the energy residual subtracts the contact work and goes to zero with h",
          "[pounding][energy]") {
  std::vector<double> residual, contact;
  for (const char* h : {"solver.h=0.002", "solver.h=0.001", "solver.h=0.0005"}) {
    const Report r = run(linear_contact_scene({h, "solver.error_estimate=false"}));
    REQUIRE(r.energy.buildings.size() == 2);
    REQUIRE(r.contacts.size() == 1);
    REQUIRE(r.contacts.at(0).impacts >= 2);
    residual.push_back(std::abs(r.energy.residual));
    contact.push_back(r.energy.contacts.at(0));
    // After the last impact nothing is stored in the contact: its work is all dissipated.
    CHECK(r.energy.contacts.at(0) == Approx(r.contacts.at(0).dissipated).epsilon(1e-12));
  }
  INFO("residuals " << residual[0] << " " << residual[1] << " " << residual[2] << ", contact " << contact[0]);
  CHECK(contact[0] > 0.05);
  // Left in the residual, the contact work would be 0.11; subtracted, what remains is the
  // integration error, about 1e-5 of it, which falls by 2.8x and 3.2x as h halves (the
  // contact-free run's residual falls irregularly too: friction switches).
  CHECK(residual[0] < 1e-5 * contact[0]);
  CHECK(residual[1] < 0.5 * residual[0]);
  CHECK(residual[2] < 0.5 * residual[1]);
}

TEST_CASE("sweep rows with a contact law report the impacts", "[pounding][sweep]") {
  const auto file = test::write_temp(
      "pounding-law-sweep.toml",
      "base = \"" + kStrong + "\"\nset = {\"solver.scheme\" = \"implicit\", \"model.contact.model\" = \"linear\", " +
          "\"model.contact.stiffness\" = 100, \"model.contact.restitution\" = 0.65}\n" +
          "[[axis]]\nkey = \"model.gap0\"\nvalues = [2.0, 0.3]\n");
  const SweepSpec spec = load_sweep(file);
  const auto rows = run_sweep(spec, {});
  REQUIRE(rows.size() == 2);
  const Scene scene = linear_contact_scene();
  const Report r = run(scene);
  REQUIRE(r.contacts.size() == 1);
  const auto columns = sweep_columns(spec);
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  const auto never = sweep_cells(spec, rows[0]), pounds = sweep_cells(spec, rows[1]);
  CHECK(never[index_of(names, "contact.impacts")] == "0");
  CHECK(never[index_of(names, "contact.force_max")] == "0");
  CHECK(never[index_of(names, "outside_model")] == "false");
  CHECK(pounds[index_of(names, "outside_model")] == "false");
  CHECK(pounds[index_of(names, "contact.impacts")] == std::to_string(r.contacts.at(0).impacts));
  CHECK(std::stod(pounds[index_of(names, "contact.force_max")]) == r.contacts.at(0).force_max);
  CHECK(std::stod(pounds[index_of(names, "contact.penetration_max")]) == r.contacts.at(0).penetration_max);
}

TEST_CASE("with the Newton impact law the gap's minimum is 0 at the first touch and impulses are reported",
          "[pounding][outputs]") {
  const Scene scene = load_scene(kStrong, {"solver.scheme=implicit", "model.gap0=0.3", "model.contact.model=impact",
                                           "model.contact.restitution=0.65"});
  const auto dir = fresh("pounding-newton");
  const RunFiles files = run_to_folder(scene, dir);
  const auto lines = lines_of(slurp(dir / "impacts.csv"));
  REQUIRE(lines.size() >= 3);
  double impulse = 0.0, impulse_max = 0.0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = fields_of(lines[i]);
    CHECK(std::stod(f[1]) == 0.0);  // no duration, no force, no penetration
    CHECK(std::stod(f[2]) == 0.0);
    CHECK(std::stod(f[4]) == 0.0);
    // Newton's law: the rebound is e times the approach (the rods and the damper act on a
    // finite force scale, nothing during an instantaneous impact).
    CHECK(std::stod(f[6]) == Approx(0.65 * std::stod(f[5])).epsilon(1e-9));
    impulse += std::stod(f[7]);
    impulse_max = std::max(impulse_max, std::stod(f[7]));
  }
  const auto j = nlohmann::json::parse(slurp(dir / "summary.json"));
  const auto& p = j["pounding"];
  CHECK(p["min_gap"].get<double>() == 0.0);
  CHECK(p["t_min_gap"].get<double>() == p["t_first_contact"].get<double>());
  CHECK(p["t_first_contact"].get<double>() == std::stod(fields_of(lines[1])[0]));
  CHECK(p["force_max"].get<double>() == 0.0);
  CHECK(p["t_force_max"].is_null());
  CHECK(p["impulse"].get<double>() == Approx(impulse).epsilon(1e-15));
  CHECK(p["impulse_max"].get<double>() == impulse_max);
  CHECK_THAT(brief_report(scene, files.report), Catch::Contains("impacts from t = 1.607, largest impulse "));
}
