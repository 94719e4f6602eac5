// Ground motion in scenes: recorded accelerograms (read, processed, scaled to the solver's
// units) and synthetic filtered noise (reproducible from its seed).
#include <catch2/catch.hpp>
#include <cmath>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"
#include "cli_helpers.hpp"
#include "state_recorder.hpp"

using namespace adjoin;

namespace {
const std::string kScenes = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/";
const std::string kElCentro = std::string(ADJOIN_REAL_RECORDS) + "/two-column/elCentro.txt";

// The message of loading scene `name` with overrides, or "no error".
std::string scene_error(const std::string& name, const std::vector<std::string>& overrides) {
  try {
    load_scene(kScenes + name, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("a record scene sees the record: a_g = -u'' in g on the solver's grid", "[ground][record]") {
  const Scene scene = load_scene(kScenes + "si-record.toml",
                                 {"ground.file=" + kElCentro, "ground.baseline=0", "ground.scale_pga=0.25", "solver.t_end=10"});
  RecordFormat format;
  format.units = AccelUnit::g;
  const Record raw = read_record(kElCentro, format);
  REQUIRE(raw.dt == Approx(0.02));
  // At the record's own sample times the forcing is the processed sample, sign flipped, in g.
  double mean = 0.0, peak = 0.0;
  for (double a : raw.accel) mean += a;
  mean /= static_cast<double>(raw.accel.size());
  for (double a : raw.accel) peak = std::max(peak, std::abs(a - mean));
  const double scale = 0.25 * kStandardGravity / peak;
  for (std::size_t i : {std::size_t{10}, std::size_t{100}, std::size_t{250}}) {
    const double t = static_cast<double>(i) * raw.dt / scene.scales.time;  // dimensionless
    CHECK(scene.ground->ag(t) == Approx(-(raw.accel[i] - mean) * scale / kStandardGravity).epsilon(1e-9));
  }
  const Report r = run(scene);
  CHECK(r.peak("ag").max_abs * scene.scales.acceleration / kStandardGravity == Approx(0.25).epsilon(0.02));
  CHECK(r.energy.input > 0.0);
}

TEST_CASE("record keys are checked: missing file, bad units, bad filter, keys of another source", "[ground][record]") {
  auto error_of = [](const std::vector<std::string>& o) { return scene_error("si-record.toml", o); };
  CHECK(error_of({"ground.file=/nonexistent.txt"}).find("/nonexistent.txt") != std::string::npos);
  CHECK(error_of({"ground.file=" + kElCentro, "ground.units=furlongs"}).find("ground.units = \"furlongs\"") != std::string::npos);
  CHECK(error_of({"ground.file=" + kElCentro, "ground.filter=notch"}).find("ground.filter = \"notch\"") != std::string::npos);
  CHECK(error_of({"ground.file=" + kElCentro, "ground.u0=1"}).find("ground.u0 is not a key of source \"record\"") != std::string::npos);
  CHECK(error_of({"ground.file=" + kElCentro, "ground.time_scale=2"}).find("SI scene") != std::string::npos);
}

TEST_CASE("a filtered-noise scene is reproducible from its seed and changes with it", "[ground][synthesis]") {
  // Within one process the motion is built once (see the cache test below); the synthesis
  // itself is checked bit for bit in test_synthesis, and against this scene's motion in the
  // EC8 type 2 test. Here: the runs are deterministic and the seed matters.
  auto run = [&](const char* seed) {
    Scene s = load_scene(kScenes + "si-noise.toml", {std::string("ground.seed=") + seed, "solver.t_end=5", "output.spectra.periods=[0.5]"});
    test::StateRecorder rec;
    adjoin::run(s, {&rec});
    return rec.states;
  };
  const auto a = run("7"), b = run("7"), c = run("8");
  REQUIRE(a.size() == b.size());
  bool identical = true, different = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    identical &= a[i].x[0] == b[i].x[0] && a[i].ag == b[i].ag;
    different |= a[i].ag != c[i].ag;
  }
  CHECK(identical);
  CHECK(different);
}

TEST_CASE("a filtered-noise scene matched to EC8 type 2 at 2 % damping, and its keys checked", "[ground][synthesis]") {
  // The scene's ground motion, read back through the library, has the asked-for 2 % spectrum.
  const std::vector<std::string> type2 = {"ground.match_ec8=\"C\"", "ground.match_ag=0.2", "ground.match_ec8_type=2",
                                          "ground.match_damping=0.02", "ground.match_band=[0.1, 2.0]",
                                          "ground.match_tolerance=0.15", "solver.t_end=1"};
  const Scene s = load_scene(kScenes + "si-noise.toml", type2);
  // The same motion synthesised directly: seed, envelope and duration of the scene.
  SynthesisOptions o;
  o.duration = 20.0;
  o.dt = 0.005;
  o.seed = 7;
  o.target_pga = 1.0;
  MatchOptions m;
  m.target = TargetSpectrum::ec8('C', 0.2, 2);
  m.period_min = 0.1;
  m.period_max = 2.0;
  m.damping = 0.02;
  // Within 15 % over the band: with the envelope kept in shape (SIMQKE's way) this seed's best
  // over 5 phase draws is 12.1 %; the test is about the scene giving the library's motion.
  m.tolerance = 0.15;
  MatchReport report;
  const Record direct = synthesize_matched(o, m, &report);
  REQUIRE(report.converged);
  // The scene's forcing at the record's instants: a_g = -u'' in g, at dimensionless t / T0.
  double worst = 0.0;
  for (std::size_t i = 0; i < direct.accel.size(); i += 37) {
    const double t = static_cast<double>(i) * direct.dt / s.scales.time;
    worst = std::max(worst, std::abs(s.ground->ag(t) + direct.accel[i] / kStandardGravity));
  }
  CHECK(worst <= 1e-9);

  auto error_of = [](const std::vector<std::string>& keys) { return scene_error("si-noise.toml", keys); };
  CHECK(error_of({"ground.match_ec8_type=3"}).find("ground.match_ec8_type") != std::string::npos);
  CHECK(error_of({"ground.match_damping=1.5"}).find("ground.match_damping") != std::string::npos);
  CHECK(error_of({"ground.match_ag=-0.1"}).find("ground.match_ag") != std::string::npos);
}

TEST_CASE("grounds are built once per process and rebuilt when what they come from changes", "[ground][cache]") {
  // Sweeps load the same ground for every run: a matched synthetic motion or a processed
  // record is built once. Another seed, or a changed record file, is another ground.
  const std::vector<std::string> short_run = {"solver.t_end=1"};
  const Scene a = load_scene(kScenes + "si-noise.toml", short_run), b = load_scene(kScenes + "si-noise.toml", short_run);
  CHECK(a.ground.get() == b.ground.get());
  const Scene c = load_scene(kScenes + "si-noise.toml", {"solver.t_end=1", "ground.seed=8"});
  CHECK(c.ground.get() != a.ground.get());
  CHECK(c.ground->ag(1.0) != a.ground->ag(1.0));

  const auto file = test::write_temp("cache-record.txt", "0 0\n0.01 0.1\n0.02 0.2\n0.03 0.1\n0.04 0\n");
  auto record_scene = [&] {
    return load_scene(kScenes + "si-record.toml", {"ground.file=\"" + file.string() + "\"", "solver.t_end=0.1"});
  };
  const Scene first = record_scene(), again = record_scene();
  CHECK(first.ground.get() == again.ground.get());
  // New content (and length): the file's stamp changes, so the ground is read again.
  test::write_temp("cache-record.txt", "0 0\n0.01 -0.3\n0.02 -0.6\n0.03 -0.3\n0.04 0\n0.05 0\n");
  const Scene changed = record_scene();
  CHECK(changed.ground.get() != first.ground.get());
  const double t = 0.02 / changed.scales.time;  // the record's peak sample, dimensionless
  CHECK(changed.ground->ag(t) * first.ground->ag(t) < 0.0);  // the sign flipped with the file
}

TEST_CASE("the project's own scenes run from a clean checkout (nothing outside the checkout needed)", "[ground][scenes]") {
  for (const char* name : {"si-record.toml", "si-noise.toml"}) {
    INFO(name);
    const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / name;
    const auto r = test::run_cli("run '" + kScenes + name + "' --set solver.t_end=4 -q --out '" + dir.string() + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    // The ground was read and moved the blocks (a missing record or noise would leave them still).
    const auto j = nlohmann::json::parse(test::slurp(dir / "summary.json"));
    CHECK(j["peaks"]["x1"]["max_abs"].get<double>() > 0.0);
    CHECK(j["peaks"]["x2"]["max_abs"].get<double>() > 0.0);
  }
}
