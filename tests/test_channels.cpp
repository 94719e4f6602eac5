// The channel registry (structure/channels.hpp) and the reading of channel values
// (observe/channel_values.hpp): the list a structure's outputs iterate over, checked against
// the structure's own counts and against each quantity's definition on a random state.
#include <catch2/catch.hpp>

#include <random>
#include <set>

#include "adjoin/observe/channel_values.hpp"
#include "adjoin/structure/channels.hpp"

using namespace adjoin;
using structure::Quantity;

namespace {

structure::Structure two_buildings(int na, int nb, std::size_t links, std::size_t contacts) {
  structure::Structure s;
  s.a.name = "A";
  s.a.masses = Eigen::VectorXd::LinSpaced(na, 1.0e4, 2.0e4);
  s.a.springs = Eigen::VectorXd::Constant(na, 1.0e7);
  structure::Building b;
  b.name = "B";
  b.masses = Eigen::VectorXd::LinSpaced(nb, 3.0e4, 5.0e4);
  b.springs = Eigen::VectorXd::Constant(nb, 2.0e7);
  s.b = b;
  for (std::size_t l = 0; l < links; ++l) {
    structure::Link link;
    link.type = structure::LinkType::spring;
    link.k = 1.0e6;
    link.floor_a = static_cast<int>(l) + 1;
    link.floor_b = static_cast<int>(l) + 1;
    s.links.push_back(link);
  }
  for (std::size_t c = 0; c < contacts; ++c) {
    structure::Contact pair;
    pair.floor_a = na;
    pair.floor_b = nb - static_cast<int>(c);
    pair.gap = 0.03 + 0.01 * static_cast<double>(c);
    s.contacts.push_back(pair);
  }
  return s;
}

}  // namespace

TEST_CASE("a structure's channels: every floor, storey, building, link and contact pair, each named once",
          "[channels]") {
  const structure::Structure s = two_buildings(5, 3, 2, 1);
  const auto list = structure::channels(s);
  // Per building 4 per floor or storey (x, drift, a_abs, shear) and the base shear; per link
  // each link quantity of the table (force, stroke, ...), 2 per contact pair.
  std::size_t per_link = 0;
  for (const auto& q : structure::quantities()) per_link += q.scope == structure::ChannelScope::link;
  CHECK(per_link >= 2);
  CHECK(list.size() == static_cast<std::size_t>((4 * 5 + 1) + (4 * 3 + 1) + 2 * 1) + 2 * per_link);
  std::set<std::string> names;
  for (const auto& c : list) names.insert(c.name);
  CHECK(names.size() == list.size());
  for (const char* name : {"A.x5", "A.drift1", "A.a3_abs", "A.shear2", "A.base_shear", "B.x3", "B.a1_abs",
                           "link2.stroke", "link1.force", "contact1.gap", "contact1.force"})
    CHECK(names.count(name) == 1);
  CHECK_FALSE(structure::find_channel(s, "B.x4"));       // B has 3 floors
  CHECK_FALSE(structure::find_channel(s, "link3.force"));
  for (const auto& c : list) {
    const auto found = structure::find_channel(s, c.name);
    REQUIRE(found);
    CHECK(found->quantity == c.quantity);
    CHECK(found->dof == c.dof);
    CHECK(structure::info(c.quantity).quantity == c.quantity);
  }
  // A's channels come first, then B's, then the links', then the contact pairs'.
  CHECK(list.front().name == "A.x1");
  CHECK(list.back().name == "contact1.force");
  // Every quantity of the table appears, and exactly one row names it.
  for (const auto& q : structure::quantities()) {
    std::size_t rows = 0;
    for (const auto& r : structure::quantities()) rows += r.quantity == q.quantity;
    CHECK(rows == 1);
  }
}

TEST_CASE("a channel's value is its quantity's definition at the state", "[channels]") {
  const structure::Structure s = two_buildings(4, 3, 1, 1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random = [&](Eigen::Index n) {
    Eigen::VectorXd v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
    return v;
  };
  StructureState st;
  st.x = random(7);
  st.v = random(7);
  st.a_abs = random(7);
  st.storey_force = random(7);
  st.link_force = random(1);
  st.link_stroke = random(1);
  st.link_velocity = random(1);
  const ChannelValues values(s, structure::channels(s));
  std::vector<double> row(values.size());

  auto value_of = [&](const std::string& name) {
    const auto& list = values.channels();
    for (std::size_t k = 0; k < list.size(); ++k)
      if (list[k].name == name) return row[k];
    FAIL("no channel " << name);
    return 0.0;
  };
  // Without contact values from the solver, the gap is computed from the floors.
  values.read(st, row.data());
  CHECK(value_of("A.x3") == st.x[2]);
  CHECK(value_of("B.x2") == st.x[5]);
  CHECK(value_of("A.drift1") == st.x[0]);
  CHECK(value_of("A.drift3") == st.x[2] - st.x[1]);
  CHECK(value_of("B.drift2") == st.x[5] - st.x[4]);
  CHECK(value_of("B.a3_abs") == st.a_abs[6]);
  CHECK(value_of("A.shear4") == st.storey_force[3]);
  CHECK(value_of("B.base_shear") ==
        Approx(-(s.b->masses[0] * st.a_abs[4] + s.b->masses[1] * st.a_abs[5] + s.b->masses[2] * st.a_abs[6])).epsilon(1e-15));
  CHECK(value_of("link1.force") == st.link_force[0]);
  CHECK(value_of("link1.stroke") == st.link_stroke[0]);
  CHECK(value_of("link1.velocity") == st.link_velocity[0]);
  CHECK(value_of("contact1.gap") == Approx(s.contacts[0].gap - (st.x[3] - st.x[6])).epsilon(1e-15));
  CHECK(value_of("contact1.force") == 0.0);
  // The solver's own gap and force, when it reports them, are taken as they are.
  st.contact_gap = Eigen::VectorXd::Constant(1, -0.002);
  st.contact_force = Eigen::VectorXd::Constant(1, 4.5e5);
  values.read(st, row.data());
  CHECK(value_of("contact1.gap") == -0.002);
  CHECK(value_of("contact1.force") == 4.5e5);
}
