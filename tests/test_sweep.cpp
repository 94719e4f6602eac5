// Sweeps (study/sweep.hpp, adjoin sweep / sweep merge) and demand models (study/demand.hpp,
// adjoin demand).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/io/file_name.hpp"
#include "adjoin/io/folder_lock.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/post/intensity.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/study/demand.hpp"
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

const std::string kStrong = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml";
const std::filesystem::path kRecords = ADJOIN_REAL_RECORDS;

std::string qpath(const std::filesystem::path& p) { return "\"" + p.string() + "\""; }

// A sweep file in its own scratch folder (its relative paths resolve there).
std::filesystem::path sweep_file(const std::string& name, const std::string& body) {
  return write_temp(name, "base = " + qpath(kStrong) + "\n" + body);
}


// Every cell except the wall_seconds column.
std::vector<std::vector<std::string>> without_wall_time(std::vector<std::vector<std::string>> rows) {
  REQUIRE(!rows.empty());
  const auto it = std::find(rows[0].begin(), rows[0].end(), "wall_seconds");
  REQUIRE(it != rows[0].end());
  const auto column = static_cast<std::size_t>(it - rows[0].begin());
  for (auto& r : rows) r.erase(r.begin() + static_cast<std::ptrdiff_t>(column));
  return rows;
}

std::size_t column_of(const SweepSpec& spec, const std::string& name) {
  const auto columns = sweep_columns(spec);
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i].name == name) return i;
  FAIL("no column " << name);
  return 0;
}

}  // namespace

TEST_CASE("sweep files: ranges, values, order of the runs", "[sweep]") {
  const auto file = sweep_file("order.toml", R"(
set = {"solver.h" = 0.01}
[[axis]]
key = "model.mu"
from = 0.1
to = 0.4
n = 4
[[axis]]
key = "model.eps"
from = 0.5
to = 8.0
n = 5
spacing = "log"
[[motion]]
name = "a"
[[motion]]
name = "b"
set = {"ground.u0" = 0.5}
)");
  const SweepSpec spec = load_sweep(file);
  REQUIRE(spec.runs() == 4 * 5 * 2);
  REQUIRE(spec.axes.size() == 2);
  CHECK(spec.axes[0].values[0].number.value() == 0.1);
  CHECK(spec.axes[0].values[1].number.value() == Approx(0.2).epsilon(1e-15));
  CHECK(spec.axes[0].values[3].number.value() == 0.4);
  // log spacing: 0.5, 1, 2, 4, 8
  for (std::size_t i = 0; i < 5; ++i) CHECK(spec.axes[1].values[i].number.value() == Approx(0.5 * std::pow(2.0, i)).epsilon(1e-14));
  CHECK(spec.axes[1].values[4].label == "8");
  // The first axis varies slowest, the motion fastest.
  CHECK(spec.coordinates(0) == std::vector<std::size_t>{0, 0, 0});
  CHECK(spec.coordinates(1) == std::vector<std::size_t>{0, 0, 1});
  CHECK(spec.coordinates(2) == std::vector<std::size_t>{0, 1, 0});
  CHECK(spec.coordinates(10) == std::vector<std::size_t>{1, 0, 0});
  CHECK(spec.coordinates(39) == std::vector<std::size_t>{3, 4, 1});
  CHECK(spec.describe(13) == "model.mu=0.2, model.eps=1, motion=b");
  const Scene scene = sweep_scene(spec, 13);
  CHECK(two_block_model(scene).mu == Approx(0.2).epsilon(1e-15));
  CHECK(two_block_model(scene).eps == Approx(1.0).epsilon(1e-14));
  CHECK(scene.solver.h == 0.01);
  CHECK(scene.ground->describe().find("u0=0.5") != std::string::npos);
}

TEST_CASE("sweep files: bad input names the file, line and key", "[sweep]") {
  auto message = [](const std::string& body) {
    try {
      load_sweep(sweep_file("bad.toml", body));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message("[[axis]]\nkey = \"model.mu\"\nfrom = 0\nto = 1\n"), Catch::Contains("bad.toml:2:") && Catch::Contains("missing n"));
  CHECK_THAT(message("[[axis]]\nkey = \"model.mu\"\nfrom = 0\nto = 1\nn = 3\nspacing = \"log\"\n"),
             Catch::Contains("bad.toml:4:") && Catch::Contains("from > 0"));
  CHECK_THAT(message("[[axis]]\nkey = \"model.mu\"\nvalues = [0.1]\nfrom = 0\n"), Catch::Contains("either values"));
  CHECK_THAT(message("[[axis]]\nkye = \"model.mu\"\nvalues = [1]\n"), Catch::Contains("bad.toml:3:") && Catch::Contains("did you mean key"));
  CHECK_THAT(message("[[motion]]\nset = {}\n"), Catch::Contains("bad.toml:2:") && Catch::Contains("name"));
  CHECK_THAT(message("[output]\nim_periods = [0.0]\n"), Catch::Contains("bad.toml:3:") && Catch::Contains("positive"));
  CHECK_THAT(message("[[axis]]\nkey = \"model.mu\"\nvalues = [0.1, 0.1]\n"), Catch::Contains("twice"));
  // An unknown scene key in an axis: the run's scene fails, and the message points at the axis.
  const SweepSpec spec = load_sweep(sweep_file("unknown.toml", "\n[[axis]]\nkey = \"model.muu\"\nvalues = [0.1, 0.2]\n"));
  try {
    run_sweep(spec, {});
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::Contains("unknown.toml:5: run 0 (model.muu=0.1, motion=base)") &&
                             Catch::Contains("model.muu") && Catch::Contains("did you mean model.mu"));
  }
  // A key an axis value unsets but the scene needs: the message names the axis value's line
  // and the base scene's own line for the table that lacks it ([model.rod2], line 16 of the
  // paper's strong scene), not a line of some re-written copy.
  const SweepSpec removed = load_sweep(sweep_file("unset.toml", R"(
[[axis]]
name = "rod2"
values = [{name = "plain"},
          {name = "no-order", unset = ["model.rod2.order"]}]
)"));
  int rod2_line = 0, line_number = 0;
  std::istringstream base(slurp(kStrong));
  for (std::string line; std::getline(base, line);) {
    ++line_number;
    if (line == "[model.rod2]") rod2_line = line_number;
  }
  REQUIRE(rod2_line > 0);
  try {
    sweep_scene(removed, 1);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::Contains("unset.toml:6: run 1 (rod2=no-order, motion=base)") &&
                             Catch::Contains("paper-strong.toml:" + std::to_string(rod2_line) + ": missing key model.rod2.order"));
  }
}

TEST_CASE("a sweep row is what `adjoin run` reports (paper's strong scene)", "[sweep]") {
  // README: |x1| 1.16654, |x2| 0.743036, min gap 1.44812, energy input 7.21543, friction 1.23778,
  // 8 phase intervals (3 stick, 5 slip).
  const SweepSpec spec = load_sweep(sweep_file("strong.toml", "[[axis]]\nkey = \"model.mu\"\nvalues = [0.3]\n"));
  const auto rows = run_sweep(spec, {});
  REQUIRE(rows.size() == 1);
  const SweepRow& r = rows[0];
  CHECK(r.error.empty());
  CHECK(r.units == "dimensionless");
  // The row's cells by column name (study/sweep_columns.hpp: SPEC §3's names).
  const auto columns = channel_columns(spec);
  REQUIRE(r.channels.size() == columns.size());
  const auto cell = [&](const std::string& name) {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i].name == name) return r.channels[i];
    FAIL("no column " << name);
    return std::string();
  };
  const auto number = [&](const std::string& name) { return std::stod(cell(name)); };
  CHECK(number("x1") == Approx(1.16654).epsilon(5e-6));
  CHECK(number("x2") == Approx(0.743036).epsilon(5e-6));
  CHECK(number("min_gap") == Approx(1.44812).epsilon(5e-6));
  CHECK(cell("contact") == "false");
  CHECK(cell("contact.impacts").empty());  // no contact law
  CHECK(number("energy_input") == Approx(7.21543).epsilon(5e-6));
  CHECK(number("share_friction") == Approx(1.23778 / 7.21543).epsilon(2e-5));
  CHECK(number("share_rod1") + number("share_rod2") + number("share_friction") + number("share_residual") ==
        Approx(1.0 - 7.95554e-07 / 7.21543).epsilon(1e-6));
  CHECK(cell("stick_intervals") == "3");
  CHECK(cell("slip_intervals") == "5");
  CHECK(cell("switches") == "7");
  // a_g = u0 Omega^2 e^{-kt} sin(Omega t): the peak of the sampled forcing, below u0 Omega^2 = 3.375.
  CHECK(r.pga_g > 2.0);
  CHECK(r.pga_g < 3.375);
}

TEST_CASE("sweeps: the table does not depend on the number of threads", "[sweep]") {
  const SweepSpec spec = load_sweep(sweep_file("threads.toml", R"(
set = {"solver.h" = 0.01, "solver.t_end" = 10.0, "solver.history" = "fft"}
[[axis]]
key = "model.mu"
from = 0.0
to = 0.8
n = 5
[[motion]]
name = "strong"
[[motion]]
name = "weak"
set = {"ground.u0" = 0.05, "ground.omega" = 3.5, "ground.k" = 0.3}
)"));
  SweepOptions one, three;
  one.jobs = 1;
  three.jobs = 3;
  std::vector<std::size_t> seen;
  three.on_row = [&](const SweepRow& row) { seen.push_back(row.index); };
  const auto a = without_wall_time(csv_rows(sweep_csv(sweep_table(spec, run_sweep(spec, one)))));
  const auto b = without_wall_time(csv_rows(sweep_csv(sweep_table(spec, run_sweep(spec, three)))));
  CHECK(a == b);
  REQUIRE(a.size() == 11);
  CHECK(std::set<std::size_t>(seen.begin(), seen.end()).size() == 10);
  // Motion is the fastest coordinate; the weak motion sticks throughout: no stroke, no friction.
  const auto mu = column_of(spec, "model.mu"), motion = column_of(spec, "motion"), drift = column_of(spec, "drift"),
             friction = column_of(spec, "share_friction");
  CHECK(a[4][mu] == "0.2");
  CHECK(a[4][motion] == "weak");
  CHECK(a[6][mu] == "0.4");
  CHECK(a[6][drift] == "0");
  CHECK(a[6][friction] == "0");
  CHECK(a[8][mu] == "0.6");  // ranges are rounded to 15 digits: 0.6, not 0.6000000000000001
  CHECK(std::stod(a[4][drift]) > 0.0);  // mu = 0.2 lets the weak motion slip a little
  CHECK(a[1][friction] == "0");  // mu = 0: no damper
  CHECK(std::stod(a[3][friction]) > 0.05);
  // A subset of runs.
  SweepOptions some;
  some.indices = {7, 2};
  const auto rows = run_sweep(spec, some);
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].index == 2);
  CHECK(rows[1].index == 7);
}

TEST_CASE("sweeps: axis values with their own edits, elastic rods drop their fractional keys", "[sweep]") {
  const SweepSpec spec = load_sweep(sweep_file("rods.toml", R"(
set = {"solver.h" = 0.01, "solver.t_end" = 10.0, "model.mu" = 0.0}
[[axis]]
key = "model.rod1.elastic"
values = [false, true]
[[axis]]
name = "rod2"
values = [{name = "fractional"}, {name = "elastic", set = {"model.rod2.elastic" = true}},
          {name = "explicit", set = {"model.rod2.elastic" = true}, unset = ["model.rod2.order", "model.rod2.tau_x", "model.rod2.tau_f"]}]
)"));
  REQUIRE(spec.runs() == 6);
  CHECK(sweep_columns(spec)[1].type == ColumnType::string);
  CHECK(two_block_model(sweep_scene(spec, 0)).rod1.elastic == false);
  CHECK(two_block_model(sweep_scene(spec, 4)).rod1.elastic == true);
  CHECK(two_block_model(sweep_scene(spec, 4)).rod2.elastic == true);
  const auto rows = run_sweep(spec, {});
  const auto value = [&](std::size_t i, const std::string& column) {
    return std::stod(sweep_cells(spec, rows[i])[column_of(spec, column)]);
  };
  // Both rods elastic, no damper, eps rho = 1: equal natural frequencies and the same forcing,
  // so the blocks move together exactly.
  for (std::size_t i : {4, 5}) {
    CHECK(rows[i].error.empty());
    CHECK(value(i, "drift") == 0.0);
    CHECK(value(i, "x1") == value(i, "x2"));
  }
  CHECK(value(4, "x1") == value(5, "x1"));
  CHECK(value(0, "drift") > 0.1);
}

TEST_CASE("sweeps: a numerical failure is a row's error, the others go on", "[sweep]") {
  // The paper scheme is conditionally stable; h = 1.5 is far beyond its bound.
  const SweepSpec spec = load_sweep(sweep_file("unstable.toml", "[[axis]]\nkey = \"solver.h\"\nvalues = [0.01, 1.5]\n"));
  const auto rows = run_sweep(spec, {});
  CHECK(rows[0].error.empty());
  CHECK_THAT(rows[1].error, Catch::Contains("stab") || Catch::Contains("step"));
  const auto cells = sweep_cells(spec, rows[1]);
  CHECK(cells[column_of(spec, "x1")].empty());
  CHECK(cells[column_of(spec, "switches")].empty());
  CHECK(cells[column_of(spec, "error")] == rows[1].error);
  // Such a row is a valid journal row (its empty cells are what a failed run leaves), and a row
  // that says it succeeded may not leave them empty.
  std::size_t index = 0;
  CHECK(sweep_row_problem(spec, SweepShard{}, cells, &index).empty());
  CHECK(index == 1);
  auto claimed = cells;
  claimed[column_of(spec, "error")] = "";
  CHECK_THAT(sweep_row_problem(spec, SweepShard{}, claimed, &index), Catch::Contains("contact"));
}

TEST_CASE("sweeps: intensity measures of a record as the solver saw it", "[sweep][records]") {
  const auto record_file = kRecords / "two-column" / "elCentro.txt";  // in the repository
  REQUIRE(std::filesystem::exists(record_file));
  // Dimensionless scene, time unit 1 s; h = 0.01 s puts a grid point on every record sample,
  // so the solver's piecewise-linear forcing is the record's own.
  const SweepSpec spec = load_sweep(sweep_file("record.toml", R"(
set = {"solver.h" = 0.01, "solver.t_end" = 32.0, "solver.scheme" = "implicit", "solver.history" = "fft"}
[output]
im_periods = [0.5, 1.0]
[[motion]]
name = "elcentro"
set = {"ground.source" = "record", "ground.file" = ")" + record_file.string() + R"(", "ground.units" = "g"}
[[motion]]
name = "elcentro-0.5g"
set = {"ground.source" = "record", "ground.file" = ")" + record_file.string() + R"(", "ground.units" = "g", "ground.scale_pga" = 0.5}
)"));
  const auto rows = run_sweep(spec, {});
  RecordFormat format;
  format.units = AccelUnit::g;
  const Record record = read_record(record_file, format);
  const IntensityMeasures im = intensity_measures(record);
  REQUIRE(rows[0].error.empty());
  CHECK(rows[0].pga_g == Approx(im.pga).epsilon(1e-12));
  CHECK(rows[1].pga_g == Approx(0.5).epsilon(1e-12));
  for (std::size_t k = 0; k < 2; ++k) {
    const double period = spec.im_periods[k];
    const double sa = spectral_values(record.dt, record.accel, period, 0.05).sa;
    CHECK(rows[0].sa_g[k] == Approx(sa).epsilon(1e-6));
    CHECK(rows[1].sa_g[k] == Approx(sa * 0.5 / im.pga).epsilon(1e-6));
  }
  const auto columns = sweep_columns(spec);
  CHECK(columns[columns.size() - 4].name == "sa_0.5");
  CHECK(columns[columns.size() - 3].name == "sa_1");
}

TEST_CASE("adjoin sweep: files, resuming from the journal, shards merged like a serial run", "[sweep][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / ("sweep_cli_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto file = sweep_file("cli.toml", R"(
set = {"solver.h" = 0.01, "solver.t_end" = 8.0}
[[axis]]
key = "model.mu"
values = [0.0, 0.3, 0.6]
[[motion]]
name = "strong"
[[motion]]
name = "weak"
set = {"ground.u0" = 0.05, "ground.omega" = 3.5, "ground.k" = 0.3}
[output]
im_periods = [1.0]
)");
  auto r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "serial") + " --jobs 2");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("6 runs"));
  CHECK(r.err.empty());  // no progress bar: stderr is not a terminal
  const std::string serial = slurp(dir / "serial" / "sweep.csv");
  const auto serial_rows = csv_rows(serial);
  REQUIRE(serial_rows.size() == 7);
  CHECK(serial_rows[0][0] == "index");
  CHECK_FALSE(std::filesystem::exists(dir / "serial" / "sweep.partial.csv"));
  // The JSON holds the same rows.
  const SweepTableFile json = read_sweep_json(dir / "serial" / "sweep.json");
  CHECK(json.runs == 6);
  CHECK(sweep_csv(json.table) == serial);

  SECTION("resume: finished runs in the journal are not run again; a torn line is dropped") {
    const SweepSpec spec = load_sweep(file);
    const auto wall = column_of(spec, "wall_seconds");
    std::filesystem::create_directories(dir / "resume");
    {
      std::ofstream journal(dir / "resume" / "sweep.partial.csv", std::ios::binary);
      journal << sweep_journal_preamble(spec, SweepShard{});
      for (std::size_t i : {4, 1}) {
        auto cells = serial_rows[i + 1];
        cells[wall] = "123";
        journal << csv_line(cells) << "\n";
      }
      journal << "5,0.6,weak,dimensionless,0.1";  // torn: the run was interrupted while writing
    }
    r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "resume") + " --quiet");
    REQUIRE(r.status == 0);
    CHECK(r.out.empty());
    const auto resumed = csv_rows(slurp(dir / "resume" / "sweep.csv"));
    REQUIRE(resumed.size() == 7);
    for (std::size_t i = 0; i < 6; ++i) CHECK((resumed[i + 1][wall] == "123") == (i == 1 || i == 4));
    CHECK(without_wall_time(resumed) == without_wall_time(serial_rows));
    CHECK_FALSE(std::filesystem::exists(dir / "resume" / "sweep.partial.csv"));
  }

  SECTION("shards 0/2 and 1/2 merged equal the serial table but for wall times") {
    for (const char* shard : {"0/2", "1/2"}) {
      r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "shards") + " -q --jobs 1 --shard " + shard);
      REQUIRE(r.status == 0);
    }
    const auto shard0 = csv_rows(slurp(dir / "shards" / "sweep.shard-0-of-2.csv"));
    REQUIRE(shard0.size() == 4);
    CHECK(shard0[1][0] == "0");
    CHECK(shard0[2][0] == "2");
    CHECK(shard0[3][0] == "4");
    r = run_cli("sweep merge " + qpath(dir / "shards") + " --out " + qpath(dir / "merged.csv"));
    REQUIRE(r.status == 0);
    CHECK(without_wall_time(csv_rows(slurp(dir / "merged.csv"))) == without_wall_time(serial_rows));
    CHECK(read_sweep_json(dir / "merged.json").shard.whole());
    // The same from the files, with the other spelling.
    r = run_cli("sweep-merge " + qpath(dir / "shards" / "sweep.shard-1-of-2.csv") + " " +
                qpath(dir / "shards" / "sweep.shard-0-of-2.json") + " --out " + qpath(dir / "merged2"));
    REQUIRE(r.status == 0);
    CHECK(slurp(dir / "merged2" / "sweep.csv") == slurp(dir / "merged.csv"));
    // A missing shard is named.
    r = run_cli("sweep merge " + qpath(dir / "shards" / "sweep.shard-0-of-2.json") + " --out " + qpath(dir / "bad.csv"));
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::StartsWith("error:") && Catch::Contains("3 of 6 runs") && Catch::Contains("runs 1, 3, 5"));
  }

  SECTION("bad input: exit 2 with the file and what is expected") {
    r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "x") + " --shard 2/2");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::StartsWith("error: --shard 2/2") && Catch::Contains("0 <= I < N"));
    const auto bad = write_temp("badbase.toml", "base = \"nowhere.toml\"\n");
    r = run_cli("sweep " + qpath(bad) + " --out " + qpath(dir / "x"));
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::StartsWith("error:") && Catch::Contains("nowhere.toml") && Catch::Contains("badbase.toml:1"));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("demand model: exact recovery of a and b, dispersion and R^2", "[demand]") {
  const double a = -0.7, b = 1.3;
  std::vector<double> im, d;
  for (double x : {0.05, 0.1, 0.2, 0.4, 0.8, 1.6}) {
    im.push_back(x);
    d.push_back(std::exp(a + b * std::log(x)));
  }
  DemandFit fit = fit_demand_model(im, d);
  CHECK(fit.n == 6);
  CHECK(fit.a == Approx(a).epsilon(1e-12));
  CHECK(fit.b == Approx(b).epsilon(1e-12));
  CHECK(fit.beta == Approx(0.0).margin(1e-12));
  CHECK(fit.r2 == Approx(1.0).epsilon(1e-12));

  // Residuals +-e at each IM: orthogonal to (1, ln IM), so the fit is unchanged, the residual
  // sum of squares is n e^2 and beta = e sqrt(n / (n - 2)).
  const double e = 0.3;
  std::vector<double> im2, d2;
  for (double x : {0.05, 0.1, 0.2, 0.4, 0.8}) {
    for (double s : {-1.0, 1.0}) {
      im2.push_back(x);
      d2.push_back(std::exp(a + b * std::log(x) + s * e));
    }
  }
  fit = fit_demand_model(im2, d2);
  CHECK(fit.a == Approx(a).epsilon(1e-12));
  CHECK(fit.b == Approx(b).epsilon(1e-12));
  CHECK(fit.beta == Approx(e * std::sqrt(10.0 / 8.0)).epsilon(1e-12));
  double mean = 0, total = 0;
  for (double v : d2) mean += std::log(v) / 10.0;
  for (double v : d2) total += (std::log(v) - mean) * (std::log(v) - mean);
  CHECK(fit.r2 == Approx(1.0 - 10.0 * e * e / total).epsilon(1e-12));

  CHECK_THROWS_WITH(fit_demand_model(std::vector<double>{1, 1, 1}, std::vector<double>{1, 2, 3}), Catch::Contains("distinct IM"));
  CHECK_THROWS_WITH(fit_demand_model(std::vector<double>{1, 2}, std::vector<double>{1, 2}), Catch::Contains("at least 3"));
  CHECK_THROWS_WITH(fit_demand_model(std::vector<double>{1, 2, 0}, std::vector<double>{1, 2, 3}), Catch::Contains("positive"));
}

TEST_CASE("adjoin demand on a real sweep over recorded motions", "[demand][records][cli]") {
  const auto elcentro = kRecords / "two-column" / "elCentro.txt", kobe = kRecords / "two-column" / "Kobe.dat";
  REQUIRE(std::filesystem::exists(elcentro));
  REQUIRE(std::filesystem::exists(kobe));
  std::string motions;
  for (double pga : {0.1, 0.2, 0.4})
    motions += "[[motion]]\nname = \"elcentro-" + std::to_string(pga).substr(0, 3) + "\"\nset = {\"ground.source\" = \"record\", \"ground.file\" = " +
               qpath(elcentro) + ", \"ground.units\" = \"g\", \"ground.scale_pga\" = " + std::to_string(pga) + "}\n";
  for (double pga : {0.15, 0.3})
    motions += "[[motion]]\nname = \"kobe-" + std::to_string(pga).substr(0, 4) + "\"\nset = {\"ground.source\" = \"record\", \"ground.file\" = " +
               qpath(kobe) + ", \"ground.units\" = \"m/s2\", \"ground.scale_pga\" = " + std::to_string(pga) + "}\n";
  const auto file = sweep_file("demand.toml", R"(
set = {"solver.h" = 0.01, "solver.t_end" = 25.0, "solver.scheme" = "implicit", "solver.history" = "fft", "model.mu" = 0.05}
[output]
im_periods = [1.0]
)" + motions);
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / ("sweep_demand_" + std::to_string(::getpid()));
  auto r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir) + " -q");
  REQUIRE(r.status == 0);
  const SweepCsvTable table = read_sweep_csv(dir / "sweep.csv");
  REQUIRE(table.rows.size() == 5);
  std::vector<double> pga, sa, x1;
  for (const auto& row : table.rows) {
    CHECK(row[table.column("error")].empty());
    pga.push_back(std::stod(row[table.column("pga_g")]));
    sa.push_back(std::stod(row[table.column("sa_1")]));
    x1.push_back(std::stod(row[table.column("x1")]));
  }
  // The motions' PGA is what they were scaled to (every record sample is on the grid).
  CHECK(pga[0] == Approx(0.1).epsilon(1e-12));
  CHECK(pga[2] == Approx(0.4).epsilon(1e-12));
  CHECK(pga[4] == Approx(0.3).epsilon(1e-12));
  // Sa of a scaled record scales with it.
  CHECK(sa[2] / sa[0] == Approx(4.0).epsilon(1e-9));

  // The fit equals the closed-form least squares on the logs of the table's columns.
  const auto fits = fit_sweep_demand(table, "x1", "sa:1");
  REQUIRE(fits.size() == 1);
  const std::size_t n = 5;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) { mx += std::log(sa[i]) / n; my += std::log(x1[i]) / n; }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (std::log(sa[i]) - mx) * (std::log(x1[i]) - my);
    sxx += (std::log(sa[i]) - mx) * (std::log(sa[i]) - mx);
  }
  const double b = sxy / sxx, a = my - b * mx;
  double ssr = 0;
  for (std::size_t i = 0; i < n; ++i) ssr += std::pow(std::log(x1[i]) - a - b * std::log(sa[i]), 2);
  CHECK(fits[0].fit.a == Approx(a).epsilon(1e-10));
  CHECK(fits[0].fit.b == Approx(b).epsilon(1e-10));
  CHECK(fits[0].fit.beta == Approx(std::sqrt(ssr / 3.0)).epsilon(1e-9));
  // A nearly elastic structure (small slip force): its displacement follows the shaking.
  CHECK(fits[0].fit.b > 0.5);
  CHECK(fits[0].fit.b < 1.5);

  r = run_cli("demand " + qpath(dir / "sweep.csv") + " --response x1 --im sa:1.0 --out " + qpath(dir / "fit.csv"));
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("ln(x1) = a + b ln(sa_1)"));
  const auto fit_rows = csv_rows(slurp(dir / "fit.csv"));
  REQUIRE(fit_rows.size() == 2);
  CHECK(std::stod(fit_rows[1][5]) == Approx(b).epsilon(1e-8));
  r = run_cli("demand " + qpath(dir / "sweep.csv") + " --response x1 --im sa:2");
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("sweep.csv:1: no column sa_2") && Catch::Contains("sa_1"));
  r = run_cli("demand " + qpath(dir / "sweep.csv") + " --response stroke");
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("no column \"stroke\"") && Catch::Contains("drift"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("scene and sweep names are plain file names (they name the output folder)", "[sweep][names]") {
  CHECK(plain_name_problem("slip-force_2 v1.5").empty());
  CHECK(plain_name_problem("élan").empty());  // UTF-8 is a file name like any other
  CHECK(plain_name_problem(std::string(kMaxPlainNameBytes, 'a')).empty());
  struct Named {
    std::string toml, raw;  // as written in the sweep file, and the name it means
  };
  const std::string long_name(kMaxPlainNameBytes + 1, 'a');
  for (const Named& bad : std::vector<Named>{{"../../x", "../../x"}, {"/tmp/x", "/tmp/x"}, {"a/b", "a/b"},
                                             {"a\\\\b", "a\\b"}, {"", ""}, {".", "."}, {"..", ".."},
                                             {"a\\u0001b", "a\x01" "b"}, {"a\\u007f", "a\x7f"}, {long_name, long_name}}) {
    INFO(bad.toml);
    CHECK(!plain_name_problem(bad.raw).empty());
    // The sweep file's name, with its file, line and key.
    CHECK_THROWS_WITH(load_sweep(sweep_file("named.toml", "name = \"" + bad.toml + "\"\n")),
                      Catch::Contains("named.toml:2: name = ") && Catch::Contains("plain file name"));
  }
  // The `\` in a TOML basic string is an escape: written as "a\\b" it is one backslash.
  CHECK_THROWS_WITH(load_sweep(sweep_file("bs.toml", "name = \"a\\\\b\"\n")), Catch::Contains("path separator"));
  // A scene's name, in the file and by --set.
  std::string text = slurp(kStrong);
  const auto at = text.find("name = \"paper-strong\"");
  REQUIRE(at != std::string::npos);
  text.replace(at, std::string("name = \"paper-strong\"").size(), "name = \"../../escaped\"");
  const auto scene = write_temp("named-scene.toml", text);
  CHECK_THROWS_WITH(load_scene(scene), Catch::Contains("named-scene.toml:2: name = \"../../escaped\"") &&
                                           Catch::Contains("path separator"));
  CHECK_THROWS_WITH(load_scene(kStrong, {"name=\"/tmp/x\""}), Catch::Contains("--set name=\"/tmp/x\"") &&
                                                                    Catch::Contains("plain file name"));
  CHECK(load_scene(kStrong, {"name=\"renamed\""}).name == "renamed");
  // Nothing was written outside: `adjoin run` refuses before it makes a folder.
  const auto r = run_cli("run " + qpath(scene) + " --quiet");
  CHECK(r.status == 2);
  CHECK_FALSE(std::filesystem::exists(std::filesystem::current_path().parent_path() / "escaped"));  // out/../../escaped
}

TEST_CASE("sweep files: two axes (or an axis and a motion) that set the same key are refused", "[sweep]") {
  const auto message = [](const std::string& body) {
    try {
      load_sweep(sweep_file("same.toml", body));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // The README's own example once did this: a range over model.mu and a table axis that sets it.
  CHECK_THAT(message(R"(
[[axis]]
key = "model.mu"
values = [0.1, 0.2]
[[axis]]
key = "model.eps"
values = [1.0, 2.0]
[[axis]]
name = "damper"
values = [{name = "none"}, {name = "strong", set = {"model.mu" = 0.6}}]
)"), Catch::Contains("same.toml:9: axis damper sets model.mu, and so does axis model.mu (") &&
        Catch::Contains("same.toml:3)"));
  CHECK_THAT(message(R"(
[[axis]]
key = "ground.u0"
values = [0.5, 1.0]
[[motion]]
name = "slow"
set = {"ground.omega" = 1.0}
[[motion]]
name = "big"
set = {"ground.u0" = 2.0}
)"), Catch::Contains("same.toml:9: motion big sets ground.u0, and so does axis ground.u0 (") &&
        Catch::Contains("same.toml:3)"));
  // Different keys, and a key the common `set` gives a default for, are fine.
  CHECK(message("set = {\"model.mu\" = 0.2}\n[[axis]]\nkey = \"model.mu\"\nvalues = [0.1]\n[[axis]]\nkey = \"model.eps\"\nvalues = [1.0]\n") ==
        "no error");
}

TEST_CASE("sweeps follow the --set rule for the structure an edit makes obsolete", "[sweep]") {
  // Re-stating the base's own ground source keeps its other keys, exactly as
  // `adjoin run --set ground.source=decaying-sine --set ground.u0=0.5` does (implied_unsets).
  const SweepSpec spec = load_sweep(sweep_file("restate.toml", R"(
[[motion]]
name = "smaller"
set = {"ground.source" = "decaying-sine", "ground.u0" = 0.5}
[[motion]]
name = "elastic"
set = {"model.rod1.elastic" = true}
)"));
  const Scene swept = sweep_scene(spec, 0);
  const Scene run = load_scene(kStrong, {"ground.source=\"decaying-sine\"", "ground.u0=0.5"});
  for (double t : {0.3, 1.7, 4.2}) CHECK(swept.ground->ag(t) == run.ground->ag(t));
  CHECK(swept.ground->describe() == run.ground->describe());
  // model.rod1.elastic = true drops the rod's order and relaxation times, as --set does.
  CHECK(two_block_model(sweep_scene(spec, 1)).rod1.elastic);
  CHECK(two_block_model(load_scene(kStrong, {"model.rod1.elastic=true"})).rod1.elastic);
}

TEST_CASE("a run's scene from the base parsed once is the scene, and the message, of adjoin run --set", "[sweep]") {
  // The sweep reads its base once and sets each run's edits as typed values on a copy of the
  // tree; `adjoin run BASE --set ... --unset ...` parses the text with the same edits. Their
  // scenes and their messages (file lines of the base included) must be the same.
  const SweepSpec spec = load_sweep(sweep_file("tree.toml", R"(
[[axis]]
name = "edit"
values = [{name = "mu", set = {"model.mu" = 0.45, "solver.h" = 0.01, "name" = "swept"}},
          {name = "si", set = {"model.units" = "SI"}},
          {name = "no-order", unset = ["model.rod1.order"]},
          {name = "eps", set = {"model.eps" = -1.0}},
          {name = "rod3", set = {"model.rod3.order" = 0.5}},
          {name = "not-a-table", set = {"model.mu.x" = 1}},
          {name = "tau", set = {"model.rod2.tau_f" = 9.0}},
          {name = "every", set = {"output.every" = 0}}]
)"));
  std::size_t base_lines = 0;
  for (std::size_t i = 0; i < spec.runs(); ++i) {
    const SweepSetting& edit = spec.axes[0].values[i];
    std::string expected = "no error";
    std::optional<Scene> run;
    try {
      run = load_scene(kStrong, edit.overrides(), edit.unset);
    } catch (const InputError& e) {
      expected = e.what();
    }
    std::string got = "no error";
    std::optional<Scene> swept;
    try {
      swept = sweep_scene(spec, i);
    } catch (const InputError& e) {
      got = e.what();
      // "tree.toml:LINE: run i (edit=..., motion=base): " + the scene's own message
      const std::string prefix = "run " + std::to_string(i) + " (" + spec.describe(i) + "): ";
      REQUIRE(got.find(prefix) != std::string::npos);
      got = got.substr(got.find(prefix) + prefix.size());
    }
    INFO("run " << i << " (" << edit.label << ")");
    CHECK(got == expected);
    if (expected.rfind(kStrong + ":", 0) == 0) ++base_lines;
    if (run && swept) {
      CHECK(swept->name == run->name);
      CHECK(two_block_model(*swept).mu == two_block_model(*run).mu);
      CHECK(two_block_model(*swept).eps == two_block_model(*run).eps);
      CHECK(two_block_model(*swept).rod1.order == two_block_model(*run).rod1.order);
      CHECK(two_block_model(*swept).rod2.tau_x == two_block_model(*run).rod2.tau_x);
      CHECK(swept->solver.h == run->solver.h);
      CHECK(swept->solver.t_end == run->solver.t_end);
      for (double t : {0.3, 1.7}) CHECK(swept->ground->ag(t) == run->ground->ag(t));
    }
  }
  CHECK(spec.axes[0].values[0].label == "mu");
  CHECK(sweep_scene(spec, 0).name == "swept");
  // Some of those messages cite lines of the base file (read from the tree parsed once).
  CHECK(base_lines >= 2);
}

TEST_CASE("sweep files are read as text files: folders, FIFOs, UTF-16 and binary are refused", "[sweep]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "sweep_text";
  std::filesystem::create_directories(dir / "folder.toml");
  CHECK_THROWS_WITH(load_sweep(dir / "folder.toml"), Catch::Contains("is a folder"));
  const auto utf16 = write_temp("utf16.toml", std::string("\xff\xfe" "b\0a\0", 6));
  CHECK_THROWS_WITH(load_sweep(utf16), Catch::Contains("UTF-16"));
  const auto binary = write_temp("binary.toml", std::string("base = 1\n\x89PNG\x01\x02", 14));
  CHECK_THROWS_WITH(load_sweep(binary), Catch::Contains("binary.toml:2:") && Catch::Contains("\\x89"));
  // The base scene too, with the sweep's line that names it.
  const auto base_dir = write_temp("folderbase.toml", "base = " + qpath(dir / "folder.toml") + "\n");
  CHECK_THROWS_WITH(load_sweep(base_dir), Catch::Contains("folderbase.toml:1: base: ") && Catch::Contains("is a folder"));
}

TEST_CASE("a sweep too large for memory is refused before it starts", "[sweep]") {
  // 1e8 points: about 500 GB of table; refused at once (it used to end in bad_alloc).
  CHECK_THROWS_WITH(load_sweep(sweep_file("huge.toml", "[[axis]]\nkey = \"model.mu\"\nfrom = 0.0\nto = 1.0\nn = 100000000\n")),
                    Catch::Contains("huge.toml:6:") && Catch::Contains("GB of memory") && Catch::Contains("80 %"));
  // The product of modest axes: accepted by the reader, refused by the size check with its need.
  const SweepSpec spec = load_sweep(sweep_file("product.toml", R"(
[[axis]]
key = "model.mu"
from = 0.0
to = 1.0
n = 20000
[[axis]]
key = "model.eps"
from = 0.5
to = 2.0
n = 20000
)"));
  CHECK(spec.runs() == 400000000u);
  CHECK_THROWS_WITH(check_sweep_memory(spec, spec.runs()), Catch::Contains("product.toml") && Catch::Contains("400000000 runs") &&
                                                               Catch::Contains("GB"));
  CHECK_NOTHROW(check_sweep_memory(spec, 1000));  // one small shard of it fits
}

TEST_CASE("journal rows are checked against the sweep before they are trusted", "[sweep][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / ("sweep_journal_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto file = sweep_file("journal.toml", R"(
set = {"solver.h" = 0.01, "solver.t_end" = 4.0}
[[axis]]
key = "model.mu"
values = [0.0, 0.3, 0.6, 0.9]
)");
  auto r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "serial") + " -q");
  REQUIRE(r.status == 0);
  const auto serial = csv_rows(slurp(dir / "serial" / "sweep.csv"));
  REQUIRE(serial.size() == 5);
  const SweepSpec spec = load_sweep(file);
  const auto wall = column_of(spec, "wall_seconds"), x1 = column_of(spec, "x1"), switches = column_of(spec, "switches");

  // Row problems, one by one.
  std::size_t index = 0;
  auto row = serial[2];
  CHECK(sweep_row_problem(spec, SweepShard{}, row, &index).empty());
  CHECK(index == 1);
  for (const char* bad : {"nan", "-inf", "inf", "1e999", "x"}) {
    row = serial[2];
    row[x1] = bad;
    CHECK_THAT(sweep_row_problem(spec, SweepShard{}, row, &index), Catch::Contains("x1 = \"" + std::string(bad) + "\""));
  }
  row = serial[2];
  row[1] = "0.45";  // run 1 has model.mu = 0.3
  CHECK_THAT(sweep_row_problem(spec, SweepShard{}, row, &index), Catch::Contains("model.mu = \"0.45\"") && Catch::Contains("\"0.3\""));
  row = serial[2];
  row[switches] = "";  // empty counts only for a failed run
  CHECK(!sweep_row_problem(spec, SweepShard{}, row, &index).empty());
  row = serial[2];
  row[0] = "7";
  CHECK_THAT(sweep_row_problem(spec, SweepShard{}, row, &index), Catch::Contains("does not exist"));
  CHECK_THAT(sweep_row_problem(spec, SweepShard{1, 2}, serial[1], &index), Catch::Contains("not in shard 1/2"));

  // A journal with one good row (wall 123), a nan, a -inf and a foreign axis value: the bad
  // rows are dropped with a warning naming the line, run again, and the table is the serial one.
  std::filesystem::create_directories(dir / "resume");
  {
    std::ofstream journal(dir / "resume" / "sweep.partial.csv", std::ios::binary);
    journal << sweep_journal_preamble(spec, SweepShard{});
    auto good = serial[3];
    good[wall] = "123";
    journal << csv_line(good) << "\n";  // line 3
    auto nan = serial[1];
    nan[x1] = "nan";
    journal << csv_line(nan) << "\n";  // line 4
    auto inf = serial[2];
    inf[column_of(spec, "energy_input")] = "-inf";
    journal << csv_line(inf) << "\n";  // line 5
    auto foreign = serial[4];
    foreign[1] = "0.95";
    journal << csv_line(foreign) << "\n";  // line 6
  }
  r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "resume"));
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("warning: ") && Catch::Contains("sweep.partial.csv:4: x1 = \"nan\"") &&
                        Catch::Contains("sweep.partial.csv:5: energy_input = \"-inf\"") &&
                        Catch::Contains("sweep.partial.csv:6: model.mu = \"0.95\"") && Catch::Contains("done again"));
  CHECK_THAT(r.err, !Catch::Contains(":3:"));
  CHECK_THAT(r.out, Catch::Contains("4 runs (1 from the journal"));
  CHECK_THAT(r.err, Catch::Contains("resuming: 1 runs from the journal"));
  const auto resumed = csv_rows(slurp(dir / "resume" / "sweep.csv"));
  REQUIRE(resumed.size() == 5);
  for (std::size_t i = 0; i < 4; ++i) CHECK((resumed[i + 1][wall] == "123") == (i == 2));
  CHECK(without_wall_time(resumed) == without_wall_time(serial));
  const std::string text = slurp(dir / "resume" / "sweep.csv");
  CHECK(text.find("nan") == std::string::npos);
  CHECK(text.find("inf") == std::string::npos);

  // A journal of another sweep is not used, and says so.
  {
    std::ofstream journal(dir / "resume" / "sweep.partial.csv", std::ios::binary);
    journal << "# adjoin sweep journal fingerprint=0000000000000000 runs=4 shard=0/1\n";
  }
  r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "resume") + " -q");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("a journal of another sweep"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("a journal row with both results and an error is dropped and run again", "[sweep][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / ("sweep_journal_error_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto file = sweep_file("journal-error.toml", R"(
set = {"solver.h" = 0.01, "solver.t_end" = 4.0}
[[axis]]
key = "model.mu"
values = [0.0, 0.3]
)");
  auto r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "serial") + " -q");
  REQUIRE(r.status == 0);
  const auto serial = csv_rows(slurp(dir / "serial" / "sweep.csv"));
  REQUIRE(serial.size() == 3);
  const SweepSpec spec = load_sweep(file);
  const auto error = column_of(spec, "error");
  // A failed run's row has empty results; one with numbers and an error is no row of a sweep.
  std::size_t index = 0;
  auto both = serial[2];
  both[error] = "numerical failure at t = 1";
  CHECK_THAT(sweep_row_problem(spec, SweepShard{}, both, &index),
             Catch::Contains("error = \"numerical failure at t = 1\", but x1 = ") && Catch::Contains("a failed run's results are empty"));
  // Resumed from a journal holding that row and a good one: the row is run again, the table is
  // the uninterrupted sweep's.
  std::filesystem::create_directories(dir / "resume");
  {
    std::ofstream journal(dir / "resume" / "sweep.partial.csv", std::ios::binary);
    journal << sweep_journal_preamble(spec, SweepShard{}) << csv_line(serial[1]) << "\n" << csv_line(both) << "\n";
  }
  r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir / "resume"));
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("sweep.partial.csv:4: error = ") && Catch::Contains("done again"));
  CHECK_THAT(r.out, Catch::Contains("2 runs (1 from the journal"));
  const auto resumed = csv_rows(slurp(dir / "resume" / "sweep.csv"));
  CHECK(without_wall_time(resumed) == without_wall_time(serial));
  std::filesystem::remove_all(dir);
}

TEST_CASE("a sweep journal that is a FIFO is refused and never read (reading it blocked for ever)", "[sweep][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / ("sweep_journal_fifo_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = sweep_file("journal-fifo.toml", "set = {\"solver.h\" = 0.01, \"solver.t_end\" = 2.0}\n");
  const auto fifo = dir / "sweep.partial.csv";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // Should a sweep open the FIFO (to read or to write it), this thread opens the other end
  // after a second, so the sweep goes on instead of hanging the test; it is then wrong by its
  // exit status.
  std::atomic<bool> finished{false};
  std::thread unblock([&] {
    for (int i = 0; !finished; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (i < 10) continue;
      if (const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK); fd >= 0) ::close(fd);  // a reader waits
      if (const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK); fd >= 0) {
        char buffer[4096];
        while (::read(fd, buffer, sizeof buffer) > 0) {
        }
        ::close(fd);
      }
    }
  });
  const auto r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir) + " -q");
  finished = true;
  unblock.join();
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains(fifo.string() + ": the sweep journal is a FIFO (named pipe), not a regular file"));
  CHECK(std::filesystem::is_fifo(std::filesystem::symlink_status(fifo)));
  CHECK(!std::filesystem::exists(dir / "sweep.csv"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("one sweep at a time per output folder: a second one is refused, naming the first", "[sweep][cli]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / ("sweep_lock_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = sweep_file("lock.toml", "set = {\"solver.h\" = 0.01, \"solver.t_end\" = 2.0}\n");
  const std::string pid = std::to_string(::getpid());
  {
    // This process holds the folder's lock, as a running sweep would.
    const FolderLock held(dir, "sweep.lock", "adjoin sweep other.toml --out x");
    CHECK_THAT(slurp(dir / "sweep.lock"), Catch::Contains("pid=" + pid));
    // Another lock on the same file (another open file, as another process has) is refused.
    CHECK_THROWS_WITH(FolderLock(dir, "sweep.lock", "second"),
                      Catch::Contains("sweep.lock: the output folder is in use by pid " + pid) &&
                          Catch::Contains("adjoin sweep other.toml --out x"));
    // Another process: `adjoin sweep` into the same folder stops with exit 2 before writing.
    const auto r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir) + " -q");
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::StartsWith("error: ") && Catch::Contains("in use by pid " + pid) &&
                          Catch::Contains("other.toml"));
    CHECK_FALSE(std::filesystem::exists(dir / "sweep.csv"));
    CHECK_FALSE(std::filesystem::exists(dir / "sweep.partial.csv"));
    // --shard 0/1 is the whole sweep: the same files, so the same lock.
    CHECK(run_cli("sweep " + qpath(file) + " --out " + qpath(dir) + " -q --shard 0/1").status == 2);
    // A real shard writes other files (sweep.shard-0-of-2.*) under its own lock: it may run.
    CHECK(run_cli("sweep " + qpath(file) + " --out " + qpath(dir) + " -q --shard 0/2").status == 0);
    CHECK(std::filesystem::exists(dir / "sweep.shard-0-of-2.csv"));
  }
  // Released (the holder ended): the sweep runs, and its own lock names it while it runs.
  const auto r = run_cli("sweep " + qpath(file) + " --out " + qpath(dir) + " -q");
  CHECK(r.status == 0);
  CHECK(std::filesystem::exists(dir / "sweep.csv"));
  CHECK_THAT(slurp(dir / "sweep.lock"), Catch::Contains("command=adjoin sweep ") && Catch::Contains("lock.toml"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("adjoin demand: a design point with too few motions is marked, the others are fitted", "[demand][cli]") {
  // Design point mu = 0.1: four motions on ln d = -1 + 1.5 ln im exactly. Design point mu = 0.3:
  // three motions, one of them failed, so two usable: not fitted.
  std::string csv = "index,model.mu,motion,units,drift,pga_g,error\n";
  std::size_t i = 0;
  for (double im : {0.1, 0.2, 0.4, 0.8}) {
    csv += std::to_string(i) + ",0.1,m" + std::to_string(i + 1) + ",dimensionless," +
           std::to_string(std::exp(-1.0 + 1.5 * std::log(im))) + "," + std::to_string(im) + ",\n";
    ++i;
  }
  csv += std::to_string(i++) + ",0.3,m1,dimensionless,0.5,0.1,\n";
  csv += std::to_string(i++) + ",0.3,m2,dimensionless,0.7,0.2,\n";
  csv += std::to_string(i++) + ",0.3,m3,dimensionless,,,numerical failure\n";
  const auto table = write_temp("demand-few.csv", csv);
  const auto out = std::filesystem::path(ADJOIN_TEST_TMP) / "demand-few-fit.csv";
  auto r = run_cli("demand " + qpath(table) + " --out " + qpath(out));
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::StartsWith("warning: ") && Catch::Contains("model.mu=0.3") && Catch::Contains("at least 3") &&
                        Catch::Contains("not fitted"));
  CHECK_THAT(r.out, Catch::Contains("1 of 2 design points not fitted"));
  const auto rows = csv_rows(slurp(out));
  REQUIRE(rows.size() == 3);
  const auto& header = rows[0];
  const auto col = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    REQUIRE(it != header.end());
    return static_cast<std::size_t>(it - header.begin());
  };
  CHECK(rows[1][col("model.mu")] == "0.1");
  CHECK(rows[1][col("fitted")] == "true");
  CHECK(std::stod(rows[1][col("a")]) == Approx(-1.0).epsilon(1e-5));
  CHECK(std::stod(rows[1][col("b")]) == Approx(1.5).epsilon(1e-5));
  CHECK(rows[2][col("model.mu")] == "0.3");
  CHECK(rows[2][col("fitted")] == "false");
  CHECK(rows[2][col("n")] == "2");
  CHECK(rows[2][col("skipped")] == "1");
  CHECK(rows[2][col("a")].empty());  // no nan: an empty cell
  CHECK(rows[2][col("beta")].empty());
  CHECK_THAT(rows[2][col("problem")], Catch::Contains("at least 3"));
  const std::string text = slurp(out);
  CHECK(text.find("nan") == std::string::npos);

  // When no design point can be fitted there is nothing to report: exit 2, naming it.
  r = run_cli("demand " + qpath(table) + " --pooled --response f2");
  CHECK(r.status == 2);
  const auto only_few = write_temp("demand-none.csv", "index,model.mu,motion,units,drift,pga_g,error\n0,0.3,m1,SI,0.5,0.1,\n1,0.3,m2,SI,0.7,0.2,\n");
  r = run_cli("demand " + qpath(only_few));
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::StartsWith("error: ") && Catch::Contains("demand-none.csv: model.mu=0.3") && Catch::Contains("at least 3"));
}

TEST_CASE("the sweep file reference's example is a valid sweep", "[sweep][docs]") {
  // It once varied model.mu on one axis and set it again in another (now an error).
  const std::string readme = slurp(std::string(ADJOIN_SOURCE_DIR) + "/docs/reference/sweep-file.md");
  const auto section = readme.find("# The sweep file");
  REQUIRE(section != std::string::npos);
  const auto begin = readme.find("```toml\n", section);
  REQUIRE(begin != std::string::npos);
  const auto end = readme.find("```", begin + 8);
  std::string text = readme.substr(begin + 8, end - begin - 8);
  const std::string base = "\"../../records/scenes/paper-strong.toml\"";
  const auto at = text.find(base);
  REQUIRE(at != std::string::npos);
  text.replace(at, base.size(), qpath(kStrong));
  const SweepSpec spec = parse_sweep(text, (std::filesystem::path(ADJOIN_TEST_TMP) / "readme.toml").string());
  CHECK(spec.axes.size() == 3);
  CHECK(spec.runs() == 21u * 2u * 2u * 1u);
  CHECK(spec.im_periods == std::vector<double>{0.5, 1.0});
}

TEST_CASE("adjoin demand: rows it skips for negative values are not called zero values", "[demand][cli]") {
  // Four usable rows on ln d = -1 + 1.5 ln im, and one with a negative response.
  std::string csv = "index,model.mu,motion,units,drift,pga_g,error\n";
  std::size_t i = 0;
  for (double im : {0.1, 0.2, 0.4, 0.8}) {
    csv += std::to_string(i) + ",0.1,m" + std::to_string(i + 1) + ",dimensionless," +
           std::to_string(std::exp(-1.0 + 1.5 * std::log(im))) + "," + std::to_string(im) + ",\n";
    ++i;
  }
  csv += std::to_string(i) + ",0.1,m5,dimensionless,-0.5,0.3,\n";
  const auto r = run_cli("demand " + qpath(write_temp("demand-negative.csv", csv)));
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("1 rows skipped: failed runs, or an IM or response that is not a positive number"));
  CHECK_THAT(r.out, !Catch::Contains("zero values"));
}
