// The sweep's journal (io/sweep_files.hpp): DIR/sweep.partial.csv, one line per finished run,
// read back by a resumed sweep with every row checked against the sweep.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/csv_line.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/output_place.hpp"
#include "adjoin/io/sweep_files.hpp"
#include "adjoin/io/text_file.hpp"

namespace adjoin {
namespace {

// The run number of a row read back (checked by sweep_row_problem).
std::size_t cell_index(const std::vector<std::string>& cells) {
  std::size_t index = 0;
  parse_count(cells.at(0), &index);
  return index;
}

}  // namespace

std::string sweep_journal_preamble(const SweepSpec& spec, const SweepShard& shard) {
  std::vector<std::string> header;
  for (const auto& c : sweep_columns(spec)) header.push_back(c.name);
  return "# adjoin sweep journal fingerprint=" + spec.fingerprint + " runs=" + std::to_string(spec.runs()) +
         " shard=" + std::to_string(shard.index) + "/" + std::to_string(shard.count) + "\n" + csv_line(header) + "\n";
}

std::string sweep_row_problem(const SweepSpec& spec, const SweepShard& shard, const std::vector<std::string>& cells,
                              std::size_t* index) {
  const auto columns = sweep_columns(spec);
  if (cells.size() != columns.size())
    return std::to_string(cells.size()) + " cells; the sweep's table has " + std::to_string(columns.size());
  if (!parse_count(cells[0], index) || cells[0] != std::to_string(*index))
    return "index " + escaped_excerpt(cells[0]) + " is not a run number";
  if (*index >= spec.runs())
    return "run " + cells[0] + " does not exist (the sweep has " + std::to_string(spec.runs()) + " runs)";
  if (!shard.contains(*index))
    return "run " + cells[0] + " is not in shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count);
  // The run's coordinates: its axis values and motion as this sweep spells them.
  const auto c = spec.coordinates(*index);
  for (std::size_t k = 0; k <= spec.axes.size(); ++k) {
    const std::string& expected = k < spec.axes.size() ? spec.axes[k].values[c[k]].label : spec.motions[c.back()].label;
    if (cells[k + 1] != expected)
      return columns[k + 1].name + " = " + escaped_excerpt(cells[k + 1]) + ", but run " + cells[0] + " of this sweep has " +
             escaped_excerpt(expected);
  }
  const std::size_t units = spec.axes.size() + 2;
  if (spec.building() && cells[units] != "SI") return "units = " + escaped_excerpt(cells[units]) + "; a building sweep is in SI";
  if (cells[units] != "dimensionless" && cells[units] != "SI")
    return "units = " + escaped_excerpt(cells[units]) + "; expected dimensionless or SI";
  const bool failed = !cells.back().empty();
  const std::size_t wall = cells.size() - 2;  // wall_seconds, then error
  for (std::size_t i = units + 1; i + 1 < cells.size(); ++i) {
    const std::string& cell = cells[i];
    // A failed run has no results (its row is written with empty cells): numbers beside an
    // error are not a row this sweep wrote.
    if (failed && i < wall && !cell.empty())
      return "error = " + escaped_excerpt(cells.back()) + ", but " + columns[i].name + " = " + escaped_excerpt(cell) +
             "; a failed run's results are empty";
    const auto bad = [&](const char* expected) {
      return columns[i].name + " = " + escaped_excerpt(cell) + "; expected " + expected;
    };
    double number = 0.0;
    std::size_t count = 0;
    switch (columns[i].type) {
      case ColumnType::number:
        // An empty cell is a value the run did not have (a failed run, or no input energy).
        if (!cell.empty() && !parse_finite(cell, &number)) return bad("a finite number or nothing");
        break;
      case ColumnType::integer:
        if (cell.empty() ? !(failed || columns[i].may_be_empty) : !parse_count(cell, &count))
          return bad("a count (nothing only for a failed run)");
        break;
      case ColumnType::boolean:
        if (cell.empty() ? !(failed || columns[i].may_be_empty) : cell != "true" && cell != "false")
          return bad("true or false (nothing only for a failed run)");
        break;
      case ColumnType::string: break;
    }
  }
  return "";
}

std::vector<std::vector<std::string>> read_sweep_journal(const std::filesystem::path& file, const SweepSpec& spec,
                                                         const SweepShard& shard, std::vector<std::string>* dropped) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) return {};
  // Never opened otherwise: a FIFO would block the sweep for ever, a device has no rows.
  if (!std::filesystem::is_regular_file(status))
    throw InputError(file.string() + ": the sweep journal is " + file_kind(status) +
                     ", not a regular file; remove it (the sweep makes its own) or give another --out");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot read the sweep journal");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string preamble = sweep_journal_preamble(spec, shard);
  const auto drop = [&](const std::string& message) {
    if (dropped) dropped->push_back(file.string() + message);
  };
  if (text.compare(0, preamble.size(), preamble) != 0) {
    if (!text.empty())
      drop(": a journal of another sweep (or of this one before its sweep file, base scene or adjoin changed); "
           "none of its rows is used");
    return {};
  }
  std::vector<std::vector<std::string>> rows;
  std::set<std::size_t> seen;
  std::size_t pos = preamble.size(), line_number = 2;
  while (pos < text.size()) {
    ++line_number;
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) break;  // a torn last line: the run was interrupted while writing it
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    std::vector<std::string> cells;
    std::size_t index = 0;
    std::string problem = split_csv_line(line, &cells) ? sweep_row_problem(spec, shard, cells, &index)
                                                        : "broken CSV quoting in " + escaped_excerpt(line);
    if (problem.empty() && !seen.insert(index).second) problem = "run " + cells[0] + " appears twice";
    if (!problem.empty()) {
      drop(":" + std::to_string(line_number) + ": " + problem);
      continue;
    }
    rows.push_back(std::move(cells));
  }
  return rows;
}

SweepJournal::SweepJournal(const SweepSpec& spec, const SweepShard& shard, const std::filesystem::path& dir,
                           std::vector<std::string>* dropped)
    : spec_(spec), path_(dir / (sweep_file_stem(shard) + ".partial.csv")) {
  rows_ = read_sweep_journal(path_, spec, shard, dropped);
  from_journal_ = rows_.size();
  std::set<std::size_t> done;
  for (const auto& r : rows_) done.insert(cell_index(r));
  // Rewrite the journal with what can be trusted (drops a torn last line or another sweep's rows).
  {
    AtomicFile file(path_);
    file.stream() << sweep_journal_preamble(spec, shard);
    for (const auto& r : rows_) file.stream() << csv_line(r) << "\n";
    file.commit();
  }
  for (std::size_t i = shard.index; i < spec.runs(); i += shard.count)
    if (!done.count(i)) pending_.push_back(i);
  if (!pending_.empty()) {
    out_.open(path_, std::ios::binary | std::ios::app);
    if (!out_) throw InputError(path_.string() + ": cannot append to the sweep journal");
  }
}

void SweepJournal::take(const SweepRow& row) {
  auto cells = sweep_cells(spec_, row);
  out_ << csv_line(cells) << "\n";
  out_.flush();
  if (!out_) throw InputError(path_.string() + ": cannot write the sweep journal (disk full?)");
  rows_.push_back(std::move(cells));
}

std::vector<std::vector<std::string>> SweepJournal::rows() const {
  auto rows = rows_;
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return cell_index(a) < cell_index(b); });
  return rows;
}

void SweepJournal::remove() {
  if (out_.is_open()) out_.close();
  std::filesystem::remove(path_);
}

}  // namespace adjoin
