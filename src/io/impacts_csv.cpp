#include "adjoin/io/impacts_csv.hpp"

#include <algorithm>
#include <charconv>
#include <iterator>

#include "../detail/finite_output.hpp"

namespace adjoin {

std::string impact_csv_row(const Impact& i, const Scales& k) {
  const double values[] = {i.start * k.time,
                           i.duration * k.time,
                           i.force_max * k.force,
                           i.t_force_max * k.time,
                           i.penetration_max * k.length,
                           i.approach_speed * k.velocity,
                           i.rebound_speed * k.velocity,
                           i.impulse * k.force * k.time};
  static const char* const columns[] = {"t_start",        "duration",      "force_max", "t_force_max", "penetration_max",
                                        "approach_speed", "rebound_speed", "impulse"};
  std::string row;
  char number[32];
  for (std::size_t c = 0; c < std::size(values); ++c) {
    detail::require_finite_output(values[c], "impacts.csv", columns[c], i.start * k.time, i.start);
    auto [end, ec] = std::to_chars(number, number + sizeof number, values[c]);
    row.append(number, end);
    row.push_back(',');
  }
  row.append(i.complete ? "true" : "false");
  return row;
}

void ImpactsCsvWriter::begin(const structure::Structure&, const StructureSolverOptions&) { out_ << kImpactsCsvHeader << '\n'; }

void ImpactsCsvWriter::impact(const Impact& i) { out_ << impact_csv_row(i, scales_) << '\n'; }

std::string impacts_csv(const Report& report) {
  std::vector<Impact> all;
  for (const auto& c : report.contacts) all.insert(all.end(), c.impact_list.begin(), c.impact_list.end());
  std::stable_sort(all.begin(), all.end(), [](const Impact& a, const Impact& b) { return a.start < b.start; });
  std::string out = std::string("contact,") + kImpactsCsvHeader + "\n";
  for (const Impact& e : all) out += std::to_string(e.contact + 1) + "," + impact_csv_row(e, Scales{}) + "\n";
  return out;
}

}  // namespace adjoin
