#pragma once
// "Did you mean ...?": the candidate nearest to a mistyped key by edit distance (Levenshtein),
// for the error messages of scene and sweep files.
#include <string>
#include <vector>

namespace adjoin::detail {

std::size_t edit_distance(const std::string& a, const std::string& b);
// The first candidate at the smallest edit distance from `word` (empty if there are none).
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace adjoin::detail
