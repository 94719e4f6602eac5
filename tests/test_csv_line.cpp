// core/csv_line: the one CSV splitter (sweep tables and journals, figure tables, demand fits).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "adjoin/core/csv_line.hpp"

using adjoin::CsvBlanks;
using Cells = std::vector<std::string>;

namespace {

Cells split(const std::string& line, CsvBlanks blanks = CsvBlanks::kept) {
  Cells cells;
  REQUIRE(adjoin::split_csv_line(line, &cells, blanks));
  return cells;
}

bool splits(const std::string& line, CsvBlanks blanks) {
  Cells cells;
  return adjoin::split_csv_line(line, &cells, blanks);
}

}  // namespace

TEST_CASE("split_csv_line: plain and quoted cells, empty cells kept", "[csv_line]") {
  CHECK(split("a,b,c") == Cells{"a", "b", "c"});
  CHECK(split("") == Cells{""});
  CHECK(split(",") == Cells{"", ""});
  CHECK(split("1,,3,") == Cells{"1", "", "3", ""});
  CHECK(split("\"a,b\",\"say \"\"hi\"\"\",x") == Cells{"a,b", "say \"hi\"", "x"});
  CHECK(split("\"\"") == Cells{""});
}

TEST_CASE("split_csv_line: blanks kept, or trimmed around cells and quotes", "[csv_line]") {
  CHECK(split(" a , b ") == Cells{" a ", " b "});
  CHECK(split(" a , b ", CsvBlanks::trimmed) == Cells{"a", "b"});
  CHECK(split("  \" a \"  ,x", CsvBlanks::trimmed) == Cells{" a ", "x"});  // inside the quotes, kept
  CHECK(split("t,\tx1\r", CsvBlanks::trimmed) == Cells{"t", "x1"});
  // Kept blanks make a quote after one a stray quote.
  CHECK_FALSE(splits(" \"a\"", CsvBlanks::kept));
}

TEST_CASE("split_csv_line refuses broken quoting in either mode", "[csv_line]") {
  for (CsvBlanks blanks : {CsvBlanks::kept, CsvBlanks::trimmed}) {
    CHECK_FALSE(splits("\"open", blanks));
    CHECK_FALSE(splits("a\"b,c", blanks));       // a quote inside an unquoted cell
    CHECK_FALSE(splits("\"a\"b,c", blanks));     // text after a closing quote
    CHECK_FALSE(splits("\"a\",\"b", blanks));
  }
}

TEST_CASE("csv_line quotes what needs it and splits back to the same cells", "[csv_line]") {
  const Cells cells{"plain", "with,comma", "with \"quote\"", "", "line\nbreak", " blank "};
  const std::string line = adjoin::csv_line(cells);
  CHECK(line == "plain,\"with,comma\",\"with \"\"quote\"\"\",,\"line\nbreak\", blank ");
  CHECK(split(line) == cells);
}
