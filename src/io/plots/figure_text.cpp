// What several figure families share (figure_text.hpp).
#include "figure_text.hpp"

#include <fstream>

#include "adjoin/core/errors.hpp"

namespace adjoin::figure {

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? separator : "") + items[i];
  return s;
}

nlohmann::json read_summary_json(const std::filesystem::path& file) {
  nlohmann::json j;
  std::ifstream in(file);
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": not valid JSON (" + e.what() + ")");
  }
  return j;
}

std::pair<double, std::string> force_unit(double peak) {
  if (peak >= 1e6) return {1e6, "MN"};
  if (peak >= 1e3) return {1e3, "kN"};
  return {1.0, "N"};
}

}  // namespace adjoin::figure
