// fractional/history_set: many elements' histories pushed together once per step. Each element's
// lag sums against its own history made alone and pushed the same values (bit for bit: a bank's
// members step as SoeHistories do, soe_bank.hpp), for each engine; elements of equal order in a
// bank, contiguous and not; an order met once; elements without a history; and the summaries.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "adjoin/fractional/history.hpp"
#include "adjoin/fractional/history_set.hpp"
#include "adjoin/fractional/soe_bank.hpp"

using namespace adjoin;

TEST_CASE("a HistorySet's lag sums equal each element's own history bit for bit", "[history_set]") {
  const HistoryEngine engine = GENERATE(HistoryEngine::soe, HistoryEngine::fft, HistoryEngine::direct);
  const WeightRule rule = GENERATE(WeightRule::bdf2, WeightRule::grunwald_letnikov);
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  // 0.5 six times, four of them side by side (a contiguous bank) and two apart; 0.3 twice, apart
  // (a bank read through its elements); 0.7 once (a history of its own); two without.
  const std::vector<double> orders = {0.3, 0.5, 0.5, 0.5, 0.5, kNone, 0.3, 0.7, 0.5, kNone, 0.5};
  const std::size_t count = 1200;
  HistorySet set(engine, rule, orders, count, 1e-12);
  REQUIRE(set.size() == orders.size());
  std::vector<std::unique_ptr<ConvolutionHistory>> alone;
  for (const double g : orders) alone.push_back(std::isnan(g) ? nullptr : make_history(engine, rule, g, count, 1e-12));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  std::vector<double> y(orders.size());
  std::size_t unequal = 0, nonzero_without = 0;
  for (std::size_t m = 0; m < count; ++m) {
    for (std::size_t e = 0; e < y.size(); ++e) {
      // A feedback of each element's own lag sum, as a Zener law's (a slip of one step shows).
      y[e] = std::sin(0.011 * static_cast<double>(m * (e + 1))) + noise(rng) - 0.05 * set.lag_sums()[e];
      if (alone[e]) alone[e]->push(y[e]);
    }
    set.push(y.data());
    for (std::size_t e = 0; e < y.size(); ++e) {
      if (alone[e]) unequal += set.lag_sums()[e] != alone[e]->lag_sum();
      else nonzero_without += set.lag_sums()[e] != 0.0;
    }
  }
  CHECK(unequal == 0);
  CHECK(nonzero_without == 0);
  // The summaries: the largest weight error and mode count of the elements, bytes of them all
  // (one bank's for its members, not one per member).
  double error = 0.0;
  std::size_t modes = 0, bytes = 0;
  for (const auto& h : alone)
    if (h) {
      error = std::max(error, h->weight_error());
      modes = std::max(modes, h->modes());
      bytes += h->bytes();
    }
  CHECK(set.weight_error() == error);
  CHECK(set.modes() == modes);
  if (engine == HistoryEngine::soe) {
    // One bank of the six elements of order 0.5, one of the two of 0.3, a SoeHistory for 0.7.
    CHECK(set.modes() > 0);
    auto c = [&](double g) { return soe_compression(rule, g, 1e-12, count); };
    const std::size_t grouped =
        SoeBank(c(0.5), count, 6).bytes() + SoeBank(c(0.3), count, 2).bytes() + SoeHistory(c(0.7), count).bytes();
    CHECK(set.bytes() == grouped);
  } else {
    CHECK(set.bytes() == bytes);
  }
}

TEST_CASE("SoeBank::push_all equals each member's push bit for bit and refuses a step begun by push", "[history_set][soe]") {
  const auto c = soe_compression(WeightRule::bdf2, 0.4, 1e-12, 600);
  for (const std::size_t members : {std::size_t{3}, std::size_t{8}, std::size_t{10}}) {
    SoeBank together(c, 600, members), apart(c, 600, members);
    std::vector<double> y(members);
    std::size_t unequal = 0;
    for (std::size_t m = 0; m < 600; ++m) {
      for (std::size_t e = 0; e < members; ++e) {
        y[e] = std::cos(0.02 * static_cast<double>(m) + static_cast<double>(e));
        apart.push(e, y[e]);
      }
      together.push_all(y.data());
      for (std::size_t e = 0; e < members; ++e) unequal += together.lag_sum(e) != apart.lag_sum(e);
    }
    CHECK(unequal == 0);
    CHECK_THROWS_AS(together.push_all(y.data()), std::logic_error);  // past the weights
  }
  SoeBank bank(c, 600, 4);
  bank.push(1, 0.5);
  const double y[4] = {1.0, 2.0, 3.0, 4.0};
  CHECK_THROWS_AS(bank.push_all(y), std::logic_error);  // member 1 has pushed this step already
}
