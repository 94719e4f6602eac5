// Sweeps whose base is a building scene (study/sweep_columns.hpp): a row is the building run
// of the same edits, the columns are the base structure's channels, and the journal, shards and
// demand models work on them as on two-block sweeps.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/sweep_columns.hpp"
#include "adjoin/study/demand.hpp"
#include "adjoin/study/sweep.hpp"
#include "cli_helpers.hpp"
#include "csv_rows.hpp"

using namespace adjoin;
using adjoin::test::csv_rows;
using adjoin::test::run_cli;
using adjoin::test::slurp;
using adjoin::test::write_temp;

namespace {

const std::filesystem::path kExamples = std::filesystem::path(ADJOIN_SOURCE_DIR) / "examples";
const std::filesystem::path kOneDamper = kExamples / "buildings" / "two-frames-one-damper.toml";
const std::filesystem::path kTwoDampers = kExamples / "buildings" / "two-frames-two-dampers.toml";

std::string qpath(const std::filesystem::path& p) { return "\"" + p.string() + "\""; }

// Short runs: 4 s of the Newhall record at h = 0.004 s, no files.
const char* kShort = "set = {\"solver.t_end\" = 4.0, \"solver.h\" = 0.004, \"output.timeseries\" = false}\n";

std::filesystem::path sweep_file(const std::string& name, const std::filesystem::path& base, const std::string& body) {
  return write_temp(name, "base = " + qpath(base) + "\n" + kShort + body);
}

std::size_t column_of(const std::vector<SweepColumn>& columns, const std::string& name) {
  const auto it = std::find_if(columns.begin(), columns.end(), [&](const SweepColumn& c) { return c.name == name; });
  REQUIRE(it != columns.end());
  return static_cast<std::size_t>(it - columns.begin());
}

std::vector<std::string> names(const std::vector<SweepColumn>& columns) {
  std::vector<std::string> out;
  for (const auto& c : columns) out.push_back(c.name);
  return out;
}

double number(const std::string& cell) {
  REQUIRE(!cell.empty());
  return std::stod(cell);
}

// Every cell except wall_seconds.
std::vector<std::vector<std::string>> without_wall_time(const SweepTable& table) {
  const std::size_t wall = column_of(table.columns, "wall_seconds");
  std::vector<std::vector<std::string>> rows = table.rows;
  for (auto& r : rows) r.erase(r.begin() + static_cast<std::ptrdiff_t>(wall));
  return rows;
}


}  // namespace

TEST_CASE("building sweeps: a row equals the building run of the same edits, cell for cell", "[building_sweep]") {
  const SweepSpec spec = load_sweep(sweep_file("row.toml", kOneDamper, R"(
[[axis]]
key = "link.1.slip_ratio"
values = [0.02, 0.1]
[[axis]]
key = "building.A.damping.ratio"
values = [0.02, 0.05]
[output]
im_periods = [1.0]
)"));
  REQUIRE(spec.building());
  REQUIRE(spec.runs() == 4);
  const std::size_t index = 2;  // slip 0.1, damping 0.02
  const SweepRow row = run_sweep_point(spec, index);
  CHECK(row.error.empty());
  const BuildingScene scene =
      load_building_scene(kOneDamper,
                          {"solver.t_end=4.0", "solver.h=0.004", "output.timeseries=false", "link.1.slip_ratio=0.1",
                           "building.A.damping.ratio=0.02"});
  const Report report = run(scene);
  CHECK(row.channels == building_channel_cells(scene.structure, scene, report));
  // Spelled out for the columns one reads first.
  const auto columns = sweep_columns(spec);
  const auto cells = sweep_cells(spec, row);
  REQUIRE(cells.size() == columns.size());
  CHECK(cells[1] == "0.1");
  CHECK(cells[2] == "0.02");
  CHECK(number(cells[column_of(columns, "A.roof_max")]) == report.peaks[4].peak.max_abs);  // A.x5
  CHECK(report.peaks[4].channel == "A.x5");
  CHECK(number(cells[column_of(columns, "link1.stroke_max")]) == report.links[0].stroke_max);
  CHECK(number(cells[column_of(columns, "link1.force_max")]) == report.links[0].force_max);
  CHECK(std::stoul(cells[column_of(columns, "link1.switches")]) == report.links[0].switches);
  CHECK(number(cells[column_of(columns, "energy_input")]) == report.energy.input);
  CHECK(number(cells[column_of(columns, "A.T1")]) == report.modes[0].periods[0]);
  CHECK(cells[column_of(columns, "units")] == "SI");
  CHECK(number(cells[column_of(columns, "pga_g")]) > 0.1);
  CHECK(number(cells[column_of(columns, "sa_1")]) > 0.0);
  // A friction link never carries more than its slip force.
  CHECK(report.links[0].force_max <= scene.structure.links[0].slip_force * (1 + 1e-12));
}

TEST_CASE("building sweeps: the columns are the base structure's channels", "[building_sweep]") {
  const SweepSpec spec = load_sweep(sweep_file("columns.toml", kTwoDampers, "[[axis]]\nkey = \"link.2.slip_ratio\"\nvalues = [0.01]\n"));
  const auto n = names(sweep_columns(spec));
  const std::vector<std::string> expected = {
      "index", "link.2.slip_ratio", "motion", "units",
      "A.T1", "A.roof_max", "A.drift_max", "A.drift_storey", "A.drift_ratio_max", "A.accel_max", "A.base_shear_max", "A.share_inherent",
      "B.T1", "B.roof_max", "B.drift_max", "B.drift_storey", "B.drift_ratio_max", "B.accel_max", "B.base_shear_max", "B.share_inherent",
      "link1.force_max", "link1.stroke_max", "link1.switches", "link1.energy_share",
      "link2.force_max", "link2.stroke_max", "link2.switches", "link2.energy_share",
      "contact1.min_gap", "contact1.contact", "contact1.impacts", "contact1.force_max", "contact1.penetration_max",
      "contact1.energy_share", "contact1.outside_model", "energy_input", "share_residual", "collapse_t", "pga_g", "wall_seconds", "error"};
  CHECK(n == expected);
  // One building, no links: its columns only.
  const auto single = building_channel_columns(
      load_building_scene(kOneDamper, {}, {"building.B", "link", "contact"}).structure);
  CHECK(names(single) == std::vector<std::string>{"A.T1", "A.roof_max", "A.drift_max", "A.drift_storey", "A.drift_ratio_max",
                                                  "A.accel_max", "A.base_shear_max", "A.share_inherent", "energy_input",
                                                  "share_residual", "collapse_t"});
}

TEST_CASE("building sweeps: slip limits, a run without its links leaves their cells empty", "[building_sweep]") {
  // No damper, a tiny slip force, a huge one (the floors locked together).
  const SweepSpec spec = load_sweep(sweep_file("limits.toml", kOneDamper, R"(
[[axis]]
key = "link.1.slip_ratio"
values = [{name = "0", unset = ["link"]}, 1e-9, 100.0]
)"));
  CHECK(sweep_columns(spec)[1].type == ColumnType::number);  // "0" counts as a number
  const auto table = sweep_table(spec, run_sweep(spec, {}));
  const auto& c = table.columns;
  const auto& none = table.rows[0];
  const auto& tiny = table.rows[1];
  const auto& locked = table.rows[2];
  CHECK(none[column_of(c, "link1.stroke_max")].empty());
  CHECK(none[column_of(c, "link1.switches")].empty());
  CHECK(none.back().empty());  // not a failure
  // The row of a run without links passes the journal's check.
  std::size_t index = 0;
  CHECK(sweep_row_problem(spec, SweepShard{}, none, &index) == "");
  // Slip force -> 0: the link's force -> 0 and the buildings move as if uncoupled.
  CHECK(number(tiny[column_of(c, "link1.force_max")]) <= 1e-9 * 170.0e3 * 9.80665 * (1 + 1e-9));
  CHECK(number(tiny[column_of(c, "A.roof_max")]) == Approx(number(none[column_of(c, "A.roof_max")])).epsilon(1e-6));
  CHECK(number(tiny[column_of(c, "B.roof_max")]) == Approx(number(none[column_of(c, "B.roof_max")])).epsilon(1e-6));
  // A slip force far above any force the link can see: it never slips (stroke 0, no switch).
  CHECK(number(locked[column_of(c, "link1.stroke_max")]) < 1e-12);
  CHECK(locked[column_of(c, "link1.switches")] == "0");
  CHECK(number(locked[column_of(c, "link1.energy_share")]) == Approx(0.0).margin(1e-9));
}

TEST_CASE("building sweeps: a run may remove its last links, not renumber the others", "[building_sweep]") {
  const auto file = sweep_file("some-links.toml", kTwoDampers, R"(
[[axis]]
name = "dampers"
values = [{name = "both"},
          {name = "upper", unset = ["link.1"]},
          {name = "lower", unset = ["link.2"]}]
)");
  const SweepSpec spec = load_sweep(file);
  CHECK(spec.link_columns == 2);
  CHECK_NOTHROW(sweep_scene(spec, 0));
  CHECK(sweep_scene(spec, 2).structure.links.size() == 1);
  try {
    sweep_scene(spec, 1);
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    const std::string m = e.what();
    INFO(m);
    CHECK(m.find(file.string() + ":7: run 1 (dampers=upper, motion=base)") != std::string::npos);
    CHECK(m.find("it removes link.1 but keeps link.2, which would become link.1") != std::string::npos);
    CHECK(m.find("unset = [\"link.2\"]") != std::string::npos);
  }
}

TEST_CASE("building sweeps: each run's scene and message from the base parsed once equal adjoin run --set", "[building_sweep]") {
  // The sweep parses its base once and reads each run from a copy of the tree with the run's
  // edits; `adjoin run BASE --set ... --unset ...` parses the text with the same edits. Their
  // scenes and messages (the base's lines included, also after --unset link.1 shifts the
  // [[link]] tables) must be the same.
  const SweepSpec spec = load_sweep(sweep_file("tree.toml", kTwoDampers, R"(
[[axis]]
name = "edit"
values = [{name = "ok", set = {"link.1.slip_ratio" = 0.05, "building.A.period" = 1.5, "name" = "swept"}},
          {name = "shifted", unset = ["link.1"], set = {"building.A.storeys" = 1}},
          {name = "no-stiffness", unset = ["building.A.stiffness"]},
          {name = "ratio", set = {"building.A.damping.ratio" = 1.5}},
          {name = "link3", set = {"link.3.slip_ratio" = 0.1}},
          {name = "units", set = {"model.units" = "SI"}},
          {name = "no-file", unset = ["ground.file"]},
          {name = "of", set = {"link.2.of" = "C"}},
          {name = "typo", set = {"building.A.stifness" = 1.0}},
          {name = "gap", set = {"contact.1.gap" = -0.01}},
          {name = "upper", unset = ["link.2", "solver.t_end"], set = {"building.B.period" = 0.6}}]
)"));
  std::size_t base_lines = 0, compared = 0;
  for (std::size_t i = 0; i < spec.runs(); ++i) {
    std::vector<std::string> overrides, unsets;
    for (const auto& s : spec.settings(i)) {
      for (const auto& o : s.overrides()) overrides.push_back(o);
      unsets.insert(unsets.end(), s.unset.begin(), s.unset.end());
    }
    std::string expected = "no error";
    std::optional<BuildingScene> run;
    try {
      run = load_building_scene(kTwoDampers, overrides, unsets);
    } catch (const InputError& e) {
      expected = e.what();
    }
    std::string got = "no error";
    std::optional<BuildingScene> swept;
    try {
      swept = spec.scenes->scene(spec, i);
    } catch (const InputError& e) {
      got = e.what();
      // "tree.toml:LINE: run i (edit=..., motion=base): " + the scene's own message
      const std::string prefix = "run " + std::to_string(i) + " (" + spec.describe(i) + "): ";
      REQUIRE(got.find(prefix) != std::string::npos);
      got = got.substr(got.find(prefix) + prefix.size());
    }
    INFO("run " << i << " (" << spec.axes[0].values[i].label << ")");
    CHECK(got == expected);
    if (expected.rfind(kTwoDampers.string() + ":", 0) == 0) ++base_lines;
    if (run && swept) {
      ++compared;
      CHECK(swept->name == run->name);
      CHECK(swept->structure.a.springs == run->structure.a.springs);
      CHECK(swept->structure.b->masses == run->structure.b->masses);
      REQUIRE(swept->structure.links.size() == run->structure.links.size());
      for (std::size_t l = 0; l < run->structure.links.size(); ++l)
        CHECK(swept->structure.links[l].slip_force == run->structure.links[l].slip_force);
      CHECK(swept->solver.h == run->solver.h);
      CHECK(swept->solver.t_end == run->solver.t_end);
      CHECK(swept->accuracy.h_rule == run->accuracy.h_rule);
      CHECK(swept->accuracy.t_end_rule == run->accuracy.t_end_rule);
      CHECK(swept->warnings == run->warnings);
      for (double t : {0.3, 1.7}) CHECK(swept->ground->ag(t) == run->ground->ag(t));
    }
  }
  CHECK(compared == 2);
  CHECK(spec.scenes->scene(spec, 0).name == "swept");
  CHECK(spec.scenes->scene(spec, 0).structure.links[0].slip_force != spec.scenes->scene(spec, 10).structure.links[0].slip_force);
  // Those messages cite the base file's lines: a shifted [[link]], [building.A], [ground].
  CHECK(base_lines >= 3);
}

TEST_CASE("building sweeps: an axis over a key the structure does not have names the line and key", "[building_sweep]") {
  // link.3 on a scene of one link (link.2 would add the next one).
  const auto file = sweep_file("no-key.toml", kOneDamper, "[[axis]]\nkey = \"link.3.slip_ratio\"\nvalues = [0.1]\n");
  const SweepSpec spec = load_sweep(file);
  try {
    run_sweep(spec, {});
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    const std::string m = e.what();
    CHECK(m.find(file.string() + ":5: run 0") != std::string::npos);
    CHECK(m.find("--set link.3.slip_ratio=0.1: the scene has 1 [[link]] table, not a number 3") != std::string::npos);
  }
}

TEST_CASE("building sweeps: resume from a journal, shards merged, and adjoin sweep give one table", "[building_sweep]") {
  const auto file = sweep_file("cli.toml", kOneDamper, R"(
name = "b-cli"
[[axis]]
key = "link.1.slip_ratio"
values = [{name = "0", unset = ["link"]}, 0.05]
[[motion]]
name = "newhall"
[[motion]]
name = "newhall-half"
set = {"ground.scale_pga" = 0.2}
)");
  const std::filesystem::path dir = std::filesystem::path(ADJOIN_TEST_TMP) / "b-cli";
  std::filesystem::remove_all(dir);
  const auto whole = run_cli("sweep " + file.string() + " --out " + (dir / "whole").string() + " --quiet --jobs 2");
  REQUIRE(whole.status == 0);
  const auto expected = csv_rows(slurp(dir / "whole" / "sweep.csv"), true);
  REQUIRE(expected.size() == 5);
  CHECK(expected[0][5] == "A.roof_max");

  // An interrupted sweep: the journal holds runs 0 and 3 (a torn line after them).
  const SweepSpec spec = load_sweep(file);
  std::filesystem::create_directories(dir / "resumed");
  {
    std::ofstream journal(dir / "resumed" / "sweep.partial.csv", std::ios::binary);
    journal << sweep_journal_preamble(spec, SweepShard{});
    for (std::size_t i : {3u, 0u}) journal << csv_line(sweep_cells(spec, run_sweep_point(spec, i))) << "\n";
    journal << "1,0,newh";
  }
  const auto resumed = run_cli("sweep " + file.string() + " --out " + (dir / "resumed").string() + " --jobs 1");
  REQUIRE(resumed.status == 0);
  CHECK(resumed.err.find("resuming: 2 runs") != std::string::npos);
  CHECK(resumed.err.find("warning") == std::string::npos);
  CHECK(csv_rows(slurp(dir / "resumed" / "sweep.csv"), true) == expected);

  // Two shards merged.
  for (const char* shard : {"0/2", "1/2"})
    REQUIRE(run_cli("sweep " + file.string() + " --out " + (dir / "shards").string() + " --quiet --shard " + shard).status == 0);
  REQUIRE(run_cli("sweep merge " + (dir / "shards").string() + " --out " + (dir / "merged.csv").string()).status == 0);
  CHECK(csv_rows(slurp(dir / "merged.csv"), true) == expected);

  // sweep.json: typed cells, empty ones as null.
  const SweepTableFile json = read_sweep_json(dir / "whole" / "sweep.json");
  CHECK(json.table.columns[column_of(json.table.columns, "link1.switches")].type == ColumnType::integer);
  CHECK(json.table.columns[column_of(json.table.columns, "contact1.contact")].type == ColumnType::boolean);
  CHECK(without_wall_time(json.table) == std::vector<std::vector<std::string>>(expected.begin() + 1, expected.end()));
}

TEST_CASE("building sweeps: demand models fit any channel column", "[building_sweep]") {
  const auto file = sweep_file("demand.toml", kOneDamper, R"(
name = "b-demand"
[[motion]]
name = "s0.25"
set = {"ground.scale_pga" = 0.1}
[[motion]]
name = "s0.5"
set = {"ground.scale_pga" = 0.2}
[[motion]]
name = "s1"
set = {"ground.scale_pga" = 0.4}
)");
  const std::filesystem::path dir = std::filesystem::path(ADJOIN_TEST_TMP) / "b-demand";
  std::filesystem::remove_all(dir);
  REQUIRE(run_cli("sweep " + file.string() + " --out " + dir.string() + " --quiet").status == 0);
  const SweepCsvTable table = read_sweep_csv(dir / "sweep.csv");
  const auto fits = fit_sweep_demand(table, "A.drift_max", "pga");
  REQUIRE(fits.size() == 1);
  REQUIRE(fits[0].problem.empty());
  CHECK(fits[0].usable == 3);
  // The same record scaled: the fit runs through the three points; with a friction damper the
  // response is not proportional to the scale, but it grows with it.
  CHECK(fits[0].fit.b > 0.0);
  const auto cli = run_cli("demand " + (dir / "sweep.csv").string() + " --response link1.stroke_max --im pga");
  CHECK(cli.status == 0);
}

TEST_CASE("building sweeps: the output reference documents every column of the registry", "[building_sweep]") {
  const std::string readme = slurp(std::filesystem::path(ADJOIN_SOURCE_DIR) / "docs" / "reference" / "outputs.md");
  for (const auto& c : building_sweep_channels()) {
    INFO(c.name);
    CHECK(readme.find("| `" + c.name + "` |") != std::string::npos);
  }
}

TEST_CASE("building sweeps: the optimum slip-force example parses, one column per channel of its two frames", "[building_sweep]") {
  const SweepSpec spec = load_sweep(kExamples / "sweeps" / "optimum-slip-force.toml");
  REQUIRE(spec.building());
  CHECK(spec.runs() == spec.axes[0].values.size() * 3);
  CHECK(sweep_columns(spec)[1].type == ColumnType::number);
  const auto n = names(sweep_columns(spec));
  CHECK(std::count(n.begin(), n.end(), "link1.stroke_max") == 1);
  CHECK(std::count(n.begin(), n.end(), "B.drift_max") == 1);
  CHECK(std::count(n.begin(), n.end(), "sa_1.9") == 1);
  // Its "0" point has no link.
  CHECK(sweep_scene(spec, 0).structure.links.empty());
  CHECK(sweep_scene(spec, 3).structure.links.size() == 1);
}
