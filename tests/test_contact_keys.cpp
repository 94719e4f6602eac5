// The scene keys of the contact laws (SPEC §6): a building scene's [[contact]] tables, their
// --set edits, and the two-block [model.contact] table as the structure sees it and as a sweep
// edits it. Each rule of README "Buildings" is checked with the message naming the file, line
// and key.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/structure/building.hpp"
#include "adjoin/study/sweep.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;
using structure::ContactModel;

namespace {

// Two frames with one contact pair at floor 3; `keys` is appended to the [[contact]] table,
// which starts on line 9 (floors on line 10, gap on 11, the first of `keys` on 12).
std::string building(const std::string& keys) {
  return "[model]\nunits = \"SI\"\n\n"
         "[building.A]\nstoreys = 3\nmass = 4.0e4\nstiffness = 5.0e6\n\n"
         "[[contact]]\nfloors = [3, 3]\ngap = 0.05\n" + keys +
         "\n[building.B]\nstoreys = 3\nmass = 5.0e4\nstiffness = 4.0e6\n";
}

structure::ContactLaw law_of(const std::string& keys, const std::vector<std::string>& sets = {},
                             const std::vector<std::string>& unsets = {}) {
  const structure::Structure s = parse_structure(building(keys), "b.toml", sets, unsets);
  REQUIRE(s.contacts.size() == 1);
  return s.contacts[0].law;
}

std::string error_of(const std::string& keys, const std::vector<std::string>& sets = {}) {
  try {
    parse_structure(building(keys), "b.toml", sets, {});
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("expected an InputError for: " + keys);
  return {};
}

bool has(const std::string& text, const std::string& part) {
  INFO(text);
  return text.find(part) != std::string::npos;
}

const std::string kStrong = test::slurp(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml");

}  // namespace

TEST_CASE("contact keys: a [[contact]] without a model keeps today's behaviour", "[contact_keys]") {
  const structure::ContactLaw law = law_of("");
  CHECK(law.model == ContactModel::none);
  CHECK_FALSE(law.compliant());
  CHECK(law_of("model = \"none\"\n").model == ContactModel::none);
}

TEST_CASE("contact keys: each model reads its keys in SI units", "[contact_keys]") {
  SECTION("linear with restitution") {
    const auto law = law_of("model = \"linear\"\nstiffness = 4.0e8\nrestitution = 0.65\n");
    CHECK(law.model == ContactModel::linear);
    CHECK(law.stiffness == 4.0e8);
    CHECK(law.restitution == 0.65);
    CHECK(std::isnan(law.damping));
    CHECK_FALSE(law.tension_cut);
    CHECK(law.damping_parameter() == Approx(-std::log(0.65) / std::sqrt(M_PI * M_PI + std::log(0.65) * std::log(0.65))));
  }
  SECTION("linear with the damping ratio and the tension cut") {
    const auto law = law_of("model = \"linear\"\nstiffness = 4.0e8\ndamping = 0.1\ntension_cut = true\n");
    CHECK(law.damping == 0.1);
    CHECK(law.damping_parameter() == 0.1);
    CHECK(law.tension_cut);
    CHECK(law.restitution == 1.0);
  }
  SECTION("hertz") {
    const auto law = law_of("model = \"hertz\"\nstiffness = 2.0e9\n");
    CHECK(law.model == ContactModel::hertz);
    CHECK(law.stiffness == 2.0e9);
  }
  SECTION("hertzdamp and jankowski") {
    const auto h = law_of("model = \"hertzdamp\"\nstiffness = 2.0e9\nrestitution = 0.65\n");
    CHECK(h.model == ContactModel::hertzdamp);
    CHECK(h.damping_parameter() == Approx(8.0 * 0.35 / (5.0 * 0.65)));
    const auto j = law_of("model = \"jankowski\"\nstiffness = 2.0e9\ndamping = 0.3\n");
    CHECK(j.model == ContactModel::jankowski);
    CHECK(j.damping == 0.3);
  }
  SECTION("impact") {
    const auto law = law_of("model = \"impact\"\nrestitution = 0.5\n");
    CHECK(law.model == ContactModel::impact);
    CHECK(law.restitution == 0.5);
    CHECK_FALSE(law.compliant());
  }
}

TEST_CASE("contact keys: every rule is named with the file, line and key", "[contact_keys][errors]") {
  // The [[contact]] table is on line 9, the first added key on line 12.
  CHECK(has(error_of("stiffness = 1e8\n"), "b.toml:12: contact[1].stiffness: a key of a contact law, but the contact has no model: set contact[1].model"));
  CHECK(has(error_of("model = \"none\"\nrestitution = 0.5\n"), "b.toml:13: contact[1].restitution: a key of a contact law"));
  CHECK(has(error_of("model = \"elastic\"\n"), "b.toml:12: contact[1].model: expected one of \"none\", \"linear\""));
  CHECK(has(error_of("model = \"linear\"\nrestitution = 0.5\n"), "b.toml:9: contact[1]: missing key stiffness"));
  CHECK(has(error_of("model = \"hertz\"\n"), "contact[1]: missing key stiffness: the hertz model needs its contact stiffness k (a positive number, N/m^1.5)"));
  CHECK(has(error_of("model = \"linear\"\nstiffness = 1e8\n"), "b.toml:9: contact[1]: missing key restitution or damping"));
  CHECK(has(error_of("model = \"jankowski\"\nstiffness = 1e9\n"), "contact[1]: missing key restitution or damping"));
  const std::string both = error_of("model = \"hertzdamp\"\nstiffness = 1e9\nrestitution = 0.5\ndamping = 0.2\n");
  CHECK(has(both, "b.toml:15: contact[1].damping: give restitution or damping, not both"));
  CHECK(has(error_of("model = \"impact\"\n"), "b.toml:9: contact[1]: missing key restitution"));
  CHECK(has(error_of("model = \"impact\"\nrestitution = 0.5\nstiffness = 1e9\n"), "b.toml:14: contact[1].stiffness: the impact model (Newton's law) has no stiffness"));
  CHECK(has(error_of("model = \"impact\"\nrestitution = 0.5\ndamping = 0.1\n"), "b.toml:14: contact[1].damping: the impact model"));
  CHECK(has(error_of("model = \"hertz\"\nstiffness = 1e9\nrestitution = 0.5\n"), "b.toml:14: contact[1].restitution: the hertz model is elastic"));
  CHECK(has(error_of("model = \"hertz\"\nstiffness = 1e9\ndamping = 0.5\n"), "b.toml:14: contact[1].damping: the hertz model is elastic"));
  CHECK(has(error_of("model = \"hertzdamp\"\nstiffness = 1e9\nrestitution = 0.5\ntension_cut = true\n"), "b.toml:15: contact[1].tension_cut: only the linear model"));
  CHECK(has(error_of("model = \"linear\"\nstiffness = 1e8\nrestitution = 0.5\ntension_cut = 1\n"), "b.toml:15: contact[1].tension_cut: expected true or false"));
  // Values.
  CHECK(has(error_of("model = \"linear\"\nstiffness = -1e8\nrestitution = 0.5\n"), "b.toml:13: contact[1].stiffness: expected a positive contact stiffness (N/m)"));
  CHECK(has(error_of("model = \"linear\"\nstiffness = \"stiff\"\nrestitution = 0.5\n"), "b.toml:13: contact[1].stiffness: expected a finite number"));
  CHECK(has(error_of("model = \"linear\"\nstiffness = 1e8\nrestitution = 0\n"), "b.toml:14: contact[1].restitution: expected a coefficient of restitution e with 0 < e <= 1"));
  CHECK(has(error_of("model = \"impact\"\nrestitution = 1.2\n"), "contact[1].restitution: expected a coefficient of restitution"));
  CHECK(has(error_of("model = \"linear\"\nstiffness = 1e8\ndamping = 1.0\n"), "b.toml:14: contact[1].damping: expected the damping ratio zeta, 0 <= zeta < 1"));
  CHECK(has(error_of("model = \"jankowski\"\nstiffness = 1e9\ndamping = -0.1\n"), "contact[1].damping: expected the damping ratio xi >= 0"));
  CHECK(has(error_of("model = \"linear\"\nstiffness = 1e8\nrestitution = 0.5\nrestitutoin = 0.5\n"), "b.toml:15: contact[1].restitutoin: unknown key"));
}

TEST_CASE("contact keys: --set edits give what editing the file gives", "[contact_keys][structure_edits]") {
  SECTION("a model and its keys on a contact without one") {
    const auto law = law_of("", {"contact.1.model=hertzdamp", "contact.1.stiffness=2e9", "contact.1.restitution=0.65"});
    CHECK(law.model == ContactModel::hertzdamp);
    CHECK(law.stiffness == 2.0e9);
    CHECK(law.restitution == 0.65);
  }
  SECTION("restitution and damping replace each other") {
    const std::string linear = "model = \"linear\"\nstiffness = 1e8\n";
    auto law = law_of(linear + "damping = 0.2\n", {"contact.1.restitution=0.7"});
    CHECK(law.restitution == 0.7);
    CHECK(std::isnan(law.damping));
    law = law_of(linear + "restitution = 0.7\n", {"contact.1.damping=0.05"});
    CHECK(law.damping == 0.05);
  }
  SECTION("a model drops the keys it does not take") {
    const std::string keys = "model = \"linear\"\nstiffness = 1e8\nrestitution = 0.6\ntension_cut = true\n";
    auto law = law_of(keys, {"contact.1.model=impact"});
    CHECK(law.model == ContactModel::impact);
    CHECK(law.restitution == 0.6);
    law = law_of(keys, {"contact.1.model=\"hertz\"", "contact.1.stiffness=3e9"});
    CHECK(law.model == ContactModel::hertz);
    CHECK(law.stiffness == 3e9);
    CHECK(law_of(keys, {"contact.1.model=none"}).model == ContactModel::none);
  }
  SECTION("a key another --set put there is not dropped: the contradiction is reported") {
    const std::string e = error_of("", {"contact.1.restitution=0.5", "contact.1.model=hertz", "contact.1.stiffness=1e9"});
    CHECK(has(e, "--set contact.1.restitution=0.5: contact[1].restitution: the hertz model is elastic"));
    const std::string both = error_of("model = \"linear\"\nstiffness = 1e8\n", {"contact.1.damping=0.1", "contact.1.restitution=0.5"});
    CHECK(has(both, "contact[1].damping: give restitution or damping, not both"));
  }
  SECTION("bad values are blamed on the --set") {
    CHECK(has(error_of("model = \"impact\"\nrestitution = 0.5\n", {"contact.1.restitution=2"}),
              "--set contact.1.restitution=2: contact[1].restitution: expected a coefficient of restitution"));
    CHECK(has(error_of("", {"contact.1.model=linear"}), "contact[1]: missing key stiffness"));
    CHECK(has(error_of("", {"contact.1.stiffness=1e8"}), "--set contact.1.stiffness=1e8: contact[1].stiffness: a key of a contact law, but the contact has no model"));
  }
}

TEST_CASE("contact keys: --unset of the model leaves law keys that are refused", "[contact_keys][structure_edits]") {
  try {
    parse_structure(building("model = \"impact\"\nrestitution = 0.5\n"), "b.toml", {}, {"contact.1.model"});
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(has(e.what(), "b.toml:13: contact[1].restitution: a key of a contact law, but the contact has no model: set contact[1].model"));
  }
}

TEST_CASE("contact keys: a two-block SI scene's law reaches the structure in N/m and N/m^1.5", "[contact_keys][units]") {
  const std::string si = R"(
[model]
units = "SI"
m1 = 2.0e5
m2 = 4.0e5
k1 = 8.0e6
k2 = 1.6e7
slip_force = 2.0e5
gap0 = 0.1
[model.rod1]
elastic = true
[model.rod2]
elastic = true
[model.contact]
model = "hertzdamp"
stiffness = 2.0e9
restitution = 0.65
[ground]
source = "decaying-sine"
u0 = 0.1
omega = 5.0
k = 0.5
[solver]
h = 0.01
t_end = 1.0
)";
  const Scene scene = parse_scene(si, "si.toml");
  // X0 = m1 g / k1 = 0.24516625 m, F0 = m1 g = 1961330 N: F0 / X0^1.5 = 16156959.8168 N/m^1.5.
  CHECK(two_block_model(scene).contact.stiffness == Approx(2.0e9 / 16156959.816820417).epsilon(1e-12));
  const structure::Structure s = structure_of(scene);
  REQUIRE(s.contacts.size() == 1);
  CHECK(s.contacts[0].gap == Approx(0.1).epsilon(1e-14));
  CHECK(s.contacts[0].law.model == ContactModel::hertzdamp);
  CHECK(s.contacts[0].law.stiffness == Approx(2.0e9).epsilon(1e-12));
  CHECK(s.contacts[0].law.restitution == 0.65);
  const Scene linear = parse_scene(si, "si.toml", {"model.contact.model=linear", "model.contact.stiffness=4e8"});
  CHECK(two_block_model(linear).contact.stiffness == Approx(50.0).epsilon(1e-14));  // 4e8 N/m / k1
  CHECK(structure_of(linear).contacts[0].law.stiffness == Approx(4.0e8).epsilon(1e-14));
}

TEST_CASE("contact keys: a two-block sweep edits model.contact keys on an axis", "[contact_keys][sweep]") {
  const std::filesystem::path folder = std::filesystem::path(ADJOIN_TEST_TMP) / "contact-sweep";
  std::filesystem::create_directories(folder);
  const std::string implicit = "scheme = \"implicit\"";
  std::string base = kStrong;
  base.replace(base.find("scheme = \"paper\""), std::string("scheme = \"paper\"").size(), implicit);
  std::ofstream(folder / "base.toml") << base << "\n[model.contact]\nmodel = \"linear\"\nstiffness = 100.0\ndamping = 0.1\n";
  const std::string text =
      "base = \"base.toml\"\n"
      "[[axis]]\nkey = \"model.contact.stiffness\"\nvalues = [1000.0, 2000.0]\n"
      "[[axis]]\nkey = \"model.contact.restitution\"\nvalues = [0.5, 0.9]\n";
  const SweepSpec spec = parse_sweep(text, (folder / "sweep.toml").string());
  const Scene first = sweep_scene(spec, 0);
  CHECK(two_block_model(first).contact.model == ContactModel::linear);
  CHECK(two_block_model(first).contact.stiffness == 1000.0);
  CHECK(two_block_model(first).contact.restitution == 0.5);
  CHECK(std::isnan(two_block_model(first).contact.damping));  // the axis' restitution replaced it
  const Scene last = sweep_scene(spec, 3);
  CHECK(two_block_model(last).contact.stiffness == 2000.0);
  CHECK(two_block_model(last).contact.restitution == 0.9);

  const std::string bad = "base = \"base.toml\"\n"
                          "[[axis]]\nkey = \"model.contact.restitution\"\nvalues = [0.5, 1.5]\n";
  const SweepSpec bad_spec = parse_sweep(bad, (folder / "bad.toml").string());
  try {
    sweep_scene(bad_spec, 1);
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(has(e.what(), "model.contact.restitution: expected a coefficient of restitution"));
  }
}
