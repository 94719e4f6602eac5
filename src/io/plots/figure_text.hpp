#pragma once
// Internal to the figures (src/io/plots/): what several figure families share.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace adjoin::figure {

// "a, b, c".
std::string join(const std::vector<std::string>& items, const std::string& separator);
// A run folder's summary.json parsed; InputError naming the file if it is not JSON.
nlohmann::json read_summary_json(const std::filesystem::path& file);
// A force axis in N, kN or MN by the largest value: the divisor and the unit.
std::pair<double, std::string> force_unit(double peak);

}  // namespace adjoin::figure
