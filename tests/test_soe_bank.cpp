// fractional/soe_bank: many soe histories of one order stepped together. Each member's lag sums
// against a SoeHistory pushed the same values (bit for bit: the same arithmetic, lane by lane),
// for both rules, with and without two-term modes, for banks that fill their last block of
// four and banks that do not, through the line's shifts and to the end of the weights; members
// of equal order grouped by HistorySet against the exact weights; misuse refused; a building whose Zener storeys
// share a bank against the direct engine.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <stdexcept>

#include "adjoin/fractional/direct_history.hpp"
#include "adjoin/fractional/history_set.hpp"
#include "adjoin/fractional/soe_bank.hpp"
#include "adjoin/fractional/weights.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/solver/structure_solver.hpp"
#include "state_recorder.hpp"

using namespace adjoin;

namespace {

// Member e's value at step m: a smooth signal of its own with some noise (the lag sums mix
// many past values, so a bookkeeping slip of one step or one lane shows at once).
double value(std::size_t e, std::size_t m, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  return std::sin(0.013 * static_cast<double>(m) * static_cast<double>(e + 1)) + noise(rng);
}

}  // namespace

TEST_CASE("a SoeBank member's lag sums equal a SoeHistory's bit for bit", "[soe][bank]") {
  const auto [rule, order] = GENERATE(table<WeightRule, double>({{WeightRule::bdf2, 0.5},
                                                                 {WeightRule::bdf2, 0.23},
                                                                 {WeightRule::grunwald_letnikov, 0.53},
                                                                 {WeightRule::grunwald_letnikov, 0.9}}));
  const std::size_t members = GENERATE(2, 4, 5, 9);
  const std::size_t count = 1500;  // past the line's shift (every 223 steps) and to the weights' end
  const auto c = soe_compression(rule, order, 1e-12, count);
  INFO("rule " << static_cast<int>(rule) << ", order " << order << ", members " << members << ", modes " << c->single
               << " + " << c->paired);
  if (rule == WeightRule::bdf2) CHECK(c->paired > 0);  // the two-term modes are exercised
  SoeBank bank(c, count, members);
  std::vector<SoeHistory> alone(members, SoeHistory(c, count));
  std::mt19937_64 rng(7);
  std::size_t unequal = 0;
  double largest = 0.0;
  for (std::size_t m = 0; m < count; ++m) {
    // Members push in an order of their own each step (the bank waits for the last).
    for (std::size_t k = 0; k < members; ++k) {
      const std::size_t e = (k + m) % members;
      const double y = value(e, m, rng);
      bank.push(e, y);
      alone[e].push(y);
    }
    REQUIRE(bank.size() == m + 1);
    for (std::size_t e = 0; e < members; ++e) {
      unequal += bank.lag_sum(e) != alone[e].lag_sum();
      largest = std::max(largest, std::abs(alone[e].lag_sum()));
    }
  }
  CHECK(unequal == 0);
  CHECK(largest > 0.1);  // the sums were not all zero
  CHECK(bank.lag_sum(0) == 0.0);  // past the last weight
}

TEST_CASE("SoeBank refuses a member pushing twice in a step and pushes past the weights", "[soe][bank]") {
  const auto c = soe_compression(WeightRule::bdf2, 0.5, 1e-12, 8);
  SoeBank bank(c, 3, 2);
  bank.push(0, 1.0);
  CHECK(bank.staged(0));
  CHECK_THROWS_AS(bank.push(0, 2.0), std::logic_error);
  bank.push(1, 1.0);
  CHECK_FALSE(bank.staged(0));
  for (int m = 1; m < 3; ++m) {
    bank.push(0, 1.0);
    bank.push(1, 1.0);
  }
  CHECK(bank.size() == 3);
  CHECK_THROWS_AS(bank.push(1, 1.0), std::logic_error);
  CHECK_THROWS_AS(SoeBank(c, 3, 0), std::invalid_argument);
}

TEST_CASE("a HistorySet shares a bank among equal orders and follows the exact weights", "[soe][bank]") {
  const std::vector<double> orders{0.5, 0.3, 0.5, 0.5, 0.7, 0.3};
  const std::size_t count = 3000;
  HistorySet histories(HistoryEngine::soe, WeightRule::bdf2, orders, count, 1e-12);
  REQUIRE(histories.size() == orders.size());
  std::vector<DirectHistory> exact;
  for (double a : orders) exact.emplace_back(bdf2_weights(a, count));
  // A bank's bytes are shared among its members: the compression and its coefficients once,
  // so forty members of one order hold less than forty SoeHistories.
  const std::size_t alone = SoeHistory(soe_compression(WeightRule::bdf2, 0.5, 1e-12, count), count).bytes();
  const std::size_t forty = HistorySet(HistoryEngine::soe, WeightRule::bdf2, std::vector<double>(40, 0.5), count, 1e-12).bytes();
  INFO("bytes: one SoeHistory " << alone << ", forty banked " << forty);
  CHECK(forty < 40 * alone);
  std::mt19937_64 rng(11);
  double worst = 0.0;
  std::vector<double> y(orders.size());
  for (std::size_t m = 0; m + 1 < count; ++m) {
    for (std::size_t i = 0; i < orders.size(); ++i) {
      y[i] = value(i, m, rng);
      exact[i].push(y[i]);
    }
    histories.push(y.data());
    for (std::size_t i = 0; i < orders.size(); ++i) {
      // Relative to the sum of |w_j y_{m-j}| <= the weights' bound times it.
      worst = std::max(worst, std::abs(histories.lag_sums()[i] - exact[i].lag_sum()) / (1.0 + std::abs(exact[i].lag_sum())));
    }
  }
  INFO("largest difference " << worst);
  CHECK(worst < 1e-11);
  CHECK(histories.modes() > 0);
  CHECK(histories.weight_error() <= 1e-12);
}

TEST_CASE("a building whose Zener storeys share a bank follows the direct engine", "[soe][bank][building]") {
  // The two-frame scene's Zener devices (A's storeys 1 and 2, order 0.5) and three more of
  // order 0.5 in B's storeys: one bank of five members (a full block and one of a single
  // member); one of order 0.35 in A's storey 3: a SoeHistory of its own.
  const std::string file = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";
  auto run = [&](const char* engine) {
    BuildingScene scene = load_building_scene(file, {std::string("solver.history=") + engine, "solver.t_end=8"});
    structure::StoreyDevice d;
    d.type = structure::DeviceType::zener;
    d.storeys = {1, 2, 3};
    d.zener = {1.0e6, 0.5, 0.2, 0.01};
    scene.structure.b->devices.push_back(d);
    d.storeys = {3};
    d.zener = {1.0e6, 0.35, 0.1, 0.01};
    scene.structure.a.devices.push_back(d);
    adjoin::test::StateRecorder r;
    const SolverSummary summary = simulate_structure(scene.solver, scene.structure, *scene.ground, r);
    return std::pair{r.states, summary};
  };
  const auto [direct, direct_summary] = run("direct");
  const auto [soe, soe_summary] = run("soe");
  REQUIRE(direct.size() == soe.size());
  CHECK(soe_summary.history_modes > 0);
  double scale = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < direct.size(); ++i) {
    scale = std::max(scale, direct[i].x.cwiseAbs().maxCoeff());
    diff = std::max(diff, (direct[i].x - soe[i].x).cwiseAbs().maxCoeff());
  }
  INFO("relative difference " << diff / scale);
  CHECK(scale > 1e-3);
  CHECK(diff < 1e-10 * scale);
}
