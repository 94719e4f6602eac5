// Edits of a building scene's structure by dotted path (--set, --unset, sweeps' edits): each
// gives the structure that editing the scene file by hand gives, and a value an edit put there
// is blamed on the edit.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "cli_helpers.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/modal.hpp"

using namespace adjoin;

namespace {

// Two frames, a device on A, two links and a contact; `extra` is put into building B's table,
// `link1` replaces the first link's keys.
std::string scene(const std::string& b_stiffness = "stiffness = 3.0e6",
                  const std::string& link1 = "slip_ratio = 0.05\nof = \"B\"", bool second_link = true) {
  std::string s =
      "[model]\nunits = \"SI\"\n\n"
      "[building.A]\nstoreys = 4\nmass = 4.0e4\nstiffness = 5.0e6\ndamping = { model = \"modal\", ratio = 0.05 }\n"
      "[[building.A.device]]\ntype = \"dashpot\"\nstoreys = [1, 2]\nc = 1.0e5\n"
      "[[building.A.device]]\ntype = \"spring\"\nstoreys = [3]\nstiffness = 1.0e6\n\n"
      "[building.B]\nstoreys = 3\nmass = 5.0e4\n" + b_stiffness + "\ndamping = { model = \"rayleigh\", ratio = 0.05 }\n\n"
      "[[link]]\nfloors = [3, 3]\ntype = \"friction\"\n" + link1 + "\n";
  if (second_link) s += "\n[[link]]\nfloors = [2, 2]\ntype = \"dashpot\"\nc = 2.0e5\n";
  s += "\n[[contact]]\nfloors = [3, 3]\ngap = 0.05\n";
  return s;
}

void same(const structure::Structure& x, const structure::Structure& y) {
  CHECK(x.a.masses == y.a.masses);
  CHECK(x.a.springs == y.a.springs);
  REQUIRE(x.b.has_value() == y.b.has_value());
  if (x.b) {
    CHECK(x.b->masses == y.b->masses);
    CHECK(x.b->springs == y.b->springs);
    CHECK(x.b->damping.ratio == y.b->damping.ratio);
  }
  CHECK(x.a.devices.size() == y.a.devices.size());
  REQUIRE(x.links.size() == y.links.size());
  for (std::size_t i = 0; i < x.links.size(); ++i) {
    CHECK(x.links[i].type == y.links[i].type);
    CHECK(x.links[i].slip_force == y.links[i].slip_force);
    CHECK(x.links[i].c == y.links[i].c);
    CHECK(x.links[i].floor_a == y.links[i].floor_a);
  }
  CHECK(x.contacts.size() == y.contacts.size());
}

}  // namespace

TEST_CASE("structure edits give what editing the file gives", "[structure_edits]") {
  SECTION("a friction link's slip ratio, and a slip force replacing it") {
    same(parse_structure(scene(), "s", {"link.1.slip_ratio=0.1"}, {}),
         parse_structure(scene("stiffness = 3.0e6", "slip_ratio = 0.1\nof = \"B\""), "s"));
    const auto forced = parse_structure(scene(), "s", {"link.1.slip_force=12345.0"}, {});
    same(forced, parse_structure(scene("stiffness = 3.0e6", "slip_force = 12345.0"), "s"));
    CHECK(forced.links[0].slip_force == 12345.0);
    // The ratio is of B's weight: 0.05 * 3 floors * 5e4 kg * g.
    CHECK(parse_structure(scene(), "s").links[0].slip_force == Approx(0.05 * 1.5e5 * kStandardGravity).epsilon(1e-15));
  }
  SECTION("a period replacing the stiffness hits its period") {
    const auto s = parse_structure(scene(), "s", {"building.B.period=0.6"}, {});
    same(s, parse_structure(scene("period = 0.6"), "s"));
    CHECK(structure::building_modes(*s.b).periods[0] == Approx(0.6).epsilon(1e-12));
  }
  SECTION("unsets of a numbered link, of every link, of a device") {
    same(parse_structure(scene(), "s", {}, {"link.2"}), parse_structure(scene("stiffness = 3.0e6", "slip_ratio = 0.05\nof = \"B\"", false), "s"));
    CHECK(parse_structure(scene(), "s", {}, {"link"}).links.empty());
    const auto s = parse_structure(scene(), "s", {}, {"building.A.device.1"});
    REQUIRE(s.a.devices.size() == 1);
    CHECK(s.a.devices[0].type == structure::DeviceType::spring);
  }
  SECTION("a numbered device's value, the storey count and the inline damping table") {
    const auto s = parse_structure(scene(), "s", {"building.A.device.1.c=3e5", "building.A.storeys=6", "building.B.damping.ratio=0.02"}, {});
    CHECK(s.a.devices[0].c == 3e5);
    CHECK(s.a.floors() == 6);
    CHECK(s.b->damping.ratio == 0.02);
  }
  SECTION("a new type drops the old type's keys: a friction link made a dashpot, a dashpot device made a spring") {
    // The file edited by hand: the first link a dashpot, the first device a spring.
    std::string by_hand = scene("stiffness = 3.0e6", "c = 1.5e5\nalpha = 0.4");
    const std::string friction = "type = \"friction\"\nc = 1.5e5";
    by_hand.replace(by_hand.find(friction), friction.size(), "type = \"dashpot\"\nc = 1.5e5");
    const std::string dashpot = "type = \"dashpot\"\nstoreys = [1, 2]\nc = 1.0e5";
    by_hand.replace(by_hand.find(dashpot), dashpot.size(), "type = \"spring\"\nstoreys = [1, 2]\nstiffness = 2.0e6");
    const auto edited = parse_structure(scene(), "s",
                                        {"link.1.type=dashpot", "link.1.c=1.5e5", "link.1.alpha=0.4",
                                         "building.A.device.1.type=spring", "building.A.device.1.stiffness=2.0e6"},
                                        {});
    const auto file = parse_structure(by_hand, "s");
    same(edited, file);
    CHECK(edited.links[0].type == structure::LinkType::dashpot);
    CHECK(edited.links[0].alpha == file.links[0].alpha);
    CHECK(edited.a.devices[0].type == structure::DeviceType::spring);
    CHECK(edited.a.devices[0].k == 2.0e6);
    // The edit's order does not matter: c set before the type is kept.
    same(parse_structure(scene(), "s", {"link.1.c=1.5e5", "link.1.alpha=0.4", "link.1.type=dashpot"}, {}), file);
    // A type set to the one it has keeps its keys.
    same(parse_structure(scene(), "s", {"link.1.type=friction"}, {}), parse_structure(scene(), "s"));
  }
  SECTION("a --set of the next number adds a link, a device, a contact") {
    const auto s = parse_structure(scene("stiffness = 3.0e6", "slip_ratio = 0.05\nof = \"B\"", false), "s",
                                   {"link.2.floors=[2, 2]", "link.2.type=dashpot", "link.2.c=2.0e5",
                                    "building.A.device.3.type=spring", "building.A.device.3.storeys=[4]",
                                    "building.A.device.3.stiffness=1.0e6", "contact.2.floors=[1, 1]", "contact.2.gap=0.1"},
                                   {});
    same(s, parse_structure(scene(), "s", {"contact.2.floors=[1, 1]", "contact.2.gap=0.1", "building.A.device.3.type=spring",
                                           "building.A.device.3.storeys=[4]", "building.A.device.3.stiffness=1.0e6"}, {}));
    REQUIRE(s.a.devices.size() == 3);
    CHECK(s.a.devices[2].storeys == std::vector<int>{4});
    REQUIRE(s.contacts.size() == 2);
    CHECK(s.contacts[1].gap == 0.1);
    // With no link at all, link.1 makes the first.
    const auto first = parse_structure(scene(), "s", {"link.1.floors=[1, 1]", "link.1.type=spring", "link.1.stiffness=1e6"}, {"link"});
    REQUIRE(first.links.size() == 1);
    CHECK(first.links[0].type == structure::LinkType::spring);
  }
  SECTION("unset first, then set, in that order") {
    const auto s = parse_structure(scene(), "s", {"link.1.c=7e4"}, {"link.1"});  // the dashpot is link 1 now
    REQUIRE(s.links.size() == 1);
    CHECK(s.links[0].type == structure::LinkType::dashpot);
    CHECK(s.links[0].c == 7e4);
  }
}

TEST_CASE("structure edits: mistakes are named by the edit or by the file line", "[structure_edits]") {
  auto message = [](const std::vector<std::string>& sets, const std::vector<std::string>& unsets) {
    try {
      parse_structure(scene(), "s.toml", sets, unsets);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // link.3 adds a third link (one more than the scene has), which then lacks its keys; link.4
  // is not the next one.
  CHECK(message({"link.3.c=1"}, {}) == "--set link.3.c=1: link[3].floors: expected 2 whole numbers (link[3] is a table --set added)");
  CHECK(message({"link.4.c=1"}, {}) ==
        "--set link.4.c=1: the scene has 2 [[link]] tables, not a number 4 (a --set adds the next one, number 3)");
  CHECK(message({"link.0.c=1"}, {}) == "--set link.0.c=1: the scene has 2 [[link]] tables, not a number 0");
  CHECK(message({"building.A.damping.ratio=1"}, {}).rfind("--set building.A.damping.ratio=1: building.A.damping.ratio: expected", 0) == 0);
  CHECK(message({"link.2.c=-5"}, {}) == "--set link.2.c=-5: link[2].c: expected a positive number");
  // A value the edit did not touch keeps its file line.
  CHECK(message({"building.A.storeys=2"}, {}).rfind("s.toml:", 0) == 0);
  CHECK(message({}, {"contact.2"}) == "--unset contact.2: the scene has 1 [[contact]] table, no number 2 to remove");
  CHECK(message({}, {"building.A.nothing"}) == "--unset building.A.nothing: the scene has no key or section building.A.nothing");
}

namespace {

// Two frames under the paper's decaying sine (SI: u0 in m), with `solver` lines added.
std::string building_run_scene(const std::string& solver = "") {
  return "[model]\nunits = \"SI\"\n\n[building.A]\nstoreys = 3\nmass = 4e4\nstiffness = 5e6\n\n"
         "[building.B]\nstoreys = 3\nmass = 5e4\nstiffness = 4e6\n\n"
         "[ground]\nsource = \"decaying-sine\"\nu0 = 0.1\nomega = 6.0\nk = 0.3\n\n"
         "[solver]\nh = 0.005\nt_end = 1.0\n" + solver;
}

std::string building_message(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parse_building_scene(text, "b.toml", sets, {});
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("building scenes: solver.scheme picks the structure step's restart rule, the two-block schemes are refused",
          "[structure_edits][building]") {
  using Restart = StructureSolverOptions::Restart;
  CHECK(parse_building_scene(building_run_scene(), "b.toml", {}, {}).solver.restart == Restart::automatic);
  CHECK(parse_building_scene(building_run_scene("scheme = \"implicit\"\n"), "b.toml", {}, {}).solver.restart == Restart::automatic);
  const BuildingScene damped = parse_building_scene(building_run_scene("scheme = \"implicit-damped\"\n"), "b.toml", {}, {});
  CHECK(damped.solver.restart == Restart::always);
  CHECK(std::string(scheme_name(damped.solver)) == "implicit-damped");
  CHECK_THAT(building_message(building_run_scene("scheme = \"paper\"\n")),
             Catch::StartsWith("b.toml:23: solver.scheme = \"paper\": a building scene runs the structure step"));
  CHECK_THAT(building_message(building_run_scene(), {"solver.scheme=implicit-gl"}),
             Catch::StartsWith("--set solver.scheme=implicit-gl: solver.scheme = \"implicit-gl\""));
}

TEST_CASE("an SI building scene describes its ground in SI units, as written", "[structure_edits][building]") {
  const BuildingScene b = parse_building_scene(building_run_scene(), "b.toml", {}, {});
  CHECK(b.ground->describe() == "decaying-sine u0=0.1 m omega=6 rad/s k=0.3 1/s");
  // and runs it as that motion: a_g = u0 omega^2 e^{-k t} sin(omega t) [m/s^2]
  const double t = 0.2;
  CHECK(b.ground->ag(t) * kStandardGravity == Approx(0.1 * 36.0 * std::exp(-0.3 * t) * std::sin(6.0 * t)).epsilon(1e-12));
}

TEST_CASE("a building run's summary says the scheme it ran and the ground in SI", "[structure_edits][building][cli]") {
  const auto scene = adjoin::test::write_temp("scheme-summary.toml", building_run_scene("scheme = \"implicit-damped\"\n"));
  const auto out = std::filesystem::path(ADJOIN_TEST_TMP) / "scheme-summary";
  const auto r = adjoin::test::run_cli("run '" + scene.string() + "' --out '" + out.string() + "' --quiet");
  REQUIRE(r.status == 0);
  const std::string summary = adjoin::test::slurp(out / "summary.json");
  CHECK_THAT(summary, Catch::Contains("\"scheme\": \"implicit-damped\""));
  CHECK_THAT(summary, Catch::Contains("u0=0.1 m"));
  std::filesystem::remove_all(out);
}

TEST_CASE("building values are range-checked up front, naming the key, the bound and the --set", "[structure_edits][building]") {
  auto message = [](const std::vector<std::string>& sets) {
    try {
      parse_structure(scene(), "s.toml", sets, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message({"building.A.mass=1e300"}) ==
        "--set building.A.mass=1e300: building.A.mass: 1e+300 is outside the supported 0.001 to 1e+12 kg (bounds that keep "
        "the step's matrices finite and well conditioned)");
  CHECK(message({"building.A.mass=1e5", "building.A.mass=-1"}) == "--set building.A.mass=-1: building.A.mass: expected a positive number");
  // The period's bound is the stiffness's, said as periods for these masses (k ~ 1 / T^2).
  const std::string shortest = message({"building.B.period=1e-300"});
  CHECK_THAT(shortest, Catch::StartsWith("--set building.B.period=1e-300: building.B.period: 1e-300 s is outside the supported "));
  CHECK_THAT(shortest, Catch::Contains("s for these floor masses"));
  CHECK_THAT(message({"building.B.period=1e300"}), Catch::Contains("s for these floor masses"));
  // Periods at the bounds the message states are accepted: k(T) = k(1 s) / T^2.
  const double k1 = structure::stiffness_for_period(Eigen::VectorXd::Constant(3, 5.0e4), 1.0);
  const double longest = std::sqrt(k1 / 1e-3) * (1 - 1e-9), shortest_ok = std::sqrt(k1 / 1e15) * (1 + 1e-9);
  CHECK(message({"building.B.period=" + std::to_string(longest)}) == "no error");
  char text[64];
  std::snprintf(text, sizeof text, "building.B.period=%.17g", shortest_ok);
  CHECK(message({text}) == "no error");
  CHECK_THAT(message({"building.A.device.1.c=1e300"}), Catch::StartsWith("--set building.A.device.1.c=1e300: building.A.device[1].c: 1e+300"));
  CHECK_THAT(message({"link.2.c=1e16"}), Catch::Contains("outside the supported 0.001 to 1e+15 N s/m"));
  CHECK(message({"link.2.c=1e15"}) == "no error");
}

TEST_CASE("keys that do not apply, repeated storeys and --set without = are refused", "[structure_edits]") {
  auto message = [](const std::string& text, const std::vector<std::string>& sets) {
    try {
      parse_structure(text, "s.toml", sets, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message(scene(), {"building.A.mass"}) == "--set building.A.mass: expected KEY=VALUE with a dotted key, e.g. building.A.mass=4.5e4");
  CHECK(message(scene(), {"building.A.device.1.storeys=[2, 2]"}) ==
        "--set building.A.device.1.storeys=[2, 2]: building.A.device[1].storeys: 2 is listed twice; list each storey once");
  CHECK(message(scene(), {"building.A.device.1.storeys=[]"}).find("at least one storey") != std::string::npos);
  CHECK_THAT(message(scene(), {"building.A.damping={ model = \"none\", ratio = 0.05 }"}),
             Catch::Contains("building.A.damping.ratio: does not apply to the model \"none\""));
  CHECK_THAT(message(scene(), {"building.A.damping.modes=[1, 2]"}),
             Catch::Contains("building.A.damping.modes: does not apply to the model \"modal\""));
  CHECK_THAT(message(scene("stiffness = 3.0e6", "slip_force = 1e4\nof = \"B\""), {}),
             Catch::StartsWith("s.toml:28: link[1].of: of names the building"));
  // Long keys are quoted as excerpts.
  const std::string long_key = "building.A." + std::string(100000, 'x');
  const std::string m = message(scene(), {long_key + "=1"});
  CHECK(m.size() < 400);
  CHECK_THAT(m, Catch::StartsWith("--set \"building.A.xxx"));
}
