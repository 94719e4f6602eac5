// A building scene's run: the scene read whole (structure, ground, solver, defaults), the
// run's files, and what they report checked against independent computations: the modes
// against the modal analysis, each peak against the largest sample of the time series, the
// base shear against the floors' inertia forces, the friction link within its slip force.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adjoin/io/run_files.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/timeseries_csv.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/structure/modal.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"
#include "needs_program.hpp"
#include "state_recorder.hpp"

using namespace adjoin;

namespace {

const std::string kScene = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";

std::map<std::string, std::vector<double>> read_columns(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (std::size_t i = 0; std::getline(row, cell, ','); ++i) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      columns[names.at(i)].push_back(end != cell.c_str() ? v : std::nan(""));
    }
  }
  return columns;
}

}  // namespace

TEST_CASE("a building scene reads whole, and chooses h and t_end when not given", "[building_run]") {
  const BuildingScene given = load_building_scene(kScene);
  CHECK(given.solver.h == 0.002);
  CHECK(given.accuracy.h_rule == "given");
  CHECK(given.structure.a.floors() == 5);
  const BuildingScene chosen = load_building_scene(kScene, {"solver.h=0.001", "solver.t_end=2"});
  CHECK(chosen.solver.h == 0.001);
  CHECK(chosen.solver.t_end == 2.0);
  // Without [solver]: h from the shortest fundamental period (B: 0.5 s) / 200, no coarser than
  // the record's dt (0.02 s); t_end = the record's duration + 5 x the longest period.
  const std::filesystem::path dir = std::filesystem::path(ADJOIN_TEST_TMP) / "building-defaults";
  std::filesystem::create_directories(dir);
  std::ifstream in(kScene);
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  scene = scene.substr(0, scene.find("[solver]"));
  const auto copy = std::filesystem::path(ADJOIN_SOURCE_DIR) / "records/scenes/buildings";  // the record path is relative
  const auto file = copy / ".defaults-test.toml";
  std::ofstream(file) << scene;
  const BuildingScene d = load_building_scene(file);
  std::filesystem::remove(file);
  CHECK(d.solver.h == Approx(0.5 / 200).epsilon(1e-9));
  const double longest = structure::coupled_modes(d.structure).periods_free[0];
  CHECK(d.solver.t_end == Approx(d.ground->duration() + 5 * longest).epsilon(1e-9));
  CHECK(d.accuracy.t_end_rule.find("duration") != std::string::npos);
}

TEST_CASE("a building run's files agree with the modal analysis and the time series", "[building_run]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "building-run";
  std::filesystem::remove_all(dir);
  const BuildingScene scene = load_building_scene(kScene, {"output.every=1", "solver.t_end=12"});
  const RunFiles files = run_to_folder(scene, dir);
  REQUIRE(files.written.size() == 2);
  std::ifstream in(dir / "summary.json");
  const auto j = nlohmann::json::parse(in);
  // Modes.
  const structure::Modes a = structure::building_modes(scene.structure.a);
  for (int i = 0; i < 5; ++i) CHECK(j["structure"]["A"]["periods"][i].get<double>() == Approx(a.periods[i]).epsilon(1e-12));
  CHECK(j["structure"]["periods_locked"].size() == 7);  // 8 floors, one pair locked together
  // Peaks against the largest sample (the refinement adds at most O(h^2)).
  const auto columns = read_columns(dir / "timeseries.csv");
  REQUIRE(columns.at("t").size() == scene.solver.steps() + 1);
  for (const char* channel : {"A.x5", "B.x3", "A.a1_abs", "link1.force", "link1.stroke"}) {
    INFO(channel);
    double largest = 0.0;
    for (double v : columns.at(channel)) largest = std::max(largest, std::abs(v));
    const double peak = j["peaks"][channel]["max_abs"].get<double>();
    CHECK(peak >= largest * (1 - 1e-12));
    CHECK(peak <= largest * (1 + 1e-3));
  }
  // Base shear of A: the floors' inertia forces, sum of m_i |a_i,abs| at each sample.
  double shear = 0.0;
  for (std::size_t k = 0; k < columns.at("t").size(); ++k) {
    double s = 0.0;
    for (int i = 1; i <= 5; ++i) s += 45e3 * columns.at("A.a" + std::to_string(i) + "_abs")[k];
    shear = std::max(shear, std::abs(s));
  }
  CHECK(j["peaks"]["A.base_shear"]["max_abs"].get<double>() == Approx(shear).epsilon(1e-3));
  // The friction link: never beyond its slip force (5 % of B's weight), and it slips.
  const double slip = 0.05 * 170e3 * 9.80665;
  CHECK(j["links"][0]["slip_force"].get<double>() == Approx(slip));
  CHECK(j["links"][0]["force_max"].get<double>() <= slip * (1 + 1e-12));
  CHECK(j["links"][0]["switches"].get<int>() > 2);
  CHECK(j["links"][0]["energy"].get<double>() > 0.0);  // friction only dissipates
  // The contact pair's gap column is the gap at rest less the link stroke.
  const auto& gap = columns.at("contact1.gap");
  const auto& stroke = columns.at("link1.stroke");
  for (std::size_t k = 0; k < gap.size(); k += 97) CHECK(gap[k] == Approx(0.05 - stroke[k]).margin(1e-15));
}

TEST_CASE("in-structure spectra of floors are the spectra of the floors' acceleration histories", "[building_run]") {
  // An independent path: the floor's a_abs column of timeseries.csv (every step, 12 digits)
  // through the single-record spectrum. The roof's spectrum at a short period is its peak
  // absolute acceleration; a floor filters the ground (the roof's spectrum peaks near T1).
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "building-spectra";
  std::filesystem::remove_all(dir);
  const BuildingScene scene = load_building_scene(
      kScene, {"output.every=1", "solver.t_end=12", "output.spectra.signals=[\"ground\", \"A.a5_abs\", \"B.a2_abs\"]",
               "output.spectra.periods=[0.02, 0.1, 0.5, 1.0, 2.0]", "output.spectra.damping=[0.02, 0.05]"});
  const RunFiles files = run_to_folder(scene, dir);
  REQUIRE(files.report.spectra.size() == 3);
  const auto columns = read_columns(dir / "timeseries.csv");
  const auto spectra = read_columns(dir / "spectra.csv");  // (the signal column reads as NaN)
  REQUIRE(spectra.at("psa").size() == 3 * 5 * 2);
  SpectrumOptions options;
  options.periods = {0.02, 0.1, 0.5, 1.0, 2.0};
  options.dampings = {0.02, 0.05};
  const char* signals[] = {"ag", "A.a5_abs", "B.a2_abs"};
  for (std::size_t k = 0; k < 3; ++k) {
    const ResponseSpectrum direct = response_spectrum(scene.solver.h, columns.at(signals[k]), options);
    for (std::size_t i = 0; i < direct.values.size(); ++i) {
      INFO(signals[k] << " T = " << direct.values[i].period << " damping " << direct.values[i].damping);
      CHECK(spectra.at("period")[k * 10 + i] == direct.values[i].period);
      CHECK(spectra.at("psa")[k * 10 + i] == Approx(direct.values[i].psa).epsilon(1e-8));
      CHECK(spectra.at("sd")[k * 10 + i] == Approx(direct.values[i].sd).epsilon(1e-8));
    }
  }
  double roof = 0.0;
  for (double a : columns.at("A.a5_abs")) roof = std::max(roof, std::abs(a));
  CHECK(spectra.at("psa")[10 + 5] == Approx(roof / kStandardGravity).epsilon(0.02));  // T = 0.02 s, 5 %
}

TEST_CASE("in-structure spectra without a list of signals are the ground's and each building's first floor's", "[building_run]") {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "building-spectra-default";
  std::filesystem::remove_all(dir);
  const BuildingScene scene =
      load_building_scene(kScene, {"output.every=1", "solver.t_end=6", "output.spectra.periods=[0.02]"});
  const RunFiles files = run_to_folder(scene, dir);
  REQUIRE(files.report.spectra.size() == 3);
  const auto columns = read_columns(dir / "timeseries.csv");
  const char* signals[] = {"ground", "A.a1_abs", "B.a1_abs"};
  const char* columns_of[] = {"ag", "A.a1_abs", "B.a1_abs"};
  for (std::size_t k = 0; k < 3; ++k) {
    INFO(signals[k]);
    CHECK(files.report.spectra[k].signal == signals[k]);
    // The spectrum of the column of timeseries.csv that names the same history.
    SpectrumOptions options;
    options.periods = {0.02};
    options.dampings = {0.05};
    const ResponseSpectrum direct = response_spectrum(scene.solver.h, columns.at(columns_of[k]), options);
    CHECK(files.report.spectra[k].spectrum.at(0, 0).psa == Approx(direct.values[0].psa).epsilon(1e-8));
  }
  CHECK(files.report.spectra[1].spectrum.at(0, 0).psa != files.report.spectra[2].spectrum.at(0, 0).psa);
}

TEST_CASE("the SI record scene written in building keys gives the two-block results", "[building_run]") {
  const Scene two_block = load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/si-record.toml",
                                     {"solver.history=fft", "solver.scheme=implicit", "solver.t_end=29"});
  test::StateRecorder grid;  // its 1 + 1 structure's states, in the scene's dimensionless units
  run(two_block, {&grid});
  // (t_end inside the record: at its very end, 30 s, one time axis rounds past the last sample.)
  const BuildingScene building =
      load_building_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/si-record-as-building.toml", {"solver.t_end=29"});
  class Rec final : public StructureObserver {
   public:
    void observe(const StructureState& s) override { states.push_back(s); }
    std::vector<StructureState> states;
  } rec;
  simulate_structure(building.solver, building.structure, *building.ground, rec);
  REQUIRE(rec.states.size() == grid.states.size());
  const Scales& k = two_block.scales;
  double dx = 0.0, dq = 0.0, x_max = 0.0;
  std::size_t switches = 0;
  for (std::size_t i = 0; i < rec.states.size(); ++i) {
    const auto& a = rec.states[i];
    const auto& b = grid.states[i];
    x_max = std::max(x_max, std::abs(b.x[0] * k.length));
    dx = std::max({dx, std::abs(a.x[0] - b.x[0] * k.length), std::abs(a.x[1] - b.x[1] * k.length)});
    dq = std::max(dq, std::abs(a.link_force[0] - b.link_force[0] * k.force));
    if (i > 0 && b.link_phase[0] != grid.states[i - 1].link_phase[0]) ++switches;
    CHECK(a.link_phase[0] == b.link_phase[0]);
  }
  INFO("dx " << dx << " of " << x_max << ", dq " << dq << " N, " << switches << " switches");
  CHECK(switches >= 8);
  CHECK(dx <= 1e-12 * x_max);
  CHECK(dq <= 1e-9 * 2.0e5);
}

TEST_CASE("the energy balance of a building run closes at order 2 with several dampers", "[building_run][energy]") {
  BuildingScene scene = load_building_scene(kScene, {"solver.t_end=15", "output.timeseries=false"});
  structure::Link second = scene.structure.links[0];
  second.floor_a = 2;
  second.floor_b = 2;
  second.slip_force = 4e4;
  scene.structure.links.push_back(second);
  std::vector<double> residuals;
  for (double h : {0.004, 0.002, 0.001}) {
    scene.solver.h = h;
    const Report r = run(scene);
    INFO("h = " << h << ": input " << r.energy.input << " J, residual " << r.energy.residual << " J");
    for (std::size_t l = 0; l < 2; ++l) {
      CHECK(r.links[l].switches > 2);
      CHECK(r.energy.links[l] > 0.0);                                              // friction dissipates
      CHECK(r.energy.links[l] == Approx(r.links[l].energy).epsilon(1e-12));  // two bookkeepings agree
    }
    CHECK(r.energy.buildings[0].inherent > 0.0);
    residuals.push_back(std::abs(r.energy.residual) / r.energy.input);
  }
  INFO("relative residuals " << residuals[0] << " " << residuals[1] << " " << residuals[2]);
  CHECK(residuals[2] < 1e-5);
  CHECK(std::log2(residuals[0] / residuals[1]) > 1.7);
  CHECK(std::log2(residuals[1] / residuals[2]) > 1.7);
}

namespace {

// two-frames.toml without its [solver] section and its output.every (the scene of issue 25: a
// new user's building scene with output.timeseries = true and no step), plus `edits`.
BuildingScene scene_without_solver(const std::string& name, const std::vector<std::string>& edits) {
  std::ifstream in(kScene);
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const auto solver = scene.find("[solver]");
  scene = scene.substr(0, solver) + "[output]\ntimeseries = true\n";
  const auto file = std::filesystem::path(ADJOIN_SOURCE_DIR) / "records/scenes/buildings" / ("." + name + ".toml");
  std::ofstream(file) << scene;
  BuildingScene s = load_building_scene(file, edits);
  std::filesystem::remove(file);
  return s;
}

std::size_t lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

}  // namespace

TEST_CASE("r3 defaults: a building scene without [solver] takes an engineer's tolerance and writes a sampled time series",
          "[building_run][defaults]") {
  // Issue 25: the default tolerance 1e-6 chose h = 5e-5 s and wrote 504 MB (882,239 rows).
  // With a contact law (impacts): rows every 1/1000 s, in whole steps.
  const BuildingScene scene = scene_without_solver(
      "r3-defaults", {"contact.1.model=hertzdamp", "contact.1.stiffness=2e9", "contact.1.restitution=0.65"});
  REQUIRE(scene.accuracy.tolerance);
  REQUIRE(*scene.accuracy.tolerance == 1e-3);  // before the run: 1e-6 would take minutes
  CHECK(scene.accuracy.h_rule.find("solver.tolerance = 0.001 (the default") != std::string::npos);
  CHECK(output_interval(scene) == 1e-3);
  CHECK(output_every(scene, 2.5e-4) == 4);
  CHECK(output_every(scene, 3e-4) == 3);
  CHECK(output_every(scene, 2.5e-3) == 1);
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "r3-defaults";
  std::filesystem::remove_all(dir);
  std::vector<std::string> warnings;
  const RunFiles files = run_to_folder(scene, dir, [&](const std::string& w) { warnings.push_back(w); });
  REQUIRE(files.tolerant);
  CHECK(files.tolerant->met);
  const double h = files.tolerant->h;
  CHECK(h >= 1e-3);  // 5e-5 with the old default
  CHECK(h == scene.solver.h);  // the first rung, T_B / 200 = 2.5e-3 s, meets 1e-3
  const std::size_t every = output_every(scene, h);
  CHECK(every == std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(1e-3 / h * (1 + 1e-9)))));
  const std::size_t steps = files.report.solver.steps;
  CHECK(lines_of(dir / "timeseries.csv") == 1 + steps / every + 1 + (steps % every ? 1 : 0));
  CHECK(std::filesystem::file_size(dir / "timeseries.csv") < 10'000'000);  // 8.6 MB (504 MB before)
  CHECK(warnings.empty());
  std::filesystem::remove_all(dir);
}

TEST_CASE("r3 defaults: without a contact law rows every 1/200 s, and a scene's own h or every is kept", "[building_run][defaults]") {
  const BuildingScene chosen = scene_without_solver("r3-defaults-200", {});
  CHECK(output_interval(chosen) == 5e-3);
  CHECK(output_every(chosen, 1e-3) == 5);
  CHECK(output_every(chosen, 0.0025) == 2);
  CHECK(output_every(chosen, 0.004) == 1);
  const BuildingScene given_h = scene_without_solver("r3-defaults-h", {"solver.h=0.001"});
  CHECK(output_interval(given_h) == 0.0);
  CHECK(output_every(given_h, 0.001) == 1);  // as before: every grid point
  const BuildingScene given_every = scene_without_solver("r3-defaults-every", {"output.every=7"});
  CHECK(output_every(given_every, 1e-4) == 7);
  // A scene's own tolerance is kept.
  const BuildingScene given_tol = scene_without_solver("r3-defaults-tol", {"solver.tolerance=1e-5"});
  CHECK(*given_tol.accuracy.tolerance == 1e-5);
}

TEST_CASE("r3 defaults: a time series over 50 MB is announced with its size before it is written", "[building_run][defaults]") {
  // two-frames at h = 3e-4 s for 45 s, every point: 150,001 rows of 22 columns (64 MB).
  const BuildingScene scene = load_building_scene(kScene, {"output.every=1", "solver.h=3e-4", "solver.error_estimate=false"});
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "r3-defaults-large";
  std::filesystem::remove_all(dir);
  std::vector<std::string> warnings;
  run_to_folder(scene, dir, [&](const std::string& w) { warnings.push_back(w); });
  REQUIRE(warnings.size() == 1);
  INFO(warnings[0]);
  CHECK(warnings[0].find("timeseries.csv will be about") != std::string::npos);
  CHECK(warnings[0].find("set output.every") != std::string::npos);
  // The size said is the file's within 25 %.
  const double said = std::stod(warnings[0].substr(warnings[0].find("about ") + 6)) * 1e6;
  const double size = static_cast<double>(std::filesystem::file_size(dir / "timeseries.csv"));
  CHECK(size > 50e6);
  CHECK(said == Approx(size).epsilon(0.25));
  std::filesystem::remove_all(dir);
}

TEST_CASE("r3 defaults: a long run shows its estimate and progress on a terminal, never in a pipe", "[building_run][progress]") {
  // ADJOIN_PROGRESS_AFTER=0: every run timed (0.25 s) shows its progress, so that a test can
  // be short; 900,000 steps of two-frames take about 1 s (more than the 0.25 s timed first).
  test::needs_program("script");
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "r3-progress";
  std::filesystem::remove_all(dir);
  const std::string run = std::string("'") + ADJOIN_CLI + "' run '" + kScene +
                          "' --set solver.h=5e-5 --set output.timeseries=false --set solver.error_estimate=false --out '" +
                          dir.string() + "'";
  const auto terminal = dir.string() + ".tty";
  // script(1) runs the command on a pseudo-terminal and copies what it shows to its stdout.
  const std::string on_tty = "ADJOIN_PROGRESS_AFTER=0 script -qec \"" + run + "\" /dev/null > '" + terminal + "' 2>&1";
  REQUIRE(std::system(on_tty.c_str()) == 0);
  const std::string shown = adjoin::test::slurp(terminal);
  CHECK(shown.find("run 1: 900000 steps of h = 5e-05 s, about") != std::string::npos);
  CHECK(shown.find("/900000 steps") != std::string::npos);
  CHECK(shown.find("ETA") != std::string::npos);
  std::filesystem::remove(terminal);
  // The same run with stderr to a file (a pipe, a log): nothing of it.
  const auto piped = adjoin::test::run_cli("run '" + kScene +
                                           "' --set solver.h=4e-4 --set output.timeseries=false "
                                           "--set solver.error_estimate=false --out '" + dir.string() + "'");
  CHECK(piped.status == 0);
  CHECK(piped.err.find("steps") == std::string::npos);
  CHECK(piped.err.find("ETA") == std::string::npos);
  // --quiet on a terminal: nothing either.
  const std::string quiet = "ADJOIN_PROGRESS_AFTER=0 script -qec \"" + run + " --quiet\" /dev/null > '" + terminal + "' 2>&1";
  REQUIRE(std::system(quiet.c_str()) == 0);
  CHECK(adjoin::test::slurp(terminal).find("ETA") == std::string::npos);
  std::filesystem::remove(terminal);
  std::filesystem::remove_all(dir);
}
