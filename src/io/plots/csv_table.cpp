// The table reader of the figures (io/csv_table.hpp), over the project's one CSV splitter and
// number parser (core/).
#include "adjoin/io/csv_table.hpp"

#include <algorithm>
#include <fstream>
#include <limits>

#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/core/errors.hpp"
#include "figure_text.hpp"

namespace adjoin {
using figure::join;

namespace fs = std::filesystem;

bool CsvTable::has(const std::string& name) const {
  return std::find(columns.begin(), columns.end(), name) != columns.end();
}

std::size_t CsvTable::column(const std::string& name, const std::string& context) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end())
    throw InputError(file.string() + ": no column '" + name + "'" + (context.empty() ? "" : " (" + context + ")") +
                     "; the columns are: " + join(columns, ", "));
  return static_cast<std::size_t>(it - columns.begin());
}

std::vector<double> CsvTable::numbers(const std::string& name, const std::string& context) const {
  const std::size_t c = column(name, context);
  std::vector<double> values(rows.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string_view cell = trim_blanks(rows[i][c]);
    if (cell.empty() || cell == "nan" || cell == "NaN" || cell == "-" || cell == "null") continue;
    if (cell == "true" || cell == "false") {  // flags such as a sweep's `contact` plot as 1 / 0
      values[i] = cell == "true" ? 1.0 : 0.0;
      continue;
    }
    // An infinity is drawn as gnuplot draws it (a gap in the curve); only text is refused.
    const NumberStatus status = parse_number(cell, values[i]);
    if (status != NumberStatus::ok && status != NumberStatus::not_finite)
      throw InputError(file.string() + ":" + std::to_string(lines[i]) + ": column '" + name + "' holds '" +
                       std::string(cell) + "', expected a number");
  }
  return values;
}

std::vector<std::string> CsvTable::texts(const std::string& name, const std::string& context) const {
  const std::size_t c = column(name, context);
  std::vector<std::string> cells;
  cells.reserve(rows.size());
  for (const auto& row : rows) cells.push_back(row[c]);
  return cells;
}

CsvTable read_csv_table(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open (expected a CSV file with a header line)");
  CsvTable table;
  table.file = file;
  std::string line;
  std::size_t number = 0;
  std::vector<std::string> fields;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 byte-order mark
    const std::string_view t = trim_blanks(line);
    if (t.empty() || t[0] == '#') continue;
    if (!split_csv_line(line, &fields, CsvBlanks::trimmed))
      throw InputError(file.string() + ":" + std::to_string(number) +
                       ": broken quoting (expected a quoted field to close, \"\" for a quote inside it, nothing after it)");
    if (table.columns.empty()) {
      for (const std::string& f : fields)
        if (f.empty())
          throw InputError(file.string() + ":" + std::to_string(number) +
                           ": empty column name in the header (expected a header line naming every column)");
      table.columns = fields;
      continue;
    }
    if (fields.size() != table.columns.size())
      throw InputError(file.string() + ":" + std::to_string(number) + ": " + std::to_string(fields.size()) +
                       " fields, expected " + std::to_string(table.columns.size()) + " as in the header");
    table.rows.push_back(fields);
    table.lines.push_back(number);
  }
  if (table.columns.empty()) throw InputError(file.string() + ": empty file (expected a CSV file with a header line)");
  return table;
}

CsvTable read_csv_table(const fs::path& file, const std::string& what) {
  if (!fs::exists(file)) throw InputError(file.string() + ": not found (expected " + what + ")");
  return read_csv_table(file);
}

}  // namespace adjoin
