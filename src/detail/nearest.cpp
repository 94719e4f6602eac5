#include "nearest.hpp"

#include <algorithm>

namespace adjoin::detail {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::string::npos;
  for (const auto& c : candidates)
    // A candidate that contains the word (three letters or more) is what was meant more often
    // than one a few edits away: "sine" is "decaying-sine", not "record".
    if (const std::size_t d = word.size() >= 3 && c.find(word) != std::string::npos ? 1 : edit_distance(word, c);
        d < best_distance) {
      best_distance = d;
      best = c;
    }
  return best;
}

}  // namespace adjoin::detail
