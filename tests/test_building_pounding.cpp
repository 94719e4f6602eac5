// Pounding outputs of building runs (SPEC §6, issue 13 "Outputs"): impacts.csv is the impacts
// the solver streams, the summary's contact totals and the sweep columns are theirs; a pair
// without a contact law flags every value after its first overlap (summary, time series, sweep
// row); the energy balance with the contact's work closes at order 2; contacts.png is drawn.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/run_files.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/timeseries_csv.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/plots.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/sweep_columns.hpp"
#include "adjoin/study/sweep.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"
#include "png_check.hpp"

using namespace adjoin;
using adjoin::test::run_cli;
using adjoin::test::slurp;
using adjoin::test::write_temp;
namespace fs = std::filesystem;

namespace {

const fs::path kScene = fs::path(ADJOIN_SOURCE_DIR) / "records/scenes/buildings/two-frames.toml";

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / ("pounding_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

nlohmann::json summary(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

// The two frames of the README under 8 s of the Newhall record: the 50 mm joint at floor 3
// closes (about 4.3 s). Every grid point written.
BuildingScene pounding_scene(std::vector<std::string> edits = {}) {
  edits.insert(edits.begin(), {"solver.t_end=8", "output.every=1"});
  return load_building_scene(kScene, edits);
}

// A linear (Kelvin-Voigt) contact at the pair: k = 1e8 N/m, e = 0.65 (contact time about
// pi sqrt(m_eff / k) = 48 ms, 24 steps of 2 ms).
void set_linear_law(BuildingScene& scene) {
  auto& law = scene.structure.contacts.at(0).law;
  law.model = structure::ContactModel::linear;
  law.stiffness = 1e8;
  law.restitution = 0.65;
}

// Everything the solver streams: impacts, and the states' contact channels.
class Recorder final : public StructureObserver {
 public:
  void observe(const StructureState& s) override {
    last = s;
    t.push_back(s.t);
    if (s.contact_gap.size() > 0) gap.push_back(s.contact_gap[0]);
    if (s.contact_force.size() > 0) force.push_back(s.contact_force[0]);
  }
  void impact(const Impact& e) override { impacts.push_back(e); }
  StructureState last;
  std::vector<double> t, gap, force;
  std::vector<Impact> impacts;
};

// The rows of a CSV file as text cells (header first).
std::vector<std::vector<std::string>> csv(const fs::path& file) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

std::map<std::string, std::vector<double>> columns(const fs::path& file) {
  const CsvTable table = read_csv_table(file);
  std::map<std::string, std::vector<double>> out;
  for (const auto& c : table.columns) out[c] = table.numbers(c);
  return out;
}

// The channel cells of a run by column name, as a sweep row has them.
std::map<std::string, std::string> sweep_cells(const BuildingScene& scene, const Report& r) {
  const auto cols = building_channel_columns(scene.structure);
  const auto cells = building_channel_cells(scene.structure, scene, r);
  std::map<std::string, std::string> out;
  for (std::size_t i = 0; i < cols.size(); ++i) out[cols[i].name] = cells[i];
  return out;
}

}  // namespace

TEST_CASE("pounding without a contact law: every value after the first overlap is flagged", "[building_run][pounding]") {
  const fs::path dir = scratch("none");
  const BuildingScene scene = pounding_scene();
  REQUIRE(scene.structure.contacts.at(0).law.model == structure::ContactModel::none);
  const RunFiles files = run_to_folder(scene, dir);
  CHECK(!fs::exists(dir / "impacts.csv"));  // no contact law, no impacts
  const auto ts = columns(dir / "timeseries.csv");
  // The first grid point where the gap is <= 0, independently from the written gap column.
  const auto& t = ts.at("t");
  const auto& gap = ts.at("contact1.gap");
  std::size_t first = t.size();
  for (std::size_t i = 0; i < t.size() && first == t.size(); ++i)
    if (gap[i] <= 0.0) first = i;
  REQUIRE(first < t.size());
  const double t_first = t[first];
  INFO("first overlap at t = " << t_first);
  CHECK(t_first > 3.0);
  CHECK(t_first < 6.0);
  // The time series: outside_model is 0 before that row and 1 from it on; the force is 0.
  const auto& outside = ts.at("outside_model");
  for (std::size_t i = 0; i < t.size(); ++i) {
    INFO("row " << i << " t = " << t[i]);
    REQUIRE(outside[i] == (i < first ? 0.0 : 1.0));
    REQUIRE(ts.at("contact1.force")[i] == 0.0);
  }
  // Even when the overlap falls between written rows, the flag is on from the next row.
  {
    BuildingScene sparse = scene;
    sparse.output.every = 7;
    const fs::path d2 = scratch("none-sparse");
    run_to_folder(sparse, d2);
    const auto s2 = columns(d2 / "timeseries.csv");
    for (std::size_t i = 0; i < s2.at("t").size(); ++i) {
      INFO("t = " << s2.at("t")[i]);
      CHECK(s2.at("outside_model")[i] == (s2.at("t")[i] < t_first - 1e-9 ? 0.0 : 1.0));
    }
  }
  // The summary: the pair's flag and the top-level flag at that time.
  const auto j = summary(dir);
  const auto& c = j["contacts"][0];
  CHECK(c["model"] == "none");
  CHECK(c["contact"] == true);
  CHECK(c["t_first_contact"].get<double>() == t_first);
  CHECK(c["outside_model_from"].get<double>() == t_first);
  CHECK(j["outside_model_from"].get<double>() == t_first);
  REQUIRE(j["flags"].size() == 1);
  const std::string flag = j["flags"][0].get<std::string>();
  CHECK(flag.find("contact1") != std::string::npos);
  CHECK(flag.find("outside the model") != std::string::npos);
  CHECK(flag.find("contact[1].model") != std::string::npos);
  CHECK(c["impacts"] == 0);
  CHECK(c["force_max"].get<double>() == 0.0);
  CHECK(c["t_force_max"].is_null());
  CHECK(c["energy"].get<double>() == 0.0);
  double min_gap = 1e9;
  for (double g : gap) min_gap = std::min(min_gap, g);
  CHECK(c["min_gap"].get<double>() == min_gap);
  CHECK(j["energy"]["contacts"][0].get<double>() == 0.0);
  // The terminal report says the results after t are not valid.
  const std::string brief = brief_report(scene, files.report);
  CHECK(brief.find("pounding is not modelled (set contact[1].model)") != std::string::npos);
  CHECK(brief.find("not valid") != std::string::npos);
  // The sweep row's flag and values are the summary's.
  const auto cells = sweep_cells(scene, files.report);
  CHECK(cells.at("contact1.outside_model") == "true");
  CHECK(cells.at("contact1.contact") == "true");
  CHECK(cells.at("contact1.impacts") == "0");
  CHECK(std::stod(cells.at("contact1.min_gap")) == min_gap);
}

TEST_CASE("a joint that never closes: no flag, no impacts file", "[building_run][pounding]") {
  const fs::path dir = scratch("wide");
  // A leftover impacts.csv of an earlier run in the folder goes with the rest of the set.
  std::ofstream(dir / "impacts.csv") << "stale\n";
  BuildingScene scene = pounding_scene({"contact.1.gap=1.0"});
  REQUIRE(scene.structure.contacts.at(0).gap == 1.0);
  const RunFiles files = run_to_folder(scene, dir);
  CHECK(!fs::exists(dir / "impacts.csv"));
  const auto j = summary(dir);
  CHECK(j["contacts"][0]["contact"] == false);
  CHECK(j["contacts"][0]["outside_model_from"].is_null());
  CHECK(j["outside_model_from"].is_null());
  CHECK(j["flags"].empty());
  CHECK(j["contacts"][0]["min_gap"].get<double>() > 0.5);
  const auto ts = columns(dir / "timeseries.csv");
  for (double v : ts.at("outside_model")) REQUIRE(v == 0.0);
  const auto cells = sweep_cells(scene, files.report);
  CHECK(cells.at("contact1.outside_model") == "false");
  CHECK(cells.at("contact1.contact") == "false");
  CHECK(brief_report(scene, files.report).find("not valid") == std::string::npos);
  // With a contact law and no contact: impacts.csv is written, header only, and no flag column.
  BuildingScene lawful = scene;
  set_linear_law(lawful);
  const fs::path d2 = scratch("wide-law");
  run_to_folder(lawful, d2);
  REQUIRE(fs::exists(d2 / "impacts.csv"));
  const auto rows = csv(d2 / "impacts.csv");
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].size() == 10);
  CHECK(rows[0][0] == "contact");
  CHECK(!read_csv_table(d2 / "timeseries.csv").has("outside_model"));
  CHECK(summary(d2)["contacts"][0]["model"] == "linear");
}

TEST_CASE("pounding with a contact law: impacts.csv, summary and sweep cells are the solver's impacts", "[building_run][pounding]") {
  BuildingScene scene = pounding_scene();
  set_linear_law(scene);
  Recorder rec;
  const Report direct = run(scene, {&rec});
  REQUIRE(rec.impacts.size() >= 3);  // the joint closes several times
  const fs::path dir = scratch("linear");
  const RunFiles files = run_to_folder(scene, dir);
  // impacts.csv: one row per streamed impact, in the order they started, every field.
  std::vector<Impact> events = rec.impacts;
  std::stable_sort(events.begin(), events.end(), [](const Impact& a, const Impact& b) { return a.start < b.start; });
  const CsvTable table = read_csv_table(dir / "impacts.csv");
  REQUIRE(table.columns == std::vector<std::string>{"contact", "t_start", "duration", "force_max", "t_force_max", "penetration_max",
                                                    "approach_speed", "rebound_speed", "impulse", "complete"});
  REQUIRE(table.rows.size() == events.size());
  const std::vector<double> start = table.numbers("t_start"), force = table.numbers("force_max"),
                            pen = table.numbers("penetration_max"), v0 = table.numbers("approach_speed"),
                            impulse = table.numbers("impulse"), duration = table.numbers("duration"),
                            complete = table.numbers("complete"), which = table.numbers("contact");
  double force_max = 0.0, t_force_max = 0.0, pen_max = 0.0, impulse_sum = 0.0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    INFO("impact " << i);
    CHECK(which[i] == events[i].contact + 1);
    CHECK(start[i] == events[i].start);  // shortest round-trip text: exact
    CHECK(duration[i] == events[i].duration);
    CHECK(force[i] == events[i].force_max);
    CHECK(pen[i] == events[i].penetration_max);
    CHECK(v0[i] == events[i].approach_speed);
    CHECK(impulse[i] == events[i].impulse);
    CHECK(complete[i] == (events[i].complete ? 1.0 : 0.0));
    if (i > 0) CHECK(start[i] >= start[i - 1]);
    if (events[i].force_max > force_max) { force_max = events[i].force_max; t_force_max = events[i].t_force_max; }
    pen_max = std::max(pen_max, events[i].penetration_max);
    impulse_sum += events[i].impulse;
  }
  CHECK(force_max > 0.0);
  // The report and the summary: the impacts' totals and the solver's dissipated energy.
  const auto j = summary(dir);
  const auto& c = j["contacts"][0];
  CHECK(c["model"] == "linear");
  CHECK(c["impacts"].get<std::size_t>() == events.size());
  CHECK(c["force_max"].get<double>() == force_max);
  CHECK(c["t_force_max"].get<double>() == t_force_max);
  CHECK(c["penetration_max"].get<double>() == pen_max);
  CHECK(c["impulse"].get<double>() == Approx(impulse_sum).epsilon(1e-12));
  CHECK(c["t_first_contact"].get<double>() <= events.front().start);
  CHECK(c["t_first_contact"].get<double>() > events.front().start - scene.solver.h);
  REQUIRE(rec.last.contact_dissipated.size() == 1);
  CHECK(c["energy"].get<double>() == rec.last.contact_dissipated[0]);
  CHECK(c["energy"].get<double>() > 0.0);  // e < 1 dissipates
  CHECK(j["energy"]["contacts"][0].get<double>() == rec.last.contact_work[0]);
  CHECK(c["outside_model_from"].is_null());
  CHECK(j["flags"].empty());
  CHECK(direct.contacts[0].impacts == events.size());
  // The time series: the force column is the solver's force, and there is no flag column.
  const auto ts = columns(dir / "timeseries.csv");
  CHECK(ts.count("outside_model") == 0);
  REQUIRE(ts.at("contact1.force").size() == rec.force.size());
  for (std::size_t i = 0; i < rec.force.size(); i += 13) REQUIRE(ts.at("contact1.force")[i] == rec.force[i]);
  // The sweep columns are the summary's values.
  const auto cells = sweep_cells(scene, files.report);
  CHECK(std::stoul(cells.at("contact1.impacts")) == events.size());
  CHECK(std::stod(cells.at("contact1.force_max")) == force_max);
  CHECK(std::stod(cells.at("contact1.penetration_max")) == pen_max);
  CHECK(std::stod(cells.at("contact1.energy_share")) ==
        Approx(c["energy"].get<double>() / j["energy"]["input"].get<double>()).epsilon(1e-12));
  CHECK(cells.at("contact1.outside_model") == "false");
  CHECK(cells.at("contact1.contact") == "true");
  // The terminal line.
  const std::string brief = brief_report(scene, files.report);
  CHECK(brief.find("contact1 (linear): " + std::to_string(events.size()) + " impact") != std::string::npos);
}

TEST_CASE("the energy balance with pounding closes at order 2", "[building_run][pounding][energy]") {
  BuildingScene scene = pounding_scene({"output.timeseries=false"});
  set_linear_law(scene);
  std::vector<double> residuals;
  for (double h : {0.002, 0.001}) {
    scene.solver.h = h;
    const Report r = run(scene);
    REQUIRE(r.contacts[0].impacts >= 3);
    INFO("h = " << h << ": input " << r.energy.input << " J, contact work " << r.energy.contacts[0] << " J, residual "
                << r.energy.residual << " J");
    CHECK(r.energy.contacts[0] >= r.contacts[0].dissipated * (1 - 1e-12));  // stored energy >= 0
    CHECK(r.contacts[0].dissipated > 1e-3 * r.energy.input);               // the impacts matter here
    // The balance without the contact's work would be off by it.
    CHECK(std::abs(r.energy.residual) < 0.1 * r.contacts[0].dissipated);
    residuals.push_back(std::abs(r.energy.residual) / r.energy.input);
  }
  INFO("relative residuals " << residuals[0] << " " << residuals[1]);
  CHECK(residuals[1] < 1e-4);
  CHECK(residuals[0] / residuals[1] > 3.0);
}

TEST_CASE("building sweeps: the pounding columns of a row are the single run's summary values", "[building_sweep][pounding]") {
  const std::string base = "\"" + kScene.string() + "\"";
  const fs::path file = write_temp("pounding-sweep.toml",
                                   "base = " + base +
                                       "\nset = {\"solver.t_end\" = 8.0, \"output.timeseries\" = false}\n"
                                       "[[axis]]\nkey = \"contact.1.gap\"\nvalues = [0.05, 1.0]\n");
  const SweepSpec spec = load_sweep(file);
  REQUIRE(spec.building());
  const auto& cols = spec.channel_columns;  // the row's channel cells, in this order
  auto column = [&](const std::string& name) {
    const auto it = std::find_if(cols.begin(), cols.end(), [&](const SweepColumn& c) { return c.name == name; });
    REQUIRE(it != cols.end());
    return static_cast<std::size_t>(it - cols.begin());
  };
  for (std::size_t run = 0; run < 2; ++run) {
    INFO("run " << run);
    const SweepRow row = run_sweep_point(spec, run);
    REQUIRE(row.error.empty());
    const BuildingScene scene = sweep_scene(spec, run);
    const fs::path dir = scratch("sweep-" + std::to_string(run));
    run_to_folder(scene, dir);
    const auto c = summary(dir)["contacts"][0];
    REQUIRE(row.channels.size() == cols.size());
    auto cell = [&](const std::string& name) { return row.channels.at(column(name)); };
    CHECK(std::stod(cell("contact1.min_gap")) == c["min_gap"].get<double>());
    CHECK(cell("contact1.contact") == (c["contact"].get<bool>() ? "true" : "false"));
    CHECK(cell("contact1.outside_model") == (c["outside_model_from"].is_null() ? "false" : "true"));
    CHECK(std::stoul(cell("contact1.impacts")) == c["impacts"].get<std::size_t>());
    CHECK(std::stod(cell("contact1.force_max")) == c["force_max"].get<double>());
    CHECK(cell("contact1.outside_model") == (run == 0 ? "true" : "false"));
  }
}

TEST_CASE("plot run on a building run with contacts draws contacts with the impacts marked", "[plot][cli][pounding]") {
  adjoin::test::needs_program("gnuplot");
  const fs::path dir = scratch("plot-none");
  run_to_folder(pounding_scene(), dir);
  const fs::path out = scratch("plot-none-svg") / "";
  const auto none = run_cli("plot run '" + dir.string() + "' --format svg --out '" + out.string() + "'");
  INFO(none.err);
  REQUIRE(none.status == 0);
  const std::string svg = slurp(out / "contacts.svg");
  CHECK(svg.find("contact1.gap") != std::string::npos);
  CHECK(svg.find("contact1.force") == std::string::npos);  // no contact law: no force panel
  CHECK(svg.find("outside the model") != std::string::npos);
  CHECK(svg.find("contact1 impacts") == std::string::npos);
  // With a contact law: the impacts of impacts.csv marked.
  BuildingScene scene = pounding_scene();
  set_linear_law(scene);
  const fs::path law = scratch("plot-law");
  const RunFiles files = run_to_folder(scene, law);
  REQUIRE(files.report.contacts[0].impacts > 0);
  const fs::path png = scratch("plot-law-png") / "";
  const auto drawn = run_cli("plot run '" + law.string() + "' --size 800x500 --out '" + png.string() + "'");
  INFO(drawn.err);
  REQUIRE(drawn.status == 0);
  adjoin::test::require_png(png / "contacts.png", 800, 500);
  const fs::path svg2 = scratch("plot-law-svg") / "";
  REQUIRE(run_cli("plot run '" + law.string() + "' --format svg --out '" + svg2.string() + "'").status == 0);
  const std::string text = slurp(svg2 / "contacts.svg");
  CHECK(text.find("contact1.force") != std::string::npos);
  CHECK(text.find("contact1 impacts") != std::string::npos);
  CHECK(text.find("contact1 peak forces") != std::string::npos);
  CHECK(text.find("outside the model") == std::string::npos);
}

TEST_CASE("the terminal line of a Newton-law pair gives its largest impulse, not a peak force of 0 N, and counts agree in number",
          "[building_run][pounding]") {
  BuildingScene scene = pounding_scene({"output.timeseries=false"});
  auto& law = scene.structure.contacts.at(0).law;
  law.model = structure::ContactModel::impact;
  law.restitution = 0.65;
  const Report r = run(scene);
  const ContactReport& c = r.contacts.at(0);
  REQUIRE(c.impacts >= 2);
  REQUIRE(c.impulse_max > 0.0);
  const std::string brief = brief_report(scene, r);
  INFO(brief);
  CHECK(brief.find("contact1 (impact): " + std::to_string(c.impacts) + " impacts,") != std::string::npos);
  CHECK(brief.find("peak force") == std::string::npos);
  CHECK(brief.find("max penetration") == std::string::npos);
  char impulse[64];
  std::snprintf(impulse, sizeof impulse, "largest impulse %.4g N s", c.impulse_max);
  CHECK(brief.find(impulse) != std::string::npos);
  // One impact, one switch: singular (a report made up for the wording; the counts are the
  // report's own).
  Report one = r;
  one.contacts.at(0).impacts = 1;
  REQUIRE_FALSE(one.links.empty());
  one.links.at(0).switches = 1;
  const std::string single = brief_report(scene, one);
  INFO(single);
  CHECK(single.find("contact1 (impact): 1 impact,") != std::string::npos);
  CHECK(single.find(", 1 switch\n") != std::string::npos);
  CHECK(single.find("1 switches") == std::string::npos);
}

TEST_CASE("an elastic Hertz contact beside a friction damper gives back what it took, to order 2, or the run stops",
          "[building_run][pounding][energy]") {
  // The frames' floors 3 carry both the friction link and the contact: the two are split in
  // the step. At a realistic k_h (2e10 N/m^1.5) the elastic law's "dissipated" energy is the
  // split's error and falls as h^2; at 1e16 and h = 2 ms the split breaks down (the contact
  // made energy: -2.6e8 J against an input of 2.6e6 J, forces of 5e11 N) and the run stops.
  auto hertz = [](double k, double h) {
    BuildingScene scene = pounding_scene({"output.timeseries=false", "solver.h=" + std::to_string(h)});
    auto& law = scene.structure.contacts.at(0).law;
    law.model = structure::ContactModel::hertz;
    law.stiffness = k;
    return scene;
  };
  std::vector<double> lost;
  for (double h : {0.002, 0.001}) {
    const Report r = run(hertz(2e10, h));
    REQUIRE(r.contacts[0].impacts >= 5);
    INFO("h " << h << ": dissipated " << r.contacts[0].dissipated << " J of an input of " << r.energy.input << " J");
    CHECK(std::abs(r.contacts[0].dissipated) < 1e-3 * r.energy.input);
    lost.push_back(std::abs(r.contacts[0].dissipated));
  }
  CHECK(lost[1] < 0.35 * lost[0]);  // order 2: a quarter
  try {
    run(hertz(1e16, 0.002));
    FAIL("the run did not stop");
  } catch (const NumericalError& e) {
    const std::string m = e.what();
    INFO(m);
    CHECK(m.find("contact pair 1 (hertz): at t = ") != std::string::npos);
    CHECK(m.find("more than the work done on it") != std::string::npos);
    CHECK(m.find("make solver.h smaller or lower contact[1].stiffness") != std::string::npos);
    CHECK(e.time() > 3.8);  // (the first impact is at 3.89 s)
  }
}
