// A two-block run's energy balance per unit m1 (observe/energy.hpp, under SPEC §3's names in
// summary.json and energy.csv) is the 1 + 1 structure's balance in joules as the building
// observers integrate it (study/channel_observer.hpp: the same trapezoidal rule on the same
// powers), so the two-block names are a presentation of the structure's terms: rod1 = A's
// storey, rod2 = B's, friction = link 1, contact = contact pair 1, base friction = the sliders.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../src/study/channel_observer.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/structure/two_block.hpp"
#include "adjoin/study/run.hpp"

using namespace adjoin;

namespace {

const std::string kStrong = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-strong.toml";

// Each term of the two-block observer's balance against the structure observer's, to rounding
// (1e-10 of the input energy).
void check_same_balance(const std::vector<std::string>& overrides) {
  INFO("paper-strong with " << overrides.size() << " overrides");
  Scene scene = load_scene(kStrong, overrides);
  scene.output.energy = true;
  const structure::Structure& s = scene.structure;
  detail::ChannelObserver channels(s);
  const Report r = run(scene, {&channels});
  const BuildingEnergy mine = r.energy, theirs = channels.energy();
  REQUIRE(mine.buildings.size() == 2);
  REQUIRE(theirs.buildings.size() == 2);
  const double scale = std::abs(theirs.input);
  REQUIRE(scale > 1.0);
  auto same = [&](double a, double b) { CHECK(std::abs(a - b) <= 1e-10 * scale); };
  same(mine.input, theirs.input);
  same(mine.residual, theirs.residual);
  for (std::size_t b = 0; b < 2; ++b) {
    same(mine.buildings[b].input, theirs.buildings[b].input);
    same(mine.buildings[b].kinetic, theirs.buildings[b].kinetic);
    REQUIRE(mine.buildings[b].storeys.size() == 1);
    same(mine.buildings[b].storeys[0], theirs.buildings[b].storeys.at(0));
    same(mine.buildings[b].isolator, theirs.buildings[b].isolator);
  }
  REQUIRE(mine.links.size() == theirs.links.size());
  for (std::size_t l = 0; l < mine.links.size(); ++l) same(mine.links[l], theirs.links[l]);
  REQUIRE(mine.contacts.size() == theirs.contacts.size());
  for (std::size_t c = 0; c < mine.contacts.size(); ++c) same(mine.contacts[c], theirs.contacts[c]);
}

}  // namespace

TEST_CASE("a two-block run's energy per unit m1 is its 1 + 1 structure's balance, term by term", "[two_block][energy]") {
  check_same_balance({});  // the paper scheme
  check_same_balance({"solver.scheme=implicit", "solver.history=fft"});
  check_same_balance({"solver.scheme=implicit", "model.mu=0"});
  check_same_balance({"solver.scheme=implicit", "model.gap0=0.3", "model.contact.model=hertzdamp",
                      "model.contact.stiffness=1e4", "model.contact.restitution=0.6"});
  check_same_balance({"solver.scheme=implicit", "model.base_friction=0.05"});
}
