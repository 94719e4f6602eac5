// The minimum seismic joint (study/seismic_joint.hpp, issue 13 "Studies"): the bisection over
// runs and the direct value s_max of one run without contact are two independent answers and
// agree to the tolerance, on the paper's strong scene and on two frames under a record; a gap
// of joint + tol never touches, one of joint - 10 tol does (without a contact law, and with
// one: impacts); adjoin joint writes joint.json and says the same.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/seismic_joint.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;
namespace fs = std::filesystem;

namespace {

const fs::path kStrong = fs::path(ADJOIN_SOURCE_DIR) / "records/scenes/paper-strong.toml";
const fs::path kFrames = fs::path(ADJOIN_SOURCE_DIR) / "examples/buildings/two-frames-one-damper.toml";

// The paper's strong scene on the implicit scheme (fft history: 8000 steps, a run in a few ms).
Scene strong_scene() { return load_scene(kStrong, {"solver.scheme=implicit", "solver.history=fft"}); }

// Two frames joined by a friction damper at floor 3, the first 10 s of the Newhall record.
BuildingScene frames_scene() { return load_building_scene(kFrames, {"solver.t_end=10"}); }

// The two frames of the examples with one more [[contact]] table (its keys `contact`), the
// record's path made absolute so the scene loads from the test's temporary folder.
BuildingScene frames_with_contact(const std::string& name, const std::string& contact,
                                  const std::vector<std::string>& overrides = {}) {
  std::ifstream in(kFrames);
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const std::string relative = "../../records/";
  scene.replace(scene.find(relative), relative.size(), (fs::path(ADJOIN_SOURCE_DIR) / "records").string() + "/");
  scene += "\n[[contact]]\n" + contact;
  const fs::path file = fs::path(ADJOIN_TEST_TMP) / (name + "_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(file) << scene;
  BuildingScene s = load_building_scene(file, overrides);
  fs::remove(file);
  return s;
}

// A two-block run of `scene` with gap0 = gap (scene units) and the contact law `law`.
ContactReport two_block_run(const Scene& scene, double gap, const structure::ContactLaw& law = {}) {
  Scene s = scene;
  s.structure.contacts[0].gap = gap / s.scales.length;  // (the blocks' pair, dimensionless)
  s.structure.contacts[0].law = law;
  return run(s).contacts.at(0);
}

ContactReport building_run(const BuildingScene& scene, double gap, const structure::ContactLaw& law = {}) {
  BuildingScene s = scene;
  s.structure.contacts.at(0).gap = gap;
  s.structure.contacts.at(0).law = law;
  return run(s).contacts.at(0);
}

void check_agreement(const SeismicJoint& j) {
  INFO(std::setprecision(17) << "joint " << j.joint << ", low " << j.joint_low << ", s_max " << j.s_max << ", tol " << j.tol << ", runs " << j.runs);
  CHECK(j.agree);
  CHECK(j.s_max > 0.0);
  CHECK(j.joint >= j.s_max);
  CHECK(j.joint - j.s_max <= j.tol);
  CHECK(j.joint_low <= j.s_max * (1.0 + 1e-12));  // touches (the first midpoint is s_max itself)
  CHECK(j.joint - j.joint_low <= j.tol);
  CHECK(j.tol == Approx(1e-6 * j.s_max));
  // [0, 2 s_max] halved to 1e-6 s_max: 21 halvings, the top's check and the direct run.
  CHECK(j.runs == 23);
  CHECK(j.widenings == 0);
  CHECK(j.srss == Approx(std::hypot(j.peak_a, j.peak_b)));
  CHECK(j.abs_sum == Approx(j.peak_a + j.peak_b));
  // s = x_A - x_B is at most |x_A| + |x_B|.
  CHECK(j.s_max <= j.abs_sum * (1.0 + 1e-9));
}

}  // namespace

TEST_CASE("seismic joint of the paper's strong scene: bisection and direct s_max agree", "[joint]") {
  const Scene scene = strong_scene();
  const SeismicJoint j = seismic_joint(scene);
  check_agreement(j);
  CHECK(j.gap_key == "model.gap0");
  CHECK_FALSE(j.building);
  // The scene's own run (gap0 = 2) reports the margin min_gap = gap0 - s_max.
  const ContactReport own = run(scene).contacts.at(0);
  CHECK(two_block_model(scene).gap0 - own.min_gap == Approx(j.s_max).epsilon(1e-12));
  CHECK(j.t_critical == Approx(own.t_min_gap).epsilon(1e-12));

  // A gap of joint + tol never touches; joint - 10 tol does, without a contact law and with
  // the Newton law and a linear one (one impact at least).
  CHECK_FALSE(two_block_run(scene, j.joint + j.tol).contact);
  CHECK(two_block_run(scene, j.joint + j.tol).min_gap >= 0.0);
  CHECK(two_block_run(scene, j.joint - 10.0 * j.tol).contact);
  structure::ContactLaw newton;
  newton.model = structure::ContactModel::impact;
  newton.restitution = 0.65;
  CHECK(two_block_run(scene, j.joint + j.tol, newton).impact_list.empty());
  CHECK_FALSE(two_block_run(scene, j.joint - 10.0 * j.tol, newton).impact_list.empty());
  structure::ContactLaw linear;
  linear.model = structure::ContactModel::linear;
  linear.stiffness = 1e3;  // dimensionless: 1000 k1
  linear.restitution = 0.65;
  CHECK(two_block_run(scene, j.joint + j.tol, linear).impact_list.empty());
  CHECK_FALSE(two_block_run(scene, j.joint - 10.0 * j.tol, linear).impact_list.empty());

  // A given tolerance, and the scene's contact law is not used.
  SeismicJointOptions coarse;
  coarse.tol = 1e-3;
  Scene with_law = scene;
  with_law.structure.contacts[0].law = linear;
  const SeismicJoint c = seismic_joint(with_law, coarse);
  CHECK(c.agree);
  CHECK(c.tol == 1e-3);
  CHECK(c.s_max == Approx(j.s_max).epsilon(1e-12));
  CHECK(c.joint - c.s_max <= 1e-3);
  CHECK(c.runs < j.runs);
  CHECK_FALSE(c.notes.empty());
}

TEST_CASE("seismic joint of two frames under a record: bisection and direct s_max agree", "[joint]") {
  const BuildingScene scene = frames_scene();
  const SeismicJoint j = seismic_joint(scene);
  check_agreement(j);
  CHECK(j.building);
  CHECK(j.gap_key == "contact.1.gap");
  CHECK(j.floor_a == 3);
  CHECK(j.floor_b == 3);
  // The scene's own run (gap 0.05 m, no contact law) reports its minimum gap on the grid: the
  // joint's s_max is refined between grid points, a little above 0.05 - min_gap (O(h^2)).
  const ContactReport own = run(scene).contacts.at(0);
  CHECK(j.s_max >= 0.05 - own.min_gap);
  CHECK(j.s_max - (0.05 - own.min_gap) < 1e-3 * j.s_max);
  CHECK(std::abs(j.t_critical - own.t_min_gap) <= scene.solver.h);

  // joint + tol: no contact, without a law (on the grid) and with the Hertzdamp law and the
  // Newton law (no impact: the solver locates touches on the parabola the joint is refined on);
  // joint - 10 tol: an impact with either law.
  CHECK_FALSE(building_run(scene, j.joint + j.tol).contact);
  structure::ContactLaw hertzdamp;
  hertzdamp.model = structure::ContactModel::hertzdamp;
  hertzdamp.stiffness = 1e9;
  hertzdamp.restitution = 0.65;
  CHECK(building_run(scene, j.joint + j.tol, hertzdamp).impacts == 0);
  CHECK(building_run(scene, j.joint - 10.0 * j.tol, hertzdamp).impacts > 0);
  structure::ContactLaw newton;
  newton.model = structure::ContactModel::impact;
  newton.restitution = 0.65;
  CHECK(building_run(scene, j.joint + j.tol, newton).impacts == 0);
  CHECK(building_run(scene, j.joint - 10.0 * j.tol, newton).impacts > 0);
  // Well below the joint the grid sees the overlap too.
  CHECK(building_run(scene, 0.9 * j.joint).contact);
}

TEST_CASE("seismic joint: bad options are refused naming them", "[joint]") {
  SeismicJointOptions o;
  std::string error;
  o.tol = 0.0;
  CHECK_FALSE(o.IsValid(&error));
  CHECK(error.find("tol") != std::string::npos);
  o.tol = -1.0;
  CHECK_THROWS_AS(seismic_joint(strong_scene(), o), InputError);
  o = SeismicJointOptions{};
  o.contact = 2;
  CHECK_THROWS_WITH(seismic_joint(frames_scene(), o), Catch::Contains("contact 2: the scene has 1 contact pair"));
  const BuildingScene none = load_building_scene(kFrames, {"solver.t_end=1"}, {"contact"});
  CHECK_THROWS_WITH(seismic_joint(none), Catch::Contains("no contact pair"));
}

TEST_CASE("adjoin joint writes joint.json with the bisection, the direct value and the codes' rules", "[joint][cli]") {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / ("joint_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto r = adjoin::test::run_cli("joint '" + kStrong.string() +
                                       "' --set solver.scheme=implicit --set solver.history=fft --tol 1e-4 --out '" +
                                       dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("minimum seismic joint of paper-strong") != std::string::npos);
  CHECK(r.out.find("agree within the tolerance") != std::string::npos);
  CHECK(r.out.find("SRSS") != std::string::npos);
  std::ifstream in(dir / "joint.json");
  const auto json = nlohmann::json::parse(in);
  const Scene scene = strong_scene();
  const SeismicJoint j = seismic_joint(scene, [] { SeismicJointOptions o; o.tol = 1e-4; return o; }());
  CHECK(json["joint"].get<double>() == Approx(j.joint).epsilon(1e-12));
  CHECK(json["direct"]["s_max"].get<double>() == Approx(j.s_max).epsilon(1e-12));
  CHECK(json["direct"]["agree"].get<bool>());
  CHECK(json["bisection"]["runs"].get<std::size_t>() == j.runs);
  CHECK(json["tolerance"].get<double>() == 1e-4);
  CHECK(json["gap_key"] == "model.gap0");
  CHECK(json["code_rules"]["srss"].get<double>() == Approx(j.srss));
  CHECK(json["code_rules"]["srss_rule"].get<std::string>().find("ASCE 7") != std::string::npos);
  CHECK(json["critical_approach"]["t"].get<double>() == Approx(j.t_critical));
  fs::remove_all(dir);
}

TEST_CASE("the impact-force sweep example runs: no impact past the minimum joint, impacts short of it", "[joint][sweep]") {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / ("impact_force_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const fs::path sweep = fs::path(ADJOIN_SOURCE_DIR) / "examples/sweeps/impact-force.toml";
  const auto r = adjoin::test::run_cli("sweep '" + sweep.string() + "' --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::ifstream in(dir / "sweep.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) header.push_back(cell);
  }
  auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    FAIL("no column " << name);
    return std::size_t{0};
  };
  const std::size_t gap = column("contact.1.gap"), slip = column("link.1.slip_ratio"),
                    impacts = column("contact1.impacts"), force = column("contact1.force_max");
  // The base's own slip ratio, 0.05: its minimum joint (whole record) from adjoin joint.
  const double joint = seismic_joint(load_building_scene(kFrames)).joint;
  int rows = 0, checked = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ++rows;
    if (cells.at(slip) != "0.05") continue;
    const double g = std::stod(cells.at(gap));
    INFO("gap " << g << ", joint " << joint);
    if (g > joint) {
      CHECK(std::stod(cells.at(impacts)) == 0);
    } else {
      CHECK(std::stod(cells.at(impacts)) > 0);
      CHECK(std::stod(cells.at(force)) > 1e5);
    }
    ++checked;
  }
  CHECK(rows == 28);
  CHECK(checked == 7);
  fs::remove_all(dir);
}

TEST_CASE("seismic joint: another pair that pounds once is noted as 1 impact, in the singular", "[joint]") {
  // The frames of the examples with a second pair at floors 3 (a Hertzdamp law, gap 0.25 m):
  // under the whole record it pounds once (examples/sweeps/impact-force.toml, slip ratio 0.05).
  const BuildingScene s = frames_with_contact("joint_one_impact",
                                              "floors = [3, 3]\ngap = 0.25\nmodel = \"hertzdamp\"\nstiffness = 2e10\nrestitution = 0.65\n");
  const Report r = run(s);
  REQUIRE(r.contacts.at(1).impacts == 1);
  SeismicJointOptions o;
  o.tol = 1e-2;
  const SeismicJoint j = seismic_joint(s, o);
  std::string notes;
  for (const auto& n : j.notes) notes += n + "\n";
  INFO(notes);
  CHECK(notes.find("contact 2 (floors 3, 3) pounds (1 impact)") != std::string::npos);
  CHECK(notes.find("1 impacts") == std::string::npos);
}

namespace {

// The two frames with a second pair, at floors 2 (no contact laws on either: the response
// does not depend on the gaps), over the first 10 s of the record.
BuildingScene two_pairs_scene() { return frames_with_contact("joint_two_pairs", "floors = [2, 2]\ngap = 0.05\n", {"solver.t_end=10"}); }

}  // namespace

TEST_CASE("seismic joint of every pair at once: the uniform joint is the largest pair's own", "[joint]") {
  const BuildingScene scene = two_pairs_scene();
  REQUIRE(scene.structure.contacts.size() == 2);
  SeismicJointOptions every;
  every.contact = 0;
  const SeismicJoint all = seismic_joint(scene, every);
  REQUIRE(all.every_pair);
  REQUIRE(all.pairs.size() == 2);
  CHECK(all.gap_key == "contact.*.gap");
  // Each pair sized alone (the other keeps its gap and no law: the same response) gives that
  // pair's s_max bit for bit, and its own bisection agrees with it.
  for (int c = 1; c <= 2; ++c) {
    SeismicJointOptions one;
    one.contact = c;
    const SeismicJoint alone = seismic_joint(scene, one);
    check_agreement(alone);
    CHECK(all.pairs[static_cast<std::size_t>(c - 1)].s_max == alone.s_max);
    CHECK(all.pairs[static_cast<std::size_t>(c - 1)].t_critical == alone.t_critical);
    CHECK(all.pairs[static_cast<std::size_t>(c - 1)].floor_a == alone.floor_a);
    CHECK(all.pairs[static_cast<std::size_t>(c - 1)].srss == alone.srss);
  }
  // The uniform joint: the bisection over one gap for both pairs finds the larger s_max.
  const double largest = std::max(all.pairs[0].s_max, all.pairs[1].s_max);
  CHECK(all.s_max == largest);
  CHECK(all.contact == (all.pairs[0].s_max >= all.pairs[1].s_max ? 1 : 2));
  CHECK(all.agree);
  CHECK(all.joint >= largest);
  CHECK(all.joint - largest <= all.tol);
  // At joint + tol neither pair touches; at the smaller pair's s_max the larger one does.
  BuildingScene s = scene;
  for (auto& pair : s.structure.contacts) pair.gap = all.joint + all.tol;
  const Report wide = run(s);
  CHECK_FALSE(wide.contacts.at(0).contact);
  CHECK_FALSE(wide.contacts.at(1).contact);
  for (auto& pair : s.structure.contacts) pair.gap = 0.999 * std::min(all.pairs[0].s_max, all.pairs[1].s_max);
  const Report narrow = run(s);
  CHECK((narrow.contacts.at(0).contact || narrow.contacts.at(1).contact));
}

TEST_CASE("adjoin joint --contact all writes every pair's joint, and a bad --contact is named", "[joint][cli]") {
  const fs::path dir = fs::path(ADJOIN_TEST_TMP) / ("joint_all_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto r = adjoin::test::run_cli("joint '" + kFrames.string() +
                                       "' --set solver.t_end=10 --contact all --tol 1e-4 --out '" + dir.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("minimum uniform seismic joint of two-frames-one-damper (contact.*.gap, every pair") != std::string::npos);
  CHECK(r.out.find("contact 1, floors A3-B3: its own joint s_max") != std::string::npos);
  std::ifstream in(dir / "joint.json");
  const auto json = nlohmann::json::parse(in);
  CHECK(json["every_pair"].get<bool>());
  REQUIRE(json["pairs"].size() == 1);
  const SeismicJoint one = seismic_joint(frames_scene(), [] { SeismicJointOptions o; o.tol = 1e-4; return o; }());
  CHECK(json["pairs"][0]["s_max"].get<double>() == Approx(one.s_max).epsilon(1e-12));
  CHECK(json["joint"].get<double>() == Approx(one.joint).epsilon(1e-12));
  fs::remove_all(dir);
  for (const std::string bad : {"0", "x", "2", "1x"}) {
    const auto b = adjoin::test::run_cli("joint '" + kFrames.string() + "' --set solver.t_end=1 --contact " + bad + " --out '" +
                                         dir.string() + "'");
    INFO(bad << ": " << b.err);
    CHECK(b.status == 2);
    CHECK(b.err.find("--contact " + bad) != std::string::npos);
  }
}

