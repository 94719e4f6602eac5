// adjoin plot: figures of a run, spectra, convergence and sweep tables; valid PNG/SVG files
// at the requested size; bad inputs exit 2 with a message naming what is wrong.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/gnuplot.hpp"
#include "adjoin/io/plots.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"
#include "png_check.hpp"

namespace fs = std::filesystem;
using adjoin::test::needs_program;
using adjoin::test::require_png;
using adjoin::test::run_cli;
using adjoin::test::slurp;
using adjoin::test::write_temp;

namespace {

const std::string kSource = ADJOIN_SOURCE_DIR;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / ("plot_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Solves the strong scene once for all the tests here.
const fs::path& strong_run() {
  static const fs::path dir = [] {
    const fs::path d = scratch("strong");
    const auto r = run_cli("run '" + kSource + "/records/scenes/paper-strong.toml' --quiet --out '" + d.string() + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    return d;
  }();
  return dir;
}

}  // namespace

TEST_CASE("plot run draws the paper's figures as PNG files of the requested size", "[plot][cli]") {
  needs_program("gnuplot");
  const fs::path& dir = strong_run();
  const auto r = run_cli("plot run '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  for (const char* name : {"displacements", "excitation", "rod-forces", "gap"}) {
    require_png(dir / (std::string(name) + ".png"), 900, 600);
    CHECK(r.out.find(name) != std::string::npos);
  }
  // No energy history in a run folder: the energy figure is skipped, and says so.
  CHECK_FALSE(fs::exists(dir / "energy.png"));
  CHECK(r.out.find("no energy figure") != std::string::npos);

  const fs::path prefix = scratch("sized") / "strong-";
  const auto sized = run_cli("plot run '" + dir.string() + "' --size 640x480 --out '" + prefix.string() + "'");
  INFO(sized.err);
  REQUIRE(sized.status == 0);
  require_png(prefix.string() + "displacements.png", 640, 480);
  require_png(prefix.string() + "excitation.png", 640, 480);
}

TEST_CASE("plot run as SVG labels the axes with the quantities and the scene's units", "[plot][cli]") {
  needs_program("gnuplot");
  const fs::path& dir = strong_run();
  const fs::path prefix = scratch("svg") / "";
  const auto r = run_cli("plot run '" + dir.string() + "' --format svg --out '" + prefix.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string displacements = slurp(prefix / "displacements.svg");
  CHECK(displacements.rfind("<?xml", 0) == 0);
  CHECK(displacements.find("<svg") != std::string::npos);
  CHECK(displacements.find("(dimensionless)") != std::string::npos);
  CHECK(displacements.find("time t") != std::string::npos);
  CHECK(displacements.find("paper-strong") != std::string::npos);
  CHECK(displacements.find("stick") != std::string::npos);
  const std::string excitation = slurp(prefix / "excitation.svg");
  CHECK(excitation.find("ground acceleration") != std::string::npos);
  CHECK(excitation.find("damper force q") != std::string::npos);
  CHECK(excitation.find("relative velocity") != std::string::npos);
  CHECK(slurp(prefix / "rod-forces.svg").find("rod force") != std::string::npos);
  const std::string gap = slurp(prefix / "gap.svg");
  CHECK(gap.find("min ξ = 1.44") != std::string::npos);
  CHECK(gap.find("contact") != std::string::npos);
}

TEST_CASE("plot run labels SI scenes in SI units and draws an energy history when there is one", "[plot][cli]") {
  needs_program("gnuplot");
  const fs::path dir = scratch("si");
  // A short SI-like run folder written by hand: the plots only read the files.
  std::ofstream(dir / "summary.json") << R"({"scene": "si-test", "units": "SI",
    "phases": [{"state": "stick", "t_start": 0.0, "t_end": 0.4}, {"state": "slip_right", "t_start": 0.4, "t_end": 1.0}],
    "pounding": {"min_gap": 0.05, "t_min_gap": 0.5, "contact": false, "t_first_contact": null}})";
  {
    std::ofstream ts(dir / "timeseries.csv");
    ts << "t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase\n";
    for (int i = 0; i <= 100; ++i) {
      const double t = i * 0.01;
      ts << t << "," << 0.01 * t << "," << 0.005 * t << ",0.01,0.005," << 1e5 * t << "," << 2e5 * t << ","
         << (t < 0.4 ? 1e4 * t : 2e4) << "," << std::sin(10 * t) << "," << 0.1 - 0.005 * t << ","
         << (t < 0.4 ? "stick" : "slip_right") << "\n";
    }
    std::ofstream e(dir / "energy.csv");
    e << "t,input,kinetic,rod1,rod2,friction,residual\n";
    for (int i = 0; i <= 100; ++i) {
      const double t = i * 0.01;
      e << t << "," << 4 * t << "," << t << "," << t << "," << t << "," << t << ",0\n";
    }
  }
  const auto r = run_cli("plot run '" + dir.string() + "' --format svg");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string displacements = slurp(dir / "displacements.svg");
  CHECK(displacements.find("[m]") != std::string::npos);
  CHECK(displacements.find("time t [s]") != std::string::npos);
  CHECK(displacements.find("dimensionless") == std::string::npos);
  const std::string excitation = slurp(dir / "excitation.svg");
  CHECK(excitation.find("[m/s²]") != std::string::npos);
  CHECK(excitation.find("[N]") != std::string::npos);
  CHECK(excitation.find("[m/s]") != std::string::npos);
  const std::string energy = slurp(dir / "energy.svg");
  CHECK(energy.find("energy [J]") != std::string::npos);
  CHECK(energy.find("friction") != std::string::npos);
}

TEST_CASE("plot spectrum, converge and sweep draw from their CSV tables", "[plot][cli]") {
  needs_program("gnuplot");
  const fs::path dir = scratch("tables");
  const fs::path spectrum = write_temp("spectrum.csv",
                                       "period,damping,sd,sv,sa,psv,psa\n"
                                       "0,0.05,0,0,0.3,0,0.3\n"
                                       "0.1,0.05,0.001,0.05,0.5,0.06,0.5\n0.5,0.05,0.02,0.2,0.6,0.25,0.6\n"
                                       "2,0.05,0.1,0.3,0.15,0.3,0.15\n"
                                       "0.1,0.02,0.0015,0.07,0.7,0.09,0.7\n0.5,0.02,0.03,0.3,0.9,0.35,0.9\n"
                                       "2,0.02,0.14,0.4,0.2,0.45,0.2\n");
  auto r = run_cli("plot spectrum '" + spectrum.string() + "' --out '" + (dir / "spectrum.svg").string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string svg = slurp(dir / "spectrum.svg");
  CHECK(svg.find("PSA [g]") != std::string::npos);
  CHECK(svg.find("period T [s]") != std::string::npos);
  CHECK(svg.find("damping 2 %") != std::string::npos);

  // A run's spectra.csv has a signal column: one curve per signal and damping (it was drawn as
  // one saw-tooth through all three), named in the legend.
  const fs::path run_spectra = write_temp("spectra.csv",
                                          "signal,period,damping,sd,sv,sa,psv,psa\n"
                                          "ground,0.1,0.05,0.001,0.05,0.5,0.06,0.5\nground,1,0.05,0.02,0.2,0.6,0.25,0.6\n"
                                          "block1,0.1,0.05,0.002,0.06,0.7,0.07,0.7\nblock1,1,0.05,0.03,0.3,0.9,0.3,0.9\n"
                                          "block2,0.1,0.05,0.003,0.07,0.8,0.08,0.8\nblock2,1,0.05,0.04,0.4,1.0,0.4,1.0\n");
  r = run_cli("plot spectrum '" + run_spectra.string() + "' --out '" + (dir / "run-spectra.svg").string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string three = slurp(dir / "run-spectra.svg");
  for (const char* label : {"ground, damping 5 %", "block1, damping 5 %", "block2, damping 5 %"}) {
    INFO(label);
    CHECK(three.find(label) != std::string::npos);
  }

  const fs::path converge = write_temp("convergence.csv",
                                       "scheme,history,h,steps,wall_seconds,error,order\n"
                                       "paper,direct,0.004,4000,0.01,1e-2,\n"
                                       "paper,direct,0.002,8000,0.03,5e-3,1.0\n"
                                       "implicit,direct,0.004,4000,0.02,1e-4,\n"
                                       "implicit,direct,0.002,8000,0.06,2.5e-5,2.0\n"
                                       "implicit,fft,0.002,8000,0.05,2.5e-5,2.0\n");
  r = run_cli("plot converge '" + converge.string() + "' --out '" + (dir / "converge.png").string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  require_png(dir / "converge.png", 900, 600);

  const fs::path sweep = write_temp("sweep.csv",
                                    "model.mu,ground,peak_x1,min_gap\n"
                                    "0.1,\"sine, strong\",1.2,1.4\n0.2,\"sine, strong\",1.1,1.5\n"
                                    "0.3,\"sine, strong\",1.0,1.6\n0.1,weak,0.1,1.9\n0.2,weak,0.1,1.9\n0.3,weak,0.1,1.9\n");
  r = run_cli("plot sweep '" + sweep.string() + "' --x model.mu --y peak_x1,min_gap --group ground --format svg --out '" +
              (dir / "sweep.svg").string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string curves = slurp(dir / "sweep.svg");
  CHECK(curves.find("friction threshold μ") != std::string::npos);  // model.mu's label
  CHECK(curves.find("peak_x1") != std::string::npos);                // a column with no label keeps its name
  CHECK(curves.find(">sine, strong<") != std::string::npos);         // key entries: the group's values
  CHECK(curves.find(">ground<") != std::string::npos);               // under the group column as the key's title
  CHECK(curves.find("smallest gap [m]") != std::string::npos);
  r = run_cli("plot sweep '" + sweep.string() + "' --x model.mu --y peak_x1 --size 500x400");
  INFO(r.err);
  REQUIRE(r.status == 0);
  require_png(sweep.parent_path() / "sweep.png", 500, 400);
}

TEST_CASE("plot rejects bad input with exit 2 and a message naming the problem", "[plot][cli]") {
  const fs::path empty = scratch("empty");
  auto r = run_cli("plot run '" + empty.string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error:", 0) == 0);
  CHECK(r.err.find("summary.json") != std::string::npos);

  std::ofstream(empty / "summary.json") << R"({"scene": "x", "units": "dimensionless"})";
  r = run_cli("plot run '" + empty.string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error:", 0) == 0);
  CHECK(r.err.find("timeseries.csv") != std::string::npos);
  CHECK(r.err.find("not found") != std::string::npos);

  r = run_cli("plot spectrum '" + (empty / "missing.csv").string() + "'");
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error:", 0) == 0);
  CHECK(r.err.find("missing.csv") != std::string::npos);

  const fs::path sweep = write_temp("bad-sweep.csv", "model.mu,peak_x1,peak_x2\n0.1,1,2\n0.2,1.5,x\n");
  r = run_cli("plot sweep '" + sweep.string() + "' --x model.mu --y peak_q");
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error:", 0) == 0);
  CHECK(r.err.find("'peak_q'") != std::string::npos);
  CHECK(r.err.find("model.mu, peak_x1, peak_x2") != std::string::npos);
  r = run_cli("plot sweep '" + sweep.string() + "' --x model.mu --y peak_x1 --group load_case");
  CHECK(r.status == 2);
  CHECK(r.err.find("'load_case'") != std::string::npos);
  r = run_cli("plot sweep '" + sweep.string() + "' --x model.mu --y peak_x2");
  CHECK(r.status == 2);
  CHECK(r.err.find("bad-sweep.csv:3") != std::string::npos);
  CHECK(r.err.find("'x'") != std::string::npos);

  const fs::path& dir = strong_run();
  r = run_cli("plot run '" + dir.string() + "' --format jpg");
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error:", 0) == 0);
  CHECK(r.err.find("--format jpg") != std::string::npos);
  CHECK(r.err.find("png or svg") != std::string::npos);
  r = run_cli("plot sweep '" + sweep.string() + "' --x model.mu --y peak_x1 --out curves.pdf");
  CHECK(r.status == 2);
  CHECK(r.err.find(".png or .svg") != std::string::npos);
  r = run_cli("plot run '" + dir.string() + "' --size big");
  CHECK(r.status == 2);
  CHECK(r.err.find("--size big") != std::string::npos);
}

TEST_CASE("read_csv_table understands quotes and reports ragged rows by line", "[plot]") {
  const fs::path file = write_temp("quoted.csv", "# comment\na,b\n\"x, y\",\"say \"\"hi\"\"\"\n1,2\n");
  const adjoin::CsvTable t = adjoin::read_csv_table(file);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0][0] == "x, y");
  CHECK(t.rows[0][1] == "say \"hi\"");
  CHECK(t.lines[1] == 4);
  CHECK_THROWS_WITH(t.numbers("b"), Catch::Contains("quoted.csv:3") && Catch::Contains("column 'b'"));
  const fs::path numeric = write_temp("numeric.csv", "a,b\n1,\n2,nan\n3,-4.5e1\n");
  const std::vector<double> b = adjoin::read_csv_table(numeric).numbers("b");
  CHECK(std::isnan(b[0]));
  CHECK(std::isnan(b[1]));
  CHECK(b[2] == -45.0);
  const fs::path ragged = write_temp("ragged.csv", "a,b\n1,2\n3\n");
  CHECK_THROWS_WITH(adjoin::read_csv_table(ragged), Catch::Contains("ragged.csv:3") && Catch::Contains("expected 2"));
}

TEST_CASE("read_csv_table trims blanks around cells and names broken quoting and missing files", "[plot]") {
  const fs::path file = write_temp("blanks.csv", "t , x\n 1 , \" a \" \n2,+1e-400\n");
  const adjoin::CsvTable t = adjoin::read_csv_table(file);
  CHECK(t.columns == std::vector<std::string>{"t", "x"});
  CHECK(t.texts("x") == std::vector<std::string>{" a ", "+1e-400"});  // quoted blanks kept
  CHECK(t.numbers("t") == std::vector<double>{1.0, 2.0});
  CHECK_THROWS_WITH(t.numbers("x"), Catch::Contains("blanks.csv:2: column 'x' holds 'a', expected a number"));
  const fs::path broken = write_temp("broken.csv", "a,b\n1,2\n3,4\"5\n");
  CHECK_THROWS_WITH(adjoin::read_csv_table(broken), Catch::Contains("broken.csv:3: broken quoting"));
  const fs::path unclosed = write_temp("unclosed.csv", "a,b\n\"1,2\n");
  CHECK_THROWS_WITH(adjoin::read_csv_table(unclosed), Catch::Contains("unclosed.csv:2: broken quoting"));
  CHECK_THROWS_WITH(adjoin::read_csv_table(file.parent_path() / "none.csv", "a sweep table"),
                    Catch::Contains("none.csv: not found (expected a sweep table)"));
}

TEST_CASE("plot run on a building run draws floor profiles of both buildings and the roofs' histories", "[plot][cli]") {
  needs_program("gnuplot");
  const fs::path dir = scratch("building");
  const auto run = run_cli("run '" + kSource + "/records/scenes/buildings/two-frames.toml' --quiet --set solver.t_end=8 --out '" +
                           dir.string() + "'");
  INFO(run.err);
  REQUIRE(run.status == 0);
  const fs::path prefix = scratch("building-png") / "";
  const auto png = run_cli("plot run '" + dir.string() + "' --size 800x500 --out '" + prefix.string() + "'");
  INFO(png.err);
  REQUIRE(png.status == 0);
  require_png(prefix / "profiles.png", 800, 500);
  require_png(prefix / "roofs.png", 800, 500);
  const fs::path svg = scratch("building-svg") / "";
  REQUIRE(run_cli("plot run '" + dir.string() + "' --format svg --out '" + svg.string() + "'").status == 0);
  const std::string profiles = slurp(svg / "profiles.svg");
  CHECK(profiles.find("peak storey drift [m]") != std::string::npos);
  CHECK(profiles.find("building A") != std::string::npos);
  CHECK(profiles.find("building B") != std::string::npos);
  const std::string roofs = slurp(svg / "roofs.svg");
  CHECK(roofs.find("A: roof, floor 5") != std::string::npos);
  CHECK(roofs.find("B: roof, floor 3") != std::string::npos);
  CHECK(roofs.find("link 1") != std::string::npos);
  CHECK(roofs.find("link force [kN]") != std::string::npos);
  // Chosen channels only: one panel each, with the names on the axes.
  const fs::path chosen = scratch("building-channels") / "";
  auto picked = run_cli("plot run '" + dir.string() + "' --channels A.x5,B.a3_abs,link1.stroke --size 700x900 --out '" +
                        chosen.string() + "'");
  INFO(picked.err);
  REQUIRE(picked.status == 0);
  CHECK(picked.out.find("channels.png") != std::string::npos);
  require_png(chosen / "channels.png", 700, 900);
  REQUIRE(run_cli("plot run '" + dir.string() + "' --channels A.x5,link1.stroke --format svg --out '" + chosen.string() + "'")
              .status == 0);
  const std::string panels = slurp(chosen / "channels.svg");
  CHECK(panels.find("A.x5") != std::string::npos);
  CHECK(panels.find("link1.stroke") != std::string::npos);
  CHECK(panels.find("B.a3_abs") == std::string::npos);
  // A name that is not a column names itself and lists the columns there are; exit 2.
  picked = run_cli("plot run '" + dir.string() + "' --channels A.x5,A.x9 --out '" + chosen.string() + "'");
  CHECK(picked.status == 2);
  CHECK(picked.err.find("--channels") != std::string::npos);
  CHECK(picked.err.find("'A.x9'") != std::string::npos);
  CHECK(picked.err.find("A.x5") != std::string::npos);
}

// ---------------------------------------------------------------- round 3: text from data in scripts

namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Files that gnuplot commands in the payloads below would create, in the folder adjoin runs
// in (the test's working folder) and in `dir`.
bool pwned(const fs::path& dir) {
  return fs::exists("PWNED") || fs::exists("PWNED2") || fs::exists(dir / "PWNED") || fs::exists(dir / "PWNED2");
}

// Text that ends a gnuplot string and runs shell commands, in every way a script can: a
// newline, a quote of either kind, backquotes, a macro.
std::string payload(const fs::path& dir) {
  const std::string touch = "touch " + (dir / "PWNED").string(), touch2 = "touch " + (dir / "PWNED2").string();
  return "x'\nsystem \"" + touch + "\"\n\" `" + touch2 + "` @GPVAL_TERM \\";
}

// A run folder whose summary.json has `scene` set to `scene`.
fs::path run_with_scene(const std::string& name, const std::string& scene) {
  const fs::path dir = scratch(name);
  fs::copy_file(strong_run() / "timeseries.csv", dir / "timeseries.csv");
  std::string summary = slurp(strong_run() / "summary.json");
  const std::string key = "\"scene\": \"";
  const auto at = summary.find(key);
  REQUIRE(at != std::string::npos);
  const auto end = summary.find('"', at + key.size());
  std::string escaped;
  for (char c : scene) {
    if (c == '"' || c == '\\') escaped += '\\';
    escaped += c == '\n' ? std::string("\\n") : std::string(1, c);
  }
  summary.replace(at, end + 1 - at, key + escaped + "\"");
  std::ofstream(dir / "summary.json") << summary;
  return dir;
}

// A shell command line (for limits set with ulimit), its output captured as run_cli does.
adjoin::test::CliResult run_shell(const std::string& command) {
  const fs::path dir = scratch("shell");
  const int raw = std::system(("sh -c " + shell_quote(command) + " >'" + (dir / "out").string() + "' 2>'" +
                               (dir / "err").string() + "'").c_str());
  adjoin::test::CliResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(dir / "out");
  r.err = slurp(dir / "err");
  return r;
}

std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.find(".tmp.") != std::string::npos || n.find(".gp") != std::string::npos) names.push_back(n);
  }
  return names;
}

}  // namespace

TEST_CASE("gnuplot_quote keeps any text inside one single-quoted string on one line", "[plot][r3]") {
  CHECK(adjoin::gnuplot_quote("it's") == "'it''s'");
  CHECK(adjoin::gnuplot_quote("a\nb\tc\rd") == "'a\\nb\\tc\\rd'");
  std::string every;
  for (int c = 1; c < 256; ++c) every += static_cast<char>(c);
  const std::string q = adjoin::gnuplot_quote(every);
  for (char c : q) CHECK_FALSE((static_cast<unsigned char>(c) < 0x20 || c == 0x7f));
  // Inside, every quote is doubled: the string ends only at the last character.
  std::size_t i = 1;
  for (; i + 1 < q.size(); ++i)
    if (q[i] == '\'') {
      REQUIRE(q[i + 1] == '\'');
      ++i;
    }
  CHECK(i == q.size() - 1);
  CHECK(adjoin::gnuplot_quote_wrapped("a\n'b", 70) == "'a\\n''b'");
  CHECK(adjoin::gnuplot_quote_wrapped("aaa bbb", 2) == "'aaa'.\"\\n\".'bbb'");
}

TEST_CASE("plot run: a scene name from summary.json runs no command", "[plot][cli][r3]") {
  needs_program("gnuplot");
  const fs::path trap = scratch("pwned-scene-trap");
  const fs::path dir = run_with_scene("pwned-scene", payload(trap));
  // The issue's repro too: a bare newline and `system`, relative to the working folder.
  const fs::path plain = run_with_scene("pwned-scene-plain", "x\nsystem \"touch PWNED\"");
  for (const fs::path& run : {dir, plain}) {
    const auto r = run_cli("plot run " + shell_quote(run.string()));
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK_FALSE(pwned(trap));
    require_png(run / "displacements.png", 900, 600);
  }
  // The title shows the text, control characters written visibly.
  REQUIRE(run_cli("plot run " + shell_quote(plain.string()) + " --format svg").status == 0);
  CHECK(slurp(plain / "gap.svg").find("x\\nsystem") != std::string::npos);
  // And the chosen-channels figure, which takes the scene name too.
  const auto c = run_cli("plot run " + shell_quote(dir.string()) + " --channels x1,gap");
  INFO(c.err);
  CHECK(c.status == 0);
  CHECK_FALSE(pwned(trap));
}

TEST_CASE("plot record and spectrum --plot: a record's file name runs no command", "[plot][cli][r3]") {
  needs_program("gnuplot");
  const fs::path trap = scratch("pwned-record-trap");
  const fs::path dir = scratch("pwned-record");
  // The name holds a quote, backquotes and a newline (a file name cannot hold '/').
  const std::string name = "x'\nsystem \"touch PWNED\"\n`touch PWNED2`.AT2";
  fs::copy_file(kSource + "/records/real/peer/RSN175_IMPVALL.H_H-E12140.AT2", dir / name);
  const std::string file = shell_quote((dir / name).string());
  const fs::path cwd = fs::current_path();
  auto r = run_cli("plot record " + file + " --out " + shell_quote((dir / "record.png").string()));
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK_FALSE(pwned(cwd));
  require_png(dir / "record.png", 900, 600);
  r = run_cli("spectrum " + file + " --out " + shell_quote((dir / "s.csv").string()) + " --plot " +
              shell_quote((dir / "s.png").string()));
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK_FALSE(pwned(cwd));
  require_png(dir / "s.png", 900, 900);
  // --title, and column names of a sweep table (a CSV line holds no newline).
  const fs::path csv = dir / "t.csv";
  std::ofstream(csv) << "a,\"b' `touch PWNED` \"\"\"\n1,2\n2,3\n";
  r = run_cli("plot sweep " + shell_quote(csv.string()) + " --x a --y " + shell_quote("b' `touch PWNED` \"") +
              " --title " + shell_quote(payload(trap)));
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK_FALSE(pwned(cwd));
  CHECK_FALSE(pwned(trap));
}

TEST_CASE("plot: a failed image write is exit 2 and leaves nothing (file size limit as a full disk)", "[plot][cli][r3]") {
  needs_program("gnuplot");
  const fs::path dir = scratch("full-disk");
  const fs::path csv = dir / "s.csv";
  std::ofstream(csv) << "a,b\n1,2\n2,3\n3,1\n";
  // A 3000x3000 PNG (~130 kB) from a 2 kB script: with a 16 kB limit gnuplot's own write
  // fails (it says nothing and exits 0), and so would adjoin's. SIGXFSZ ignored: writes fail.
  const std::string command = "trap '' XFSZ; ulimit -f 16; exec '" + std::string(ADJOIN_CLI) + "' plot sweep '" +
                              csv.string() + "' --x a --y b --size 3000x3000";
  const auto r = run_shell(command);
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error:", 0) == 0);
  CHECK(r.err.find("s.png") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "s.png"));
  CHECK(leftovers(dir).empty());

  // A run folder under the same limit: none of its figures, no temporaries, no script files.
  const fs::path out = scratch("full-disk-run");
  const std::string run_command = "trap '' XFSZ; ulimit -f 20; exec '" + std::string(ADJOIN_CLI) + "' plot run '" +
                                  strong_run().string() + "' --size 3000x3000 --out '" + out.string() + "/'";
  const auto rr = run_shell(run_command);
  INFO(rr.err);
  CHECK(rr.status == 2);
  CHECK(fs::is_empty(out));
}

TEST_CASE("plot run reads and draws everything before writing: a damaged CSV leaves no figure", "[plot][cli][r3]") {
  needs_program("gnuplot");
  const fs::path dir = scratch("damaged");
  fs::copy_file(strong_run() / "timeseries.csv", dir / "timeseries.csv");
  fs::copy_file(strong_run() / "summary.json", dir / "summary.json");
  std::ofstream(dir / "energy.csv") << "t,input,kinetic\n0,0,0\n1,zz,1\n";
  const fs::path out = scratch("damaged-figs") / "sub";
  const auto r = run_cli("plot run '" + dir.string() + "' --out '" + out.string() + "/'");
  CHECK(r.status == 2);
  CHECK(r.err.find("energy.csv:3") != std::string::npos);
  CHECK_FALSE(fs::exists(out));  // not even the folder
  CHECK(leftovers(dir.parent_path()).empty());
}

// ---------------------------------------------------------------- round 3: figures for a report

namespace {

// The distinct stroke colours of the curves in an SVG of gnuplot's.
std::set<std::string> stroke_colours(const std::string& svg) {
  std::set<std::string> colours;
  for (std::size_t at = svg.find("stroke='rgb("); at != std::string::npos; at = svg.find("stroke='rgb(", at + 1))
    colours.insert(svg.substr(at, svg.find(')', at) - at));
  return colours;
}

}  // namespace

TEST_CASE("plot sweep: 13 groups in 12 distinct colours, y from zero, text x, engineering ticks", "[plot][cli][r3]") {
  needs_program("gnuplot");
  const fs::path dir = scratch("report-sweep");
  std::string text = "motion,link.1.slip_ratio,link1.energy_share,link1.force_max,damper\n";
  for (int g = 0; g < 13; ++g)
    for (int i = 0; i < 3; ++i)
      text += "m" + std::to_string(g) + "," + std::to_string(0.1 * i) + "," + std::to_string(0.05 * (g + i)) + "," +
              std::to_string(1e7 * (1 + i)) + "," + (i % 2 ? "friction" : "none") + "\n";
  std::ofstream(dir / "s.csv") << text;
  const std::string csv = "'" + (dir / "s.csv").string() + "'";
  auto r = run_cli("plot sweep " + csv + " --x link.1.slip_ratio --y link1.energy_share --group motion --out '" +
                   (dir / "a.svg").string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string a = slurp(dir / "a.svg");
  // 12 colours for the curves (the 13th repeats the first, dashed), besides the grey of the
  // grid and the key's box; the palette cycled at 8 before.
  std::set<std::string> colours = stroke_colours(a);
  colours.erase("stroke='rgb(208, 208, 208"), colours.erase("stroke='rgb(176, 176, 176");
  CHECK(colours.size() == 12);
  CHECK(a.find("share of the input energy, link 1") != std::string::npos);
  CHECK(a.find("slip force of link 1 / weight of building B") != std::string::npos);
  CHECK(a.find("-0.1") == std::string::npos);  // the axis starts at 0, not below
  // Forces of 1e7 N: ticks as 1.0e7, not 1x10^7.
  r = run_cli("plot sweep " + csv + " --x link.1.slip_ratio --y link1.force_max --out '" + (dir / "b.svg").string() + "'");
  REQUIRE(r.status == 0);
  const std::string b = slurp(dir / "b.svg");
  CHECK(b.find("e7") != std::string::npos);
  CHECK(b.find("10^") == std::string::npos);
  CHECK(b.find("×") == std::string::npos);
  CHECK(b.find("peak force, link 1 [N]") != std::string::npos);
  // A text-valued x column is a categorical axis (it was "expected a number", exit 2).
  r = run_cli("plot sweep " + csv + " --x damper --y link1.energy_share --group motion --out '" + (dir / "c.svg").string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string c = slurp(dir / "c.svg");
  CHECK(c.find(">none<") != std::string::npos);
  CHECK(c.find(">friction<") != std::string::npos);
  // --logx with zeros says how many rows it leaves out; with nothing left it is exit 2.
  r = run_cli("plot sweep " + csv + " --x link.1.slip_ratio --y link1.energy_share --logx --out '" + (dir / "d.png").string() + "'");
  CHECK(r.status == 0);
  CHECK(r.err.find("--logx: 13 row(s) with link.1.slip_ratio <= 0 are not drawn") != std::string::npos);
  std::ofstream(dir / "zeros.csv") << "a,b\n0,1\n-1,2\n";
  r = run_cli("plot sweep '" + (dir / "zeros.csv").string() + "' --x a --y b --logx");
  CHECK(r.status == 2);
  CHECK(r.err.find("--logx: every value of column 'a' is zero or negative") != std::string::npos);
  r = run_cli("plot sweep " + csv + " --x damper --y link1.energy_share --logx");
  CHECK(r.status == 2);
  CHECK(r.err.find("holds text") != std::string::npos);
}

TEST_CASE("plot run: overlays of several runs, a time window, a run without links titled so", "[plot][cli][r3]") {
  needs_program("gnuplot");
  const fs::path linked = scratch("overlay-linked"), unlinked = scratch("overlay-unlinked");
  const std::string scene = "'" + kSource + "/records/scenes/buildings/two-frames.toml' --quiet --set solver.t_end=6 ";
  REQUIRE(run_cli("run " + scene + "--out '" + linked.string() + "'").status == 0);
  REQUIRE(run_cli("run " + scene + "--unset link --out '" + unlinked.string() + "'").status == 0);
  const fs::path out = scratch("overlay-out") / "";
  auto r = run_cli("plot run '" + linked.string() + "' '" + unlinked.string() + "' --format svg --window 1:4 --out '" +
                   out.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string svg = slurp(out / "overlay.svg");
  CHECK(svg.find("(overlay-linked)") != std::string::npos);
  CHECK(svg.find("(no links) (overlay-unlinked)") != std::string::npos);
  CHECK(svg.find("displacement, floor 5, building") != std::string::npos);  // (wrapped before "A [m]")
  // The window's ends are the axis' ends: ticks 1 to 4, none at 0 or 5.
  CHECK(svg.find(">1<") != std::string::npos);
  CHECK(svg.find(">4<") != std::string::npos);
  CHECK(svg.find(">5<") == std::string::npos);
  // One run without links: its figures say so.
  r = run_cli("plot run '" + unlinked.string() + "' --format svg");
  REQUIRE(r.status == 0);
  CHECK(slurp(unlinked / "profiles.svg").find("(no links)") != std::string::npos);
  // Windows: bad syntax, T0 >= T1 and a window outside the run are exit 2 naming --window.
  for (const char* bad : {"5", "a:b", "3:3", "4:2", "100:200"}) {
    r = run_cli("plot run '" + linked.string() + "' --window '" + bad + "' --out '" + out.string() + "'");
    INFO(bad << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("--window") != std::string::npos);
  }
  // The help's example names real columns.
  r = run_cli("plot run --help");
  CHECK(r.out.find("A.drift1") == std::string::npos);
  CHECK(r.out.find("--window") != std::string::npos);
}
