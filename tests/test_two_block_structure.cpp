// The paper's model as the 1 + 1 structure (structure/two_block.hpp) and back.
#include <catch2/catch.hpp>

#include "adjoin/structure/builder.hpp"
#include "adjoin/structure/two_block.hpp"

using namespace adjoin;

namespace {

void check_same(const Model& a, const Model& b) {
  CHECK(a.rho == Approx(b.rho).epsilon(1e-15));
  CHECK(a.eps == b.eps);
  CHECK(a.mu == b.mu);
  CHECK(a.gap0 == b.gap0);
  CHECK(a.base_friction == b.base_friction);
  for (const auto& [x, y] : {std::pair{a.rod1, b.rod1}, std::pair{a.rod2, b.rod2}}) {
    CHECK(x.elastic == y.elastic);
    if (x.elastic) continue;
    CHECK(x.order == y.order);
    CHECK(x.tau_x == y.tau_x);
    CHECK(x.tau_f == y.tau_f);
  }
  CHECK(a.contact.model == b.contact.model);
  CHECK(a.contact.stiffness == b.contact.stiffness);
  CHECK(a.contact.restitution == b.contact.restitution);
}

}  // namespace

TEST_CASE("two_block_model inverts two_block_structure") {
  Model paper = Model::Paper();
  Model odd;  // every part the model has, none at its default
  odd.rho = 0.41;  // 1 / (1 / 0.41) is not 0.41 exactly
  odd.eps = 7.25;
  odd.mu = 0.0;   // no damper: no link
  odd.gap0 = 0.125;
  odd.base_friction = 0.05;
  odd.rod1 = Rod::Elastic();
  odd.rod2 = Rod{0.71, 3.0, 0.5, false};
  odd.contact.model = structure::ContactModel::hertzdamp;
  odd.contact.stiffness = 40.0;
  odd.contact.restitution = 0.7;
  for (const Model& m : {paper, odd}) {
    const auto back = structure::two_block_model(structure::two_block_structure(m));
    REQUIRE(back);
    check_same(*back, m);
    // and the structure of the model read back is the structure, but for rho's rounding
    const structure::Structure again = structure::two_block_structure(*back);
    CHECK(again.b->masses[0] == Approx(1.0 / m.rho).epsilon(1e-15));
    CHECK(again.links.size() == (m.mu > 0.0 ? 1u : 0u));
  }
}

TEST_CASE("two_block_model refuses what is not the 1 + 1 structure, and says why") {
  const structure::Structure s = structure::two_block_structure(Model::Paper());
  std::string why;
  auto refused = [&](structure::Structure t, const std::string& reason) {
    why.clear();
    CHECK_FALSE(structure::two_block_model(t, &why));
    INFO(why);
    CHECK(why.find(reason) != std::string::npos);
  };
  structure::Structure t = s;
  t.b.reset();
  refused(t, "no building B");
  t = s;
  t.a.masses[0] = 2.0;  // SI, or not block 1's units
  refused(t, "building A's mass and stiffness are not 1");
  t = s;
  t.links.push_back(t.links[0]);
  refused(t, "not one friction damper");
  t = s;
  t.links[0].type = structure::LinkType::dashpot;
  refused(t, "not one friction damper");
  t = s;
  t.contacts.clear();
  refused(t, "not one contact pair");
  t = s;
  t.b->ground_friction = 0.1;  // A has none
  refused(t, "base frictions");
  t = s;
  t.a.damping.model = structure::DampingModel::modal;
  refused(t, "building A has damping");
  t = s;
  t.b->devices[0].type = structure::DeviceType::dashpot;
  refused(t, "building B's storey is not one Zener rod");
  // a building pair written in code (structure/builder.hpp) with two floors is no model
  structure::StructureBuilder b;
  b.building('A', 2).mass(1e5).stiffness(1e8);
  b.building('B', 1).mass(1e5).stiffness(1e8);
  refused(b.build(), "2 floors");
}
