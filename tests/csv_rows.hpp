#pragma once
// A CSV text (a sweep table, a journal) as rows of cells, split by the library's own splitter;
// optionally without the wall_seconds column, the one cell two runs of a sweep may differ in.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/core/csv_line.hpp"

namespace adjoin::test {

inline std::vector<std::vector<std::string>> csv_rows(const std::string& text, bool drop_wall = false) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::size_t wall = 0;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    REQUIRE(split_csv_line(line, &cells));
    if (rows.empty()) wall = static_cast<std::size_t>(std::find(cells.begin(), cells.end(), "wall_seconds") - cells.begin());
    if (drop_wall && wall < cells.size()) cells.erase(cells.begin() + static_cast<std::ptrdiff_t>(wall));
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace adjoin::test
