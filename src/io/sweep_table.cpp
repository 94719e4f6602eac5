// The sweep's table files (io/sweep_files.hpp): sweep.json written and read back, shard tables
// merged, and both files written whole.
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/sweep_files.hpp"

namespace adjoin {

namespace {

std::string shortest(double v) { return sweep_number_cell(v); }

std::string read_text(const std::filesystem::path& file, const std::string& what) {
  // A folder or a FIFO is not opened (a FIFO would block the program).
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (std::filesystem::is_directory(status)) throw InputError(file.string() + ": is a folder; expected the " + what);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(file.string() + ": is not a regular file (a FIFO, device or socket); expected the " + what);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open the " + what);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

const char* type_name(ColumnType t) {
  switch (t) {
    case ColumnType::integer: return "integer";
    case ColumnType::number: return "number";
    case ColumnType::boolean: return "boolean";
    case ColumnType::string: return "string";
  }
  return "string";
}

bool parse_type(const std::string& name, ColumnType* t) {
  for (ColumnType c : {ColumnType::integer, ColumnType::number, ColumnType::boolean, ColumnType::string})
    if (name == type_name(c)) { *t = c; return true; }
  return false;
}

nlohmann::ordered_json cell_json(ColumnType type, const std::string& cell) {
  if (cell.empty()) return nullptr;
  switch (type) {
    case ColumnType::integer: {
      std::size_t v = 0;
      if (parse_count(cell, &v)) return v;
      break;
    }
    case ColumnType::number: {
      double v = 0;
      if (const NumberStatus s = parse_number(cell, v); s == NumberStatus::ok || s == NumberStatus::not_finite) return v;
      break;
    }
    case ColumnType::boolean: return cell == "true";
    case ColumnType::string: break;
  }
  return cell;
}

std::string json_cell(ColumnType type, const nlohmann::json& v, const std::string& where) {
  if (v.is_null()) return "";
  switch (type) {
    case ColumnType::integer:
      if (v.is_number_unsigned()) return std::to_string(v.get<std::uint64_t>());
      break;
    case ColumnType::number:
      if (v.is_number()) return shortest(v.get<double>());
      break;
    case ColumnType::boolean:
      if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
      break;
    case ColumnType::string:
      if (v.is_string()) return v.get<std::string>();
      if (v.is_number()) return shortest(v.get<double>());
      break;
  }
  throw InputError(where + ": expected " + std::string(type_name(type)) + ", found " + v.dump());
}

}  // namespace

SweepTableFile sweep_table_file(const SweepSpec& spec, SweepTable table, const SweepShard& shard) {
  SweepTableFile f;
  f.sweep = spec.name;
  f.base = spec.base.string();
  f.fingerprint = spec.fingerprint;
  f.runs = spec.runs();
  f.shard = shard;
  f.table = std::move(table);
  return f;
}

std::string sweep_json(const SweepTableFile& f) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["sweep"] = f.sweep;
  j["base"] = f.base;
  j["fingerprint"] = f.fingerprint;
  j["runs"] = f.runs;
  j["shard"] = f.shard.whole() ? ordered_json(nullptr) : ordered_json{{"index", f.shard.index}, {"count", f.shard.count}};
  ordered_json columns = ordered_json::array();
  for (const auto& c : f.table.columns) columns.push_back(ordered_json{{"name", c.name}, {"type", type_name(c.type)}});
  j["columns"] = columns;
  ordered_json rows = ordered_json::array();
  for (const auto& r : f.table.rows) {
    ordered_json row = ordered_json::object();
    for (std::size_t i = 0; i < f.table.columns.size() && i < r.size(); ++i)
      row[f.table.columns[i].name] = cell_json(f.table.columns[i].type, r[i]);
    rows.push_back(row);
  }
  j["rows"] = rows;
  return j.dump(1) + "\n";
}

SweepTableFile read_sweep_json(const std::filesystem::path& file) {
  const std::string name = file.string();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_text(file, "sweep table (sweep.json)"));
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(name + ": not valid JSON (" + e.what() + ")");
  }
  SweepTableFile f;
  f.file = file;
  try {
    auto need = [&](const char* key) -> const nlohmann::json& {
      if (!j.is_object() || !j.contains(key)) throw InputError(name + ": missing key \"" + key + "\" (expected a sweep.json written by adjoin sweep)");
      return j.at(key);
    };
    f.sweep = need("sweep").get<std::string>();
    f.base = need("base").get<std::string>();
    f.fingerprint = need("fingerprint").get<std::string>();
    f.runs = need("runs").get<std::size_t>();
    const auto& shard = need("shard");
    if (!shard.is_null()) {
      f.shard.index = shard.at("index").get<std::size_t>();
      f.shard.count = shard.at("count").get<std::size_t>();
      if (f.shard.count == 0 || f.shard.index >= f.shard.count) throw InputError(name + ": \"shard\" index must be below count");
    }
    for (const auto& c : need("columns")) {
      SweepColumn column;
      column.name = c.at("name").get<std::string>();
      if (!parse_type(c.at("type").get<std::string>(), &column.type))
        throw InputError(name + ": column \"" + column.name + "\" has an unknown type " + c.at("type").dump());
      f.table.columns.push_back(column);
    }
    if (f.table.columns.empty() || f.table.columns[0].name != "index")
      throw InputError(name + ": the first column must be \"index\"");
    std::size_t n = 0;
    for (const auto& r : need("rows")) {
      ++n;
      std::vector<std::string> cells;
      for (const auto& c : f.table.columns) {
        const std::string where = name + ": row " + std::to_string(n) + ", column " + c.name;
        if (!r.contains(c.name)) throw InputError(where + ": missing");
        cells.push_back(json_cell(c.type, r.at(c.name), where));
      }
      f.table.rows.push_back(std::move(cells));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name + ": unexpected structure (" + e.what() + "); expected a sweep.json written by adjoin sweep");
  }
  return f;
}

SweepTableFile merge_sweep_tables(const std::vector<SweepTableFile>& parts) {
  if (parts.empty()) throw InputError("sweep merge: no tables to merge");
  const SweepTableFile& first = parts.front();
  SweepTableFile merged;
  merged.sweep = first.sweep;
  merged.base = first.base;
  merged.fingerprint = first.fingerprint;
  merged.runs = first.runs;
  merged.table.columns = first.table.columns;
  std::vector<const std::vector<std::string>*> by_index(first.runs, nullptr);
  std::vector<std::string> owner(first.runs);
  for (const auto& p : parts) {
    const std::string name = p.file.empty() ? std::string("a table") : p.file.string();
    if (p.fingerprint != first.fingerprint || p.runs != first.runs)
      throw InputError(name + ": belongs to another sweep (fingerprint " + p.fingerprint + ", " + std::to_string(p.runs) +
                       " runs) than " + first.file.string() + " (fingerprint " + first.fingerprint + ", " +
                       std::to_string(first.runs) + " runs)");
    bool same_columns = p.table.columns.size() == first.table.columns.size();
    for (std::size_t i = 0; same_columns && i < p.table.columns.size(); ++i)
      same_columns = p.table.columns[i].name == first.table.columns[i].name;
    if (!same_columns) throw InputError(name + ": its columns differ from those of " + first.file.string());
    for (const auto& row : p.table.rows) {
      std::size_t index = 0;
      if (row.empty() || !parse_count(row[0], &index) || index >= first.runs)
        throw InputError(name + ": a row has index \"" + (row.empty() ? std::string() : row[0]) + "\"; expected 0.." +
                         std::to_string(first.runs - 1));
      if (by_index[index])
        throw InputError(name + ": run " + std::to_string(index) + " is also in " + owner[index] + " (overlapping shards)");
      by_index[index] = &row;
      owner[index] = name;
    }
  }
  std::vector<std::size_t> missing;
  for (std::size_t i = 0; i < by_index.size(); ++i)
    if (!by_index[i]) missing.push_back(i);
  if (!missing.empty()) {
    std::string list;
    for (std::size_t k = 0; k < missing.size() && k < 10; ++k) list += (k ? ", " : "") + std::to_string(missing[k]);
    if (missing.size() > 10) list += ", ...";
    throw InputError("sweep merge: " + std::to_string(missing.size()) + " of " + std::to_string(first.runs) +
                     " runs are in none of the tables (runs " + list + "); merge every shard");
  }
  for (const auto* row : by_index) merged.table.rows.push_back(*row);
  return merged;
}

std::string sweep_file_stem(const SweepShard& shard) {
  if (shard.whole()) return "sweep";
  return "sweep.shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
}

void write_sweep_table(const SweepTableFile& table, const std::filesystem::path& csv, const std::filesystem::path& json) {
  // A pair: both written whole before either replaces its file.
  AtomicFile csv_file(csv), json_file(json);
  csv_file.stream() << sweep_csv(table.table);
  json_file.stream() << sweep_json(table);
  csv_file.finish();
  json_file.finish();
  csv_file.publish();
  json_file.publish();
}

}  // namespace adjoin
