#pragma once
// The table reader every figure is drawn from (and tests read adjoin's CSV outputs with): a
// CSV file with a header line, header names -> columns, cells kept as text and converted on
// demand, every defect an InputError naming file:line or the column.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace adjoin {

// Quoted fields ("a,b", with "" for a quote) are understood and blanks around a field are
// not part of it (core/csv_line.hpp); blank lines and lines starting with '#' are skipped;
// every row must have as many fields as the header.
struct CsvTable {
  std::filesystem::path file;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::size_t> lines;  // the file line of each row (1-based)

  bool has(const std::string& name) const;
  // Index of a column; InputError naming the column and listing the available ones otherwise.
  std::size_t column(const std::string& name, const std::string& context = "") const;
  // The column as numbers: an empty cell, nan/NaN, "-" or null is NaN; true/false are 1/0;
  // anything else that is not a number is an InputError naming file:line and the column.
  std::vector<double> numbers(const std::string& name, const std::string& context = "") const;
  // The column's cells as text.
  std::vector<std::string> texts(const std::string& name, const std::string& context = "") const;
};

CsvTable read_csv_table(const std::filesystem::path& file);
// The same, and a file that does not exist is "FILE: not found (expected `what`)".
CsvTable read_csv_table(const std::filesystem::path& file, const std::string& what);

}  // namespace adjoin
