#pragma once
// CSV lines, split and joined: the one splitter every table reader of adjoin uses (sweep
// tables and journals, the tables figures are drawn from, demand fits). RFC 4180 quoting: a
// cell in double quotes may hold commas, and "" stands for a quote inside it.
//
// The core layer: no adjoin header below it, so every layer may include it.
#include <string>
#include <string_view>
#include <vector>

namespace adjoin {

enum class CsvBlanks {
  kept,     // a cell is every byte between the commas (tables adjoin wrote itself)
  trimmed,  // blanks around a cell (and around a quoted cell's quotes) are not part of it
};

// Splits one CSV line (no line break) into `cells`; false if the quoting is broken: an
// unclosed quote, a quote inside an unquoted cell, or text after a closing quote.
bool split_csv_line(std::string_view line, std::vector<std::string>* cells, CsvBlanks blanks = CsvBlanks::kept);

// One CSV line of `cells`: a cell holding ',', '"' or a line break is quoted.
std::string csv_line(const std::vector<std::string>& cells);

}  // namespace adjoin
