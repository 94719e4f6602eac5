// core/errors: an InputError names the field it is about (InputError::field), in one spelling
// whichever reader found it (a scene line, a --set, the builder), so that code which must know
// the field (a sweep pointing at the axis value that set it) never reads the message.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/scene.hpp"
#include "cli_helpers.hpp"

using namespace adjoin;

namespace {

// The field of the InputError `load` throws ("" if it throws another error or none).
template <typename Load>
std::string field_of(Load&& load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.field();
  }
  return "(no error)";
}

const std::string kPaper = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml";
const std::string kFrames = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";

}  // namespace

TEST_CASE("field_path writes a scene's dotted key with list items in brackets", "[errors]") {
  CHECK(field_path("solver.h") == "solver.h");
  CHECK(field_path("link.1.slip_force") == "link[1].slip_force");
  CHECK(field_path("building.A.masses.2") == "building.A.masses[2]");
  CHECK(field_path("contact.12") == "contact[12]");
  CHECK(field_path("model") == "model");
  CHECK(field_path("") == "");
}

TEST_CASE("a two-block scene's errors name their field, from the file or from a --set", "[errors]") {
  CHECK(field_of([] { load_scene(kPaper, {"solver.h=-1"}); }) == "solver.h");
  CHECK(field_of([] { load_scene(kPaper, {"model.rod1.order=2"}); }) == "model.rod1.order");
  CHECK(field_of([] { load_scene(kPaper, {}, {"model.mu"}); }) == "model.mu");  // a missing key
  CHECK(field_of([] { load_scene(kPaper, {}, {"solver.nothing"}); }) == "solver.nothing");  // --unset of no key
  CHECK(field_of([] { load_scene(kPaper, {"solver.h.x=1"}); }) == "solver.h.x");  // h is not a table
}

TEST_CASE("a building scene's errors name their field in the builder's spelling", "[errors]") {
  CHECK(field_of([] { load_building_scene(kFrames, {"building.A.perod=1.0"}); }) == "building.A.perod");
  CHECK(field_of([] { load_building_scene(kFrames, {"link.1.slip_force=-1"}); }) == "link[1].slip_force");
  CHECK(field_of([] { load_building_scene(kFrames, {"link.3.slip_ratio=0.1"}); }) == "link[3].slip_ratio");  // (link.2 would add one)
  CHECK(field_of([] { load_building_scene(kFrames, {}, {"link.9"}); }) == "link[9]");
}

TEST_CASE("a sweep points at the line of the axis value whose edit is the error's field", "[errors]") {
  // Two axes: the second's value sets a key the base scene refuses; the message must name that
  // value's line (7), not the first axis' (4), though both edit the run.
  const auto sweep = test::write_temp("fields.toml",
                                      "base = \"" + kPaper + "\"\n"
                                      "[[axis]]\n"
                                      "key = \"model.mu\"\n"
                                      "values = [0.3]\n"
                                      "[[axis]]\n"
                                      "key = \"model.rod2.order\"\n"
                                      "values = [0.5, 1.5]\n");
  const auto r = test::run_cli("sweep '" + sweep.string() + "' --out '" + (sweep.parent_path() / "fields-out").string() + "'");
  CHECK(r.status == 2);
  INFO(r.err);
  CHECK(r.err.find("fields.toml:7: run 1") != std::string::npos);
}
