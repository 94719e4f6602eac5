// Edits of a building scene's structure by dotted path (--set, --unset, sweeps' edits): each
// gives the structure that editing the scene file by hand gives, and a value an edit put there
// is blamed on the edit.
#include <catch2/catch.hpp>

#include <string>

#include "adjoin/errors.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/model/units.hpp"
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
  CHECK(message({"link.3.c=1"}, {}) == "--set link.3.c=1: the scene has 2 [[link]] tables, not a number 3");
  CHECK(message({"link.0.c=1"}, {}) == "--set link.0.c=1: the scene has 2 [[link]] tables, not a number 0");
  CHECK(message({"building.A.damping.ratio=1"}, {}).rfind("--set building.A.damping.ratio=1: building.A.damping.ratio: expected", 0) == 0);
  CHECK(message({"link.2.c=-5"}, {}) == "--set link.2.c=-5: link[2].c: expected a positive number");
  // A value the edit did not touch keeps its file line.
  CHECK(message({"building.A.storeys=2"}, {}).rfind("s.toml:", 0) == 0);
  CHECK(message({}, {"contact.2"}) == "--unset contact.2: the scene has 1 [[contact]] tables");
  CHECK(message({}, {"building.A.nothing"}) == "--unset building.A.nothing: the scene has no key or section building.A.nothing");
}
