// CSV lines split and joined (core/csv_line.hpp).
#include "adjoin/core/csv_line.hpp"

#include "adjoin/core/parse_number.hpp"

namespace adjoin {

bool split_csv_line(std::string_view line, std::vector<std::string>* cells, CsvBlanks blanks) {
  const bool trim = blanks == CsvBlanks::trimmed;
  const auto is_blank = [&](char c) { return trim && (c == ' ' || c == '\t' || c == '\r'); };
  cells->clear();
  std::string cell;
  bool quoted = false, was_quoted = false;
  const auto finish = [&] {
    cells->push_back(was_quoted ? std::move(cell) : std::string(trim ? trim_blanks(cell) : cell));
    cell.clear();
    was_quoted = false;
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c != '"') {
        cell += c;
      } else if (i + 1 < line.size() && line[i + 1] == '"') {
        cell += '"';
        ++i;
      } else {
        quoted = false;
      }
    } else if (c == ',') {
      finish();
    } else if (c == '"' && !was_quoted && (trim ? trim_blanks(cell).empty() : cell.empty())) {
      quoted = was_quoted = true;
      cell.clear();  // blanks before the quote
    } else if (was_quoted && is_blank(c)) {
      // blanks after the closing quote
    } else if (c == '"' || was_quoted) {
      return false;  // a quote inside an unquoted cell, or text after a closing quote
    } else {
      cell += c;
    }
  }
  if (quoted) return false;
  finish();
  return true;
}

std::string csv_line(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) line += ',';
    const std::string& c = cells[i];
    if (c.find_first_of(",\"\n\r") == std::string::npos) {
      line += c;
    } else {
      line += '"';
      for (char ch : c) {
        if (ch == '"') line += '"';
        line += ch;
      }
      line += '"';
    }
  }
  return line;
}

}  // namespace adjoin
