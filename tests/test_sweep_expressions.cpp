// Sweeps that say what engineers mean (SPEC §9): list-valued keys, a link's type changed, a
// link added or removed, as an axis of tables or as [[variant]] tables. Each run is checked
// bit for bit against the same edits made by hand: `adjoin run BASE --set ... --unset ...`
// (load_building_scene with those options, then run), and, for a type change, against the scene
// file edited by hand.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/sweep.hpp"
#include "adjoin/study/sweep_columns.hpp"
#include "cli_helpers.hpp"
#include "csv_rows.hpp"

using namespace adjoin;
using adjoin::test::csv_rows;
using adjoin::test::run_cli;
using adjoin::test::slurp;
using adjoin::test::write_temp;

namespace {

const std::filesystem::path kBuildings = std::filesystem::path(ADJOIN_SOURCE_DIR) / "examples" / "buildings";
const std::filesystem::path kOneDamper = kBuildings / "two-frames-one-damper.toml";
const std::filesystem::path kTwoDampers = kBuildings / "two-frames-two-dampers.toml";

// Short runs: 3 s of the Newhall record at h = 0.004 s, no files; the same as --set options.
const char* kShort = "set = {\"solver.t_end\" = 3.0, \"solver.h\" = 0.004, \"output.timeseries\" = false}\n";
const std::vector<std::string> kShortSets = {"solver.t_end=3.0", "solver.h=0.004", "output.timeseries=false"};

std::filesystem::path sweep_file(const std::string& name, const std::filesystem::path& base, const std::string& body) {
  return write_temp(name, "base = \"" + base.string() + "\"\n" + kShort + body);
}

std::size_t column_of(const std::vector<SweepColumn>& columns, const std::string& name) {
  const auto it = std::find_if(columns.begin(), columns.end(), [&](const SweepColumn& c) { return c.name == name; });
  REQUIRE(it != columns.end());
  return static_cast<std::size_t>(it - columns.begin());
}

// The sweep's run `index` against `adjoin run BASE --set <sets> --unset <unsets>` done by hand:
// every channel cell the same, bit for bit (the cells are shortest round-trip numbers). Returns
// the hand-made scene.
BuildingScene check_same_as_by_hand(const SweepSpec& spec, std::size_t index, const std::filesystem::path& base,
                                    const std::vector<std::string>& sets, const std::vector<std::string>& unsets = {}) {
  INFO("run " << index << " (" << spec.describe(index) << ")");
  const SweepRow row = run_sweep_point(spec, index);
  REQUIRE(row.error.empty());
  std::vector<std::string> overrides = kShortSets;
  overrides.insert(overrides.end(), sets.begin(), sets.end());
  BuildingScene scene = load_building_scene(base, overrides, unsets);
  const Report report = run(scene);
  const ChannelCounts counts{2, spec.link_columns, spec.contact_columns};
  CHECK(row.channels == building_channel_cells(counts, scene, report));
  return scene;
}

}  // namespace

TEST_CASE("sweep expressions: list-valued keys on an axis and in a table value equal --set by hand, bit for bit", "[sweep_expressions]") {
  const auto file = sweep_file("lists.toml", kOneDamper, R"(
[[axis]]
name = "placement"
values = [[3, 3], [2, 3], [1, 2],
          {name = "floor2-heavy", set = {"link.1.floors" = [2, 2], "building.B.masses" = [6.0e4, 6.0e4, 4.0e4]}}]
key = "link.1.floors"
)");
  const SweepSpec spec = load_sweep(file);
  REQUIRE(spec.runs() == 4);
  // Spelled by hand as a user types them (no spaces): the same scene.
  check_same_as_by_hand(spec, 0, kOneDamper, {"link.1.floors=[3,3]"});
  const BuildingScene moved = check_same_as_by_hand(spec, 1, kOneDamper, {"link.1.floors=[2,3]"});
  CHECK(moved.structure.links[0].floor_a == 2);
  CHECK(moved.structure.links[0].floor_b == 3);
  check_same_as_by_hand(spec, 2, kOneDamper, {"link.1.floors=[1,2]"});
  const BuildingScene heavy =
      check_same_as_by_hand(spec, 3, kOneDamper, {"link.1.floors=[2,2]", "building.B.masses=[6.0e4,6.0e4,4.0e4]"});
  CHECK(heavy.structure.b->masses[2] == 4.0e4);

  // The table: the list as written ("[2, 3]"), quoted in the CSV because of its comma, and a
  // string column (the values are not numbers). The placements change the answer.
  const SweepTable table = sweep_table(spec, run_sweep(spec, {}));
  CHECK(table.columns[1].name == "placement");
  CHECK(table.columns[1].type == ColumnType::string);
  CHECK(table.rows[1][1] == "[2, 3]");
  CHECK(table.rows[3][1] == "floor2-heavy");
  const std::string csv = sweep_csv(table);
  CHECK(csv.find("\n1,\"[2, 3]\",base,SI,") != std::string::npos);
  std::istringstream lines(csv);
  std::string header, first;
  std::getline(lines, header);
  std::getline(lines, first);
  std::vector<std::string> cells;
  REQUIRE(split_csv_line(first, &cells));
  CHECK(cells[1] == "[3, 3]");
  const std::size_t roof = column_of(table.columns, "A.roof_max");
  CHECK(table.rows[0][roof] != table.rows[2][roof]);
}

TEST_CASE("sweep expressions: variants change a link's type, add and remove links, each equal to --set by hand, bit for bit", "[sweep_expressions]") {
  const auto file = sweep_file("variants.toml", kOneDamper, R"(
[[variant]]
name = "none"
unset = ["link"]

[[variant]]
name = "friction"

[[variant]]
name = "viscous"
set = {"link.1.type" = "dashpot", "link.1.c" = 2.0e5, "link.1.alpha" = 0.4}

[[variant]]
name = "two-friction"
set = {"link.2.floors" = [2, 2], "link.2.type" = "friction", "link.2.slip_ratio" = 0.05, "link.2.of" = "B"}
)");
  const SweepSpec spec = load_sweep(file);
  REQUIRE(spec.axes.size() == 1);
  CHECK(spec.axes[0].name == "variant");
  CHECK(spec.link_columns == 2);  // the base's one, and the link.2 a variant adds
  REQUIRE(spec.runs() == 4);

  check_same_as_by_hand(spec, 0, kOneDamper, {}, {"link"});
  check_same_as_by_hand(spec, 1, kOneDamper, {});
  // The type change drops slip_ratio and of (the old type's keys), as editing the file would.
  const BuildingScene viscous =
      check_same_as_by_hand(spec, 2, kOneDamper, {"link.1.type=dashpot", "link.1.c=2.0e5", "link.1.alpha=0.4"});
  REQUIRE(viscous.structure.links.size() == 1);
  CHECK(viscous.structure.links[0].type == structure::LinkType::dashpot);
  CHECK(viscous.structure.links[0].c == 2.0e5);
  CHECK(viscous.structure.links[0].alpha == 0.4);
  const BuildingScene two = check_same_as_by_hand(
      spec, 3, kOneDamper, {"link.2.floors=[2,2]", "link.2.type=friction", "link.2.slip_ratio=0.05", "link.2.of=B"});
  REQUIRE(two.structure.links.size() == 2);
  CHECK(two.structure.links[1].slip_force == two.structure.links[0].slip_force);  // 5 % of B's weight, both

  // The scene file edited by hand (the link a dashpot) runs as the variant does.
  std::string text = slurp(kOneDamper);
  const std::string friction = "type = \"friction\"\nslip_ratio = 0.05\nof = \"B\"";
  REQUIRE(text.find(friction) != std::string::npos);
  text.replace(text.find(friction), friction.size(), "type = \"dashpot\"\nc = 2.0e5\nalpha = 0.4");
  const std::string record = "../../records/real/peer/";
  text.replace(text.find(record), record.size(), (kBuildings / record).lexically_normal().string());
  const BuildingScene edited = load_building_scene(write_temp("viscous-by-hand.toml", text), kShortSets);
  const Report by_hand = run(edited);
  const SweepRow row = run_sweep_point(spec, 2);
  CHECK(row.channels == building_channel_cells(ChannelCounts{2, 2, 1}, edited, by_hand));

  // Columns: link2's cells are empty where a run has one link, link1's where it has none.
  const SweepTable table = sweep_table(spec, run_sweep(spec, {}));
  const std::size_t force1 = column_of(table.columns, "link1.force_max"), force2 = column_of(table.columns, "link2.force_max");
  CHECK(table.rows[0][force1].empty());
  CHECK(table.rows[1][force2].empty());
  CHECK(table.rows[2][force2].empty());
  CHECK(!table.rows[3][force2].empty());
  CHECK(table.rows[2][column_of(table.columns, "link1.switches")] == "0");  // a dashpot does not switch
  std::size_t at = 0;
  for (const auto& r : table.rows) CHECK(sweep_row_problem(spec, SweepShard{}, r, &at) == "");  // the journal takes them
}

TEST_CASE("sweep expressions: [[variant]] tables are the axis of tables they abbreviate", "[sweep_expressions]") {
  const std::string edits = R"({name = "none", unset = ["link"]}, {name = "viscous", set = {"link.1.type" = "dashpot", "link.1.c" = 2.0e5}})";
  const SweepSpec axis = load_sweep(sweep_file("as-axis.toml", kOneDamper, "[[axis]]\nname = \"variant\"\nvalues = [" + edits + "]\n"));
  const SweepSpec variants = load_sweep(sweep_file("as-variants.toml", kOneDamper, R"(
[[variant]]
name = "none"
unset = ["link"]
[[variant]]
name = "viscous"
set = {"link.1.type" = "dashpot", "link.1.c" = 2.0e5}
[[axis]]
key = "link.1.floors"
values = [[3, 3], [2, 2]]
)"));
  REQUIRE(variants.axes.size() == 2);
  CHECK(variants.axes[0].name == "variant");  // the first axis: variants vary slowest
  CHECK(sweep_columns(variants)[1].name == "variant");
  for (std::size_t v = 0; v < 2; ++v) {
    CHECK(variants.axes[0].values[v].label == axis.axes[0].values[v].label);
    CHECK(variants.axes[0].values[v].overrides() == axis.axes[0].values[v].overrides());
    CHECK(variants.axes[0].values[v].unset == axis.axes[0].values[v].unset);
  }
  // An axis of its own name would be a second "variant" column.
  const auto clash = sweep_file("clash.toml", kOneDamper, "[[variant]]\nname = \"a\"\n[[axis]]\nname = \"variant\"\nkey = \"link.1.c\"\nvalues = [1.0]\n");
  try {
    load_sweep(clash);
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("axis name \"variant\" is already a column") != std::string::npos);
  }
}

TEST_CASE("sweep expressions: list values made in code are those the sweep file gives", "[sweep_expressions]") {
  // The library's API for other studies (adjoin optimize's placements): sweep_value.
  const SweepValue floors = sweep_value(std::vector<SweepScalar>{std::int64_t{2}, std::int64_t{3}});
  CHECK(floors.text == "[2, 3]");
  CHECK(sweep_value(std::vector<SweepScalar>{2.0e5, std::string("B"), true}).text == "[2e+05, \"B\", true]");  // a TOML float
  CHECK(sweep_value(2.0).text == "2.0");
  SweepSpec spec = load_sweep(sweep_file("in-code.toml", kOneDamper, "[[axis]]\nkey = \"link.1.floors\"\nvalues = [[2, 3]]\n"));
  CHECK(spec.axes[0].values[0].set[0].second.text == floors.text);
  CHECK(spec.axes[0].values[0].set[0].second.value == floors.value);
  // Changed in code, the run follows the new value.
  spec.axes[0].values[0].set[0].second = sweep_value(std::vector<SweepScalar>{std::int64_t{1}, std::int64_t{1}});
  CHECK(sweep_scene(spec, 0).structure.links[0].floor_b == 1);
}

TEST_CASE("sweep expressions: a sweep of list values and variants resumes from its journal to the same table", "[sweep_expressions][cli]") {
  const auto file = sweep_file("resume.toml", kOneDamper, R"(
[[variant]]
name = "friction"
[[variant]]
name = "viscous"
set = {"link.1.type" = "dashpot", "link.1.c" = 2.0e5}
[[axis]]
key = "link.1.floors"
values = [[3, 3], [2, 2]]
)");
  const std::filesystem::path dir = std::filesystem::path(ADJOIN_TEST_TMP) / "expr-cli";
  std::filesystem::remove_all(dir);
  const auto whole = run_cli("sweep " + file.string() + " --out " + (dir / "whole").string() + " --quiet --jobs 2");
  REQUIRE(whole.status == 0);
  const SweepSpec spec = load_sweep(file);
  std::filesystem::create_directories(dir / "resumed");
  {
    std::ofstream journal(dir / "resumed" / "sweep.partial.csv", std::ios::binary);
    journal << sweep_journal_preamble(spec, SweepShard{});
    for (std::size_t i : {1u, 2u}) journal << csv_line(sweep_cells(spec, run_sweep_point(spec, i))) << "\n";
  }
  const auto resumed = run_cli("sweep " + file.string() + " --out " + (dir / "resumed").string() + " --jobs 1");
  REQUIRE(resumed.status == 0);
  CHECK(resumed.err.find("resuming: 2 runs") != std::string::npos);
  // Every cell but wall_seconds the same.
  const auto without_wall = [](const std::string& text) { return csv_rows(text, true); };
  const auto expected = without_wall(slurp(dir / "whole" / "sweep.csv"));
  REQUIRE(expected.size() == 5);
  CHECK(expected[3][1] == "viscous");
  CHECK(expected[3][2] == "[3, 3]");
  CHECK(without_wall(slurp(dir / "resumed" / "sweep.csv")) == expected);
}

TEST_CASE("sweep expressions: the damper-variants example, a row against adjoin run --set by hand", "[sweep_expressions]") {
  const auto example = std::filesystem::path(ADJOIN_SOURCE_DIR) / "examples" / "sweeps" / "two-frames-damper-variants.toml";
  const SweepSpec spec = load_sweep(example);
  REQUIRE(spec.runs() == 12);
  REQUIRE(spec.axes.size() == 1);
  CHECK(spec.axes[0].name == "variant");
  CHECK(spec.link_columns == 2);
  std::vector<std::string> labels;
  for (const auto& v : spec.axes[0].values) labels.push_back(v.label);
  CHECK(labels == std::vector<std::string>{"none", "friction", "viscous", "two-friction"});
  // Run 6: the viscous variant under the base's record (the whole record: the file's own run).
  REQUIRE(spec.describe(6) == "variant=viscous, motion=newhall");
  const SweepRow row = run_sweep_point(spec, 6);
  REQUIRE(row.error.empty());
  const BuildingScene scene = load_building_scene(
      kOneDamper, {"output.timeseries=false", "link.1.type=dashpot", "link.1.c=1.5e5", "link.1.alpha=0.4"});
  CHECK(row.channels == building_channel_cells(ChannelCounts{2, 2, 1}, scene, run(scene)));
  // The two-friction variant: two links of half the slip force each.
  const RunSpec two = sweep_scene(spec, 9);
  REQUIRE(two.structure.links.size() == 2);
  CHECK(two.structure.links[1].floor_a == 2);
  CHECK(two.structure.links[0].slip_force == two.structure.links[1].slip_force);
  CHECK(two.structure.links[0].slip_force * 2.0 == Approx(sweep_scene(spec, 3).structure.links[0].slip_force).epsilon(1e-15));
}

TEST_CASE("sweep expressions: adjoin sweep of variants and adjoin run --set of the same edits write the same numbers", "[sweep_expressions][cli]") {
  // The commands themselves: sweep.csv's cells against summary.json's values, as text (both
  // write shortest round-trip numbers, so equal text is equal bits).
  const auto file = sweep_file("cli-variants.toml", kOneDamper, R"(
[[variant]]
name = "viscous"
set = {"link.1.type" = "dashpot", "link.1.c" = 1.5e5, "link.1.alpha" = 0.4}
[[variant]]
name = "two-friction"
[variant.set]
"link.1.floors" = [3, 3]
"link.2.floors" = [2, 2]
"link.2.type" = "friction"
"link.2.slip_force" = 4.0e4
)");
  const std::filesystem::path dir = std::filesystem::path(ADJOIN_TEST_TMP) / "expr-cli-run";
  std::filesystem::remove_all(dir);
  REQUIRE(run_cli("sweep " + file.string() + " --out " + (dir / "sweep").string() + " --quiet").status == 0);
  std::istringstream csv(slurp(dir / "sweep" / "sweep.csv"));
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(csv, line);) {
    rows.emplace_back();
    REQUIRE(split_csv_line(line, &rows.back()));
  }
  REQUIRE(rows.size() == 3);
  const auto cell = [&](std::size_t row, const std::string& column) {
    const auto it = std::find(rows[0].begin(), rows[0].end(), column);
    REQUIRE(it != rows[0].end());
    return rows[row][static_cast<std::size_t>(it - rows[0].begin())];
  };
  const std::string base = "run " + kOneDamper.string() + " --quiet --set solver.t_end=3.0 --set solver.h=0.004 --set output.timeseries=false";
  const std::vector<std::string> by_hand = {
      " --set link.1.type=dashpot --set link.1.c=1.5e5 --set link.1.alpha=0.4",
      " --set 'link.1.floors=[3, 3]' --set 'link.2.floors=[2,2]' --set link.2.type=friction --set link.2.slip_force=4.0e4"};
  for (std::size_t v = 0; v < by_hand.size(); ++v) {
    const std::filesystem::path out = dir / ("run" + std::to_string(v));
    const auto r = run_cli(base + by_hand[v] + " --out " + out.string());
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
    const auto text = [](const nlohmann::json& number) { return sweep_number_cell(number.get<double>()); };
    CHECK(cell(v + 1, "A.roof_max") == text(summary["peaks"]["A.x5"]["max_abs"]));
    CHECK(cell(v + 1, "link1.force_max") == text(summary["links"][0]["force_max"]));
    CHECK(cell(v + 1, "link1.stroke_max") == text(summary["links"][0]["stroke_max"]));
    CHECK(cell(v + 1, "energy_input") == text(summary["energy"]["input"]));
    CHECK(summary["links"].size() == v + 1);
    if (v == 1) CHECK(cell(v + 1, "link2.force_max") == text(summary["links"][1]["force_max"]));
  }
  CHECK(cell(1, "link2.force_max").empty());
}

TEST_CASE("sweep expressions: a list value in a two-block sweep is the --set of the same list", "[sweep_expressions]") {
  // A two-block scene reads the edits as typed values (io/sweep_scenes.cpp): a list as a TOML array.
  const auto strong = std::filesystem::path(ADJOIN_SOURCE_DIR) / "records" / "scenes" / "paper-strong.toml";
  const SweepSpec spec = load_sweep(sweep_file("two-block-list.toml", strong, R"(
[[axis]]
key = "output.spectra.damping"
values = [[0.02, 0.05], [0.1]]
[[axis]]
name = "signals"
values = [{name = "ground-only", set = {"output.spectra.signals" = ["ground"]}}]
)"));
  REQUIRE(spec.runs() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const RunSpec swept = sweep_scene(spec, i);
    const RunSpec by_hand = load_scene(strong, {"solver.t_end=3.0", "solver.h=0.004", "output.timeseries=false",
                                                i == 0 ? "output.spectra.damping=[0.02,0.05]" : "output.spectra.damping=[0.1]",
                                                "output.spectra.signals=[\"ground\"]"});
    REQUIRE(swept.output.spectra);
    REQUIRE(by_hand.output.spectra);
    CHECK(swept.output.spectra->damping == by_hand.output.spectra->damping);
    CHECK(swept.output.spectra->signals == by_hand.output.spectra->signals);
  }
  CHECK(sweep_scene(spec, 0).output.spectra->damping == std::vector<double>{0.02, 0.05});
  CHECK(sweep_scene(spec, 1).output.spectra->signals == std::vector<std::string>{"ground"});
}
