#include "adjoin/study/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>
#include <toml++/toml.h>

#include "../detail/nearest.hpp"
#include "adjoin/errors.hpp"
#include "adjoin/ground/record_motion.hpp"
#include "adjoin/io/file_name.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/observe/energy.hpp"
#include "adjoin/observe/peaks.hpp"
#include "adjoin/observe/phases.hpp"
#include "adjoin/observe/pounding.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/solver/simulate.hpp"
#include "adjoin/study/building_sweep.hpp"

namespace adjoin {

std::string sweep_number_cell(double v) {
  if (std::isnan(v)) return "";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- numbers as text: shortest round-trip form, so text -> double -> text is the identity ----

std::string shortest(double v) { return sweep_number_cell(v); }

bool parse_double(const std::string& text, double* value) {
  if (text.empty()) return false;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

bool parse_size(const std::string& text, std::size_t* value) {
  if (text.empty()) return false;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end;
}

// A double as a TOML float ("1.0", not "1", so that it stays a float).
std::string toml_float(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::string s = shortest(v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char code[8];
          std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(c));
          out += code;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::uint64_t fnv1a(std::uint64_t hash, const std::string& text) {
  for (const char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

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

// ---- reading the sweep file ----

class SweepReader {
 public:
  explicit SweepReader(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const toml::node* node, const std::string& message) const {
    throw InputError(where(node) + message);
  }
  std::string where(const toml::node* node) const {
    if (node && node->source().begin.line > 0) return name_ + ":" + std::to_string(node->source().begin.line) + ": ";
    return name_ + ": ";
  }
  std::size_t line(const toml::node* node) const { return node ? node->source().begin.line : 0; }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

void check_keys(const SweepReader& r, const toml::table& table, const std::vector<std::string>& known,
                const std::string& where_name) {
  for (const auto& [key, node] : table) {
    const std::string k(key.str());
    if (std::find(known.begin(), known.end(), k) != known.end()) continue;
    const std::string best = detail::nearest(k, known);
    r.fail(&node, "unknown key " + k + " in " + where_name + "; did you mean " + best + "? (expected one of: " + [&] {
      std::string list;
      for (const auto& c : known) list += (list.empty() ? "" : ", ") + c;
      return list;
    }() + ")");
  }
}

// The TOML text of a value (for a --set override) and its label; InputError for tables/arrays.
std::pair<std::string, std::string> value_text(const SweepReader& r, const toml::node& node, const std::string& key,
                                               std::optional<double>* number) {
  if (auto v = node.as_integer()) {
    *number = static_cast<double>(v->get());
    return {std::to_string(v->get()), shortest(static_cast<double>(v->get()))};
  }
  if (auto v = node.as_floating_point()) {
    if (!std::isfinite(v->get())) r.fail(&node, key + ": the value must be finite");
    *number = v->get();
    return {toml_float(v->get()), shortest(v->get())};
  }
  if (auto v = node.as_boolean()) return {v->get() ? "true" : "false", v->get() ? "true" : "false"};
  if (auto v = node.as_string()) return {toml_string(v->get()), v->get()};
  r.fail(&node, key + ": expected a number, a string or true/false");
}

// Paths in a sweep file are relative to its folder; the scene reads a --set path relative to the
// working folder, so join them here.
std::string resolve_path_value(const std::string& key, const std::string& value, const std::filesystem::path& folder) {
  if (key != "ground.file") return value;
  const std::filesystem::path p(value);
  if (p.is_relative() && !folder.empty()) return (folder / p).lexically_normal().string();
  return value;
}

// Flattens `set = {...}` (quoted dotted keys or nested tables) into (dotted key, node).
void flatten(const toml::table& table, const std::string& prefix, std::vector<std::pair<std::string, const toml::node*>>& out) {
  for (const auto& [key, node] : table) {
    const std::string path = prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
    if (auto t = node.as_table()) flatten(*t, path, out);
    else out.emplace_back(path, &node);
  }
}

// `set = {...}` and `unset = [...]` of an axis value or a motion.
void read_edits(const SweepReader& r, const toml::table& table, const std::filesystem::path& folder, SweepSetting& s) {
  if (auto node = table.get("set")) {
    auto t = node->as_table();
    if (!t) r.fail(node, "set must be a table of scene keys, e.g. set = {\"ground.file\" = \"x.AT2\", \"ground.units\" = \"g\"}");
    std::vector<std::pair<std::string, const toml::node*>> flat;
    flatten(*t, "", flat);
    for (const auto& [key, value] : flat) {
      std::optional<double> unused;
      auto [text, label] = value_text(r, *value, key, &unused);
      if (key == "ground.file" && value->is_string())
        text = toml_string(resolve_path_value(key, value->as_string()->get(), folder));
      s.set.emplace_back(key, text);
    }
  }
  if (auto node = table.get("unset")) {
    auto a = node->as_array();
    if (!a) r.fail(node, "unset must be an array of scene keys, e.g. unset = [\"model.rod1.order\"]");
    for (const auto& k : *a) {
      if (!k.is_string()) r.fail(&k, "unset: expected scene keys as strings");
      s.unset.push_back(k.as_string()->get());
    }
  }
}

const std::vector<std::string>& fixed_column_names();

// What a sweep holds in memory, per axis value (its edits) and per run (its row: the cells, then
// the CSV and JSON texts built from them): measured 6.0 kB a run at 26 columns (40,000 runs,
// peak RSS), rounded up to 256 bytes a column (README "Sweeps").
constexpr double kBytesPerValue = 256.0;
double bytes_per_run(std::size_t columns) { return 256.0 * static_cast<double>(columns); }

// "478 GB": sizes in messages.
std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  return text;
}

// What a sweep may use: 80 % of the machine's memory (0: unknown, no limit), as `adjoin run`.
double memory_budget() { return 0.8 * physical_memory_bytes(); }

std::string budget_text() {
  return "more than the " + gigabytes(memory_budget()) + " this machine can give (80 % of " +
         gigabytes(physical_memory_bytes()) + ")";
}

std::vector<double> range_values(const SweepReader& r, const toml::table& axis, const std::string& name) {
  auto number = [&](const char* key) -> double {
    auto node = axis.get(key);
    if (!node) r.fail(&axis, "axis " + name + ": missing " + key + " (a range needs from, to and n; or give values = [...])");
    if (auto v = node->value<double>(); v && std::isfinite(*v)) return *v;
    r.fail(node, "axis " + name + ": " + key + " must be a finite number");
  };
  const double from = number("from"), to = number("to");
  auto n_node = axis.get("n");
  if (!n_node) r.fail(&axis, "axis " + name + ": missing n (the number of points from `from` to `to`)");
  auto n_value = n_node->as_integer();
  if (!n_value || n_value->get() < 1 || n_value->get() > 100000000)
    r.fail(n_node, "axis " + name + ": n must be an integer from 1 to 1e8");
  const auto n = static_cast<std::size_t>(n_value->get());
  // Sized before the points are made: a huge axis is refused now, not by bad_alloc later.
  const double need = static_cast<double>(n) * (kBytesPerValue + bytes_per_run(fixed_column_names().size() + 1));
  if (memory_budget() > 0.0 && need > memory_budget())
    r.fail(n_node, "axis " + name + ": n = " + std::to_string(n) + " points would need about " + gigabytes(need) +
                       " of memory for the sweep's table alone, " + budget_text() + "; use fewer points");
  std::string spacing = "lin";
  if (auto node = axis.get("spacing")) {
    if (!node->is_string() || (node->as_string()->get() != "lin" && node->as_string()->get() != "log"))
      r.fail(node, "axis " + name + ": spacing must be \"lin\" or \"log\"");
    spacing = node->as_string()->get();
  }
  if (n == 1 && from != to) r.fail(n_node, "axis " + name + ": n = 1 needs from = to");
  if (spacing == "log" && !(from > 0.0 && to > 0.0))
    r.fail(axis.get("from"), "axis " + name + ": spacing = \"log\" needs from > 0 and to > 0");
  std::vector<double> values(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double u = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    values[i] = spacing == "log" ? std::exp(std::log(from) + u * (std::log(to) - std::log(from))) : from + u * (to - from);
    // 15 significant digits: 0.6, not 0.6000000000000001, in the table and the scene.
    char text[32];
    std::snprintf(text, sizeof text, "%.15g", values[i]);
    values[i] = std::strtod(text, nullptr);
  }
  values.front() = from;
  values.back() = to;
  return values;
}

const std::vector<std::string>& fixed_column_names() {
  static const std::vector<std::string> names = {
      "index", "motion", "units", "x1", "x2", "drift", "f1", "f2", "a1_abs", "a2_abs", "min_gap", "contact",
      "outside_model", "contact.impacts", "contact.force_max", "contact.penetration_max",
      "energy_input", "share_rod1", "share_rod2", "share_friction", "share_residual", "stick_intervals",
      "slip_intervals", "switches", "pga_g", "wall_seconds", "error"};
  return names;
}

std::string sa_column(double period) { return "sa_" + shortest(period); }

// ---- the runs ----

// Keeps what the intensity measures need: max |a_g| always, the history only for Sa.
class GroundRecorder final : public Observer {
 public:
  explicit GroundRecorder(bool keep) : keep_(keep) {}
  void begin(const RunInfo& info) override {
    pga = 0.0;
    ag.clear();
    if (keep_) ag.reserve(info.steps + 1);
  }
  void observe(const State& s) override {
    pga = std::max(pga, std::abs(s.ag));
    if (keep_) ag.push_back(s.ag);
  }
  double pga = 0.0;
  std::vector<double> ag;

 private:
  bool keep_;
};

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

std::vector<std::string> SweepSetting::overrides() const {
  std::vector<std::string> out;
  for (const auto& [key, text] : set) out.push_back(key + "=" + text);
  return out;
}

std::size_t SweepSpec::runs() const {
  std::size_t n = motions.size();
  for (const auto& a : axes) n *= a.values.size();
  return n;
}

std::vector<std::size_t> SweepSpec::coordinates(std::size_t index) const {
  std::vector<std::size_t> c(axes.size() + 1, 0);
  c[axes.size()] = index % motions.size();
  index /= motions.size();
  for (std::size_t k = axes.size(); k-- > 0;) {
    c[k] = index % axes[k].values.size();
    index /= axes[k].values.size();
  }
  return c;
}

std::vector<SweepSetting> SweepSpec::settings(std::size_t index) const {
  const auto c = coordinates(index);
  std::vector<SweepSetting> s;
  if (!common.set.empty() || !common.unset.empty()) s.push_back(common);
  for (std::size_t k = 0; k < axes.size(); ++k) s.push_back(axes[k].values[c[k]]);
  s.push_back(motions[c.back()]);
  return s;
}

std::string SweepSpec::describe(std::size_t index) const {
  const auto c = coordinates(index);
  std::string text;
  for (std::size_t k = 0; k < axes.size(); ++k) text += axes[k].name + "=" + axes[k].values[c[k]].label + ", ";
  return text + "motion=" + motions[c.back()].label;
}

namespace {

// The scene keys the values of one axis (or motion) set.
std::set<std::string> keys_set(const std::vector<SweepSetting>& values) {
  std::set<std::string> keys;
  for (const auto& v : values)
    for (const auto& [key, text] : v.set) keys.insert(key);
  return keys;
}

// Two axes that set the same key: every run has both, and the later one silently overwrites the
// earlier (so one axis is not what its column says). The same for an axis and a motion.
void check_axis_keys(const SweepReader& r, const SweepSpec& spec) {
  const auto at = [&](std::size_t line) { return r.name() + (line ? ":" + std::to_string(line) : std::string()); };
  for (std::size_t b = 0; b < spec.axes.size(); ++b) {
    const auto later = keys_set(spec.axes[b].values);
    for (std::size_t a = 0; a < b; ++a)
      for (const auto& key : keys_set(spec.axes[a].values))
        if (later.count(key))
          throw InputError(at(spec.axes[b].line) + ": axis " + spec.axes[b].name + " sets " + key + ", and so does axis " +
                           spec.axes[a].name + " (" + at(spec.axes[a].line) +
                           "); every run would take one axis' value and drop the other's: set " + key +
                           " on one axis only (or combine the two into one axis of tables)");
    for (const auto& motion : spec.motions)
      for (const auto& [key, text] : motion.set)
        if (later.count(key))
          throw InputError(at(motion.line) + ": motion " + motion.label + " sets " + key + ", and so does axis " +
                           spec.axes[b].name + " (" + at(spec.axes[b].line) +
                           "); the motion's value would replace the axis' in every run: set " + key +
                           " on the axis or in the motions, not both");
  }
}

}  // namespace

SweepSpec parse_sweep(const std::string& text, const std::string& name) {
  SweepReader r(name);
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw InputError(name + ":" + std::to_string(e.source().begin.line) + ": not valid TOML: " + std::string(e.description()));
  }
  check_keys(r, root, {"name", "base", "set", "unset", "axis", "motion", "output"}, "the sweep file");
  const std::filesystem::path folder = std::filesystem::path(name).parent_path();

  SweepSpec spec;
  spec.file = name;
  spec.name = std::filesystem::path(name).stem().string();
  if (!plain_name_problem(spec.name).empty()) spec.name = "sweep";  // a file called "..toml"
  if (auto node = root.get("name")) {
    if (!node->is_string()) r.fail(node, "name must be a string (a plain file name: the output folder out/<name>/)");
    spec.name = node->as_string()->get();
    // The name picks the output folder (out/<name>/): a path there would write outside out/.
    if (const std::string problem = plain_name_problem(spec.name); !problem.empty())
      r.fail(node, "name = " + escaped_excerpt(spec.name) + " " + problem +
                       "; expected a plain file name (it names the output folder out/<name>/)");
  }
  auto base = root.get("base");
  if (!base) r.fail(nullptr, "missing key base (the base scene file, relative to the sweep file)");
  if (!base->is_string() || base->as_string()->get().empty()) r.fail(base, "base must be the path of a scene file (a string)");
  spec.base = std::filesystem::path(base->as_string()->get());
  if (spec.base.is_relative() && !folder.empty()) spec.base = (folder / spec.base).lexically_normal();

  spec.common.line = r.line(root.get("set") ? root.get("set") : root.get("unset"));
  read_edits(r, root, folder, spec.common);

  std::set<std::string> column_names(fixed_column_names().begin(), fixed_column_names().end());
  if (auto node = root.get("axis")) {
    auto axes = node->as_array();
    if (!axes || !axes->is_array_of_tables()) r.fail(node, "axis must be written as [[axis]] tables");
    for (auto& element : *axes) {
      const toml::table& t = *element.as_table();
      check_keys(r, t, {"key", "name", "values", "from", "to", "n", "spacing"}, "[[axis]]");
      SweepAxis axis;
      axis.line = r.line(&t);
      if (auto k = t.get("key")) {
        if (!k->is_string() || k->as_string()->get().empty()) r.fail(k, "axis key must be a dotted scene key (a string), e.g. \"model.mu\"");
        axis.key = k->as_string()->get();
      }
      if (auto n = t.get("name")) {
        if (!n->is_string() || n->as_string()->get().empty()) r.fail(n, "axis name must be a non-empty string");
        axis.name = n->as_string()->get();
      }
      if (axis.name.empty()) axis.name = axis.key;
      if (axis.name.empty()) r.fail(&t, "[[axis]] needs key = \"dotted.scene.key\" or, when every value is a table of edits, name = \"column\"");
      if (axis.name.rfind("sa_", 0) == 0 || !column_names.insert(axis.name).second)
        r.fail(&t, "axis name \"" + axis.name + "\" is already a column of the table; give the axis another name = \"...\"");
      const bool has_values = t.contains("values");
      const bool has_range = t.contains("from") || t.contains("to") || t.contains("n");
      if (has_values == has_range) r.fail(&t, "axis " + axis.name + ": give either values = [...] or from, to, n (and spacing)");
      if (has_range) {
        if (axis.key.empty()) r.fail(&t, "axis " + axis.name + ": a range needs key = \"dotted.scene.key\"");
        for (double v : range_values(r, t, axis.name)) {
          SweepSetting s;
          s.label = shortest(v);
          s.number = v;
          s.line = axis.line;
          s.set.emplace_back(axis.key, toml_float(v));
          axis.values.push_back(std::move(s));
        }
      } else {
        auto values = t.get("values")->as_array();
        if (!values || values->empty()) r.fail(t.get("values"), "axis " + axis.name + ": values must be a non-empty array");
        std::set<std::string> labels;
        for (auto& v : *values) {
          SweepSetting s;
          s.line = r.line(&v);
          if (auto vt = v.as_table()) {
            check_keys(r, *vt, {"name", "set", "unset"}, "an axis value");
            auto label = vt->get("name");
            if (!label || !label->is_string() || label->as_string()->get().empty())
              r.fail(&v, "axis " + axis.name + ": a value written as a table needs name = \"label\" (and set = {...}, unset = [...])");
            s.label = label->as_string()->get();
            // A name that is a number ({name = "0", unset = ["link"]}: "no damper" as slip 0) keeps
            // the axis a number column when its other values are numbers.
            if (double number = 0.0; parse_double(s.label, &number) && std::isfinite(number)) s.number = number;
            read_edits(r, *vt, folder, s);
          } else {
            if (axis.key.empty()) r.fail(&v, "axis " + axis.name + ": a plain value needs the axis' key = \"dotted.scene.key\"");
            auto [value_toml, label] = value_text(r, v, axis.key, &s.number);
            if (axis.key == "ground.file" && v.is_string())
              value_toml = toml_string(resolve_path_value(axis.key, v.as_string()->get(), folder));
            s.label = label;
            s.set.emplace_back(axis.key, value_toml);
          }
          if (!labels.insert(s.label).second) r.fail(&v, "axis " + axis.name + ": the value " + s.label + " appears twice");
          axis.values.push_back(std::move(s));
        }
      }
      spec.axes.push_back(std::move(axis));
    }
  }
  if (auto node = root.get("motion")) {
    auto motions = node->as_array();
    if (!motions || !motions->is_array_of_tables()) r.fail(node, "motion must be written as [[motion]] tables");
    std::set<std::string> names;
    for (auto& element : *motions) {
      const toml::table& t = *element.as_table();
      check_keys(r, t, {"name", "set", "unset"}, "[[motion]]");
      SweepSetting s;
      s.line = r.line(&t);
      auto label = t.get("name");
      if (!label || !label->is_string() || label->as_string()->get().empty())
        r.fail(&t, "[[motion]] needs name = \"...\" (the table's motion column)");
      s.label = label->as_string()->get();
      if (!names.insert(s.label).second) r.fail(label, "motion \"" + s.label + "\" appears twice");
      read_edits(r, t, folder, s);
      spec.motions.push_back(std::move(s));
    }
  }
  if (spec.motions.empty()) {
    SweepSetting s;
    s.label = "base";
    spec.motions.push_back(s);
  }
  if (auto node = root.get("output")) {
    auto t = node->as_table();
    if (!t) r.fail(node, "output must be a table ([output])");
    check_keys(r, *t, {"im_periods", "im_damping"}, "[output]");
    if (auto p = t->get("im_periods")) {
      auto a = p->as_array();
      if (!a) r.fail(p, "output.im_periods must be an array of periods [s], e.g. [0.5, 1.0]");
      for (auto& v : *a) {
        auto x = v.value<double>();
        if (!x || !(*x > 0.0) || !std::isfinite(*x)) r.fail(&v, "output.im_periods: each period must be a positive number [s]");
        if (std::find(spec.im_periods.begin(), spec.im_periods.end(), *x) != spec.im_periods.end())
          r.fail(&v, "output.im_periods: the period " + shortest(*x) + " appears twice");
        spec.im_periods.push_back(*x);
      }
    }
    if (auto d = t->get("im_damping")) {
      auto x = d->value<double>();
      if (!x || !(*x >= 0.0 && *x < 1.0)) r.fail(d, "output.im_damping must be a damping ratio in [0, 1)");
      spec.im_damping = *x;
    }
  }
  const double total = [&] {
    double n = static_cast<double>(spec.motions.size());
    for (const auto& a : spec.axes) n *= static_cast<double>(a.values.size());
    return n;
  }();
  if (total > 1e9) r.fail(nullptr, "the sweep has " + shortest(total) + " runs; at most 1e9");
  check_axis_keys(r, spec);

  // The base scene: read once, and checked on its own (its errors name its file and line).
  try {
    spec.base_text = read_text_file(spec.base, "scene");
  } catch (const InputError& e) {
    throw InputError(r.where(base) + "base: " + e.what());
  }
  bool building = false;
  try {
    const toml::table base_table = toml::parse(spec.base_text, spec.base.string());
    spec.base_source = base_table.at_path("ground.source").value_or(std::string());
    building = base_table.contains("building");
  } catch (const toml::parse_error&) {
    // parse_scene below words the syntax error with its line
  }
  if (building) {
    prepare_building_sweep(spec);
    for (const auto& axis : spec.axes)
      for (const auto& c : spec.channel_columns)
        if (axis.name == c.name)
          throw InputError(r.name() + ":" + std::to_string(axis.line) + ": axis name \"" + axis.name +
                           "\" is already a column of the table; give the axis another name = \"...\"");
  } else {
    (void)parse_scene(spec.base_text, spec.base.string());
  }
  std::uint64_t hash = 14695981039346656037ull;
  hash = fnv1a(hash, text);
  hash = fnv1a(hash, std::string(1, '\0') + spec.base_text);
  hash = fnv1a(hash, std::string(1, '\0') + ADJOIN_VERSION);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  spec.fingerprint = hex;
  return spec;
}

SweepSpec load_sweep(const std::filesystem::path& file) {
  SweepSpec spec = parse_sweep(read_text_file(file, "sweep"), file.string());
  spec.file = file;
  return spec;
}

void check_sweep_memory(const SweepSpec& spec, std::size_t runs) {
  double values = 0.0;
  for (const auto& a : spec.axes) values += static_cast<double>(a.values.size());
  const double per_run = bytes_per_run(sweep_columns(spec).size());
  const double need = values * kBytesPerValue + static_cast<double>(runs) * per_run;
  if (memory_budget() <= 0.0 || need <= memory_budget()) return;
  char per[32];
  std::snprintf(per, sizeof per, "%.2g", per_run / 1e3);
  throw InputError(spec.file.string() + ": the sweep's table of " + std::to_string(runs) + " runs would need about " +
                   gigabytes(need) + " of memory (about " + per + " kB a run), " + budget_text() +
                   "; use fewer points on the axes, or split it with --shard I/N over several machines");
}

RunSpec sweep_scene(const SweepSpec& spec, std::size_t index) {
  const auto settings = spec.settings(index);
  std::vector<std::string> overrides, unset;
  // The structure an edit makes obsolete is dropped by the rule `adjoin run --set` follows
  // (implied_unsets), with the ground source as the edits so far leave it.
  std::string source = spec.base_source;
  for (const auto& s : settings) {
    for (auto& o : s.overrides()) overrides.push_back(std::move(o));
    unset.insert(unset.end(), s.unset.begin(), s.unset.end());
    for (const auto& [key, text] : s.set) {
      for (auto& k : implied_unsets(key, text, source)) unset.push_back(std::move(k));
      if (key == "ground.source") source = toml::parse("v = " + text)["v"].value_or(std::string());
    }
  }
  try {
    RunSpec scene = parse_scene(spec.base_text, spec.base.string(), overrides, unset);
    scene.file = spec.base;
    return scene;
  } catch (const InputError& e) {
    // Point at the axis value or motion that set the offending key, when there is one.
    std::size_t line = 0;
    const std::string message = e.what();
    for (const auto& s : settings) {
      for (const auto& o : s.overrides())
        if (message.rfind("--set " + o + ":", 0) == 0) line = s.line;
      for (const auto& key : s.unset)
        if (message.find("missing key " + key + " ") != std::string::npos) line = s.line;
    }
    const std::string where = spec.file.string() + (line ? ":" + std::to_string(line) : std::string()) + ": ";
    throw InputError(where + "run " + std::to_string(index) + " (" + spec.describe(index) + "): " + message);
  }
}

SweepRow run_sweep_point(const SweepSpec& spec, std::size_t index) {
  if (spec.building()) return run_building_sweep_point(spec, index);
  const auto start = std::chrono::steady_clock::now();
  SweepRow row;
  row.index = index;
  const RunSpec scene = sweep_scene(spec, index);
  const Scales& k = scene.scales;
  row.units = k.units_name();

  PeakObserver peaks;
  PhaseObserver phases;
  PoundingObserver pounding;
  EnergyObserver energy;
  GroundRecorder ground(!spec.im_periods.empty());
  ObserverList observers({&peaks, &phases, &pounding, &energy, &ground});
  try {
    simulate(scene.solver, scene.model, *scene.ground, observers);
    const Peaks& p = peaks.peaks();
    row.x1 = p.x1.max_abs * k.length;
    row.x2 = p.x2.max_abs * k.length;
    row.drift = p.drift.max_abs * k.length;
    row.f1 = p.f1.max_abs * k.force;
    row.f2 = p.f2.max_abs * k.force;
    row.a1_abs = p.a1.max_abs * k.acceleration;
    row.a2_abs = p.a2.max_abs * k.acceleration;
    row.min_gap = pounding.margin().min_gap * k.length;
    row.contact = pounding.margin().contact;
    row.outside_model = pounding.margin().outside_model();
    row.contact_law = pounding.margin().has_law();
    if (row.contact_law) {
      row.impacts = pounding.margin().impacts.size();
      row.force_max = pounding.margin().force_max * k.force;
      row.penetration_max = pounding.margin().penetration_max * k.length;
    }
    const EnergyBalance& e = energy.balance();
    row.energy_input = e.input * k.energy;
    const double in = e.input != 0.0 ? e.input : kNaN;
    row.share_rod1 = e.rod1 / in;
    row.share_rod2 = e.rod2 / in;
    row.share_friction = e.friction / in;
    row.share_residual = e.residual / in;
    for (const auto& interval : phases.intervals())
      ++(interval.state == Phase::stick ? row.stick_intervals : row.slip_intervals);
    row.switches = phases.switches();
    // Intensity measures of the forcing as the solver saw it (dimensionless accelerations are in g).
    row.pga_g = ground.pga;
    if (!spec.im_periods.empty()) {
      const auto* record = dynamic_cast<const RecordMotion*>(scene.ground.get());
      const double seconds = record ? record->time_scale() : k.time;
      std::vector<double> accel(ground.ag.size());
      for (std::size_t i = 0; i < accel.size(); ++i) accel[i] = ground.ag[i] * kStandardGravity;
      SpectrumOptions options;
      options.dampings = {spec.im_damping};
      options.threads = 1;
      for (double period : spec.im_periods)
        row.sa_g.push_back(spectral_values(scene.solver.h * seconds, accel, period, spec.im_damping, options).sa);
    }
  } catch (const NumericalError& e) {
    const SweepRow blank = [&] {
      SweepRow b;
      b.index = index;
      b.units = row.units;
      for (double* v : {&b.x1, &b.x2, &b.drift, &b.f1, &b.f2, &b.a1_abs, &b.a2_abs, &b.min_gap, &b.force_max,
                        &b.penetration_max, &b.energy_input,
                        &b.share_rod1, &b.share_rod2, &b.share_friction, &b.share_residual, &b.pga_g})
        *v = kNaN;
      b.sa_g.assign(spec.im_periods.size(), kNaN);
      return b;
    }();
    row = blank;
    row.error = one_line(e.what());
    if (row.error.empty()) row.error = "numerical failure";
  }
  row.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return row;
}

std::vector<SweepRow> run_sweep(const SweepSpec& spec, const SweepOptions& options) {
  std::vector<std::size_t> indices = options.indices;
  if (indices.empty()) {
    indices.resize(spec.runs());
    for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
  } else {
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    if (indices.back() >= spec.runs())
      throw InputError(spec.file.string() + ": run " + std::to_string(indices.back()) + " does not exist (the sweep has " +
                       std::to_string(spec.runs()) + " runs)");
  }
  std::vector<SweepRow> rows(indices.size());
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex lock;
  std::exception_ptr failure;
  std::size_t failure_index = std::numeric_limits<std::size_t>::max();

  auto work = [&] {
    for (;;) {
      if (stop.load()) return;
      const std::size_t k = next.fetch_add(1);
      if (k >= indices.size()) return;
      try {
        rows[k] = run_sweep_point(spec, indices[k]);
        if (options.on_row) {
          std::lock_guard<std::mutex> guard(lock);
          options.on_row(rows[k]);
        }
      } catch (...) {
        std::lock_guard<std::mutex> guard(lock);
        if (indices[k] < failure_index) {
          failure_index = indices[k];
          failure = std::current_exception();
        }
        stop.store(true);
        return;
      }
    }
  };
  unsigned jobs = options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  jobs = static_cast<unsigned>(std::min<std::size_t>(jobs, indices.size()));
  if (jobs <= 1) {
    work();
  } else {
    std::vector<std::thread> threads;
    for (unsigned j = 0; j < jobs; ++j) threads.emplace_back(work);
    for (auto& t : threads) t.join();
  }
  if (failure) std::rethrow_exception(failure);
  return rows;
}

// ---- the table ----

std::vector<SweepColumn> sweep_columns(const SweepSpec& spec) {
  std::vector<SweepColumn> c{{"index", ColumnType::integer}};
  for (const auto& a : spec.axes) {
    const bool numeric = std::all_of(a.values.begin(), a.values.end(), [](const SweepSetting& s) { return s.number.has_value(); });
    c.push_back({a.name, numeric ? ColumnType::number : ColumnType::string});
  }
  c.push_back({"motion", ColumnType::string});
  c.push_back({"units", ColumnType::string});
  if (spec.building()) {
    c.insert(c.end(), spec.channel_columns.begin(), spec.channel_columns.end());
    c.push_back({"pga_g", ColumnType::number});
    for (double t : spec.im_periods) c.push_back({sa_column(t), ColumnType::number});
    c.push_back({"wall_seconds", ColumnType::number});
    c.push_back({"error", ColumnType::string});
    return c;
  }
  for (const char* n : {"x1", "x2", "drift", "f1", "f2", "a1_abs", "a2_abs", "min_gap"}) c.push_back({n, ColumnType::number});
  c.push_back({"contact", ColumnType::boolean});
  // Pounding (SPEC §6): whether the run went on past a contact with no contact law, and the
  // contact law's results (empty cells for a run without a law).
  c.push_back({"outside_model", ColumnType::boolean});
  c.push_back({"contact.impacts", ColumnType::integer, true});
  c.push_back({"contact.force_max", ColumnType::number});
  c.push_back({"contact.penetration_max", ColumnType::number});
  for (const char* n : {"energy_input", "share_rod1", "share_rod2", "share_friction", "share_residual"})
    c.push_back({n, ColumnType::number});
  for (const char* n : {"stick_intervals", "slip_intervals", "switches"}) c.push_back({n, ColumnType::integer});
  c.push_back({"pga_g", ColumnType::number});
  for (double t : spec.im_periods) c.push_back({sa_column(t), ColumnType::number});
  c.push_back({"wall_seconds", ColumnType::number});
  c.push_back({"error", ColumnType::string});
  return c;
}

namespace {

// x1 ... switches: the two-block columns between units and pga_g.
void append_two_block_cells(const SweepRow& row, std::vector<std::string>& cells) {
  for (double v : {row.x1, row.x2, row.drift, row.f1, row.f2, row.a1_abs, row.a2_abs, row.min_gap}) cells.push_back(shortest(v));
  const bool failed = !row.error.empty();
  cells.push_back(failed ? "" : (row.contact ? "true" : "false"));
  cells.push_back(failed ? "" : (row.outside_model ? "true" : "false"));
  const bool law = !failed && row.contact_law;
  cells.push_back(law ? std::to_string(row.impacts) : "");
  cells.push_back(law ? shortest(row.force_max) : "");
  cells.push_back(law ? shortest(row.penetration_max) : "");
  for (double v : {row.energy_input, row.share_rod1, row.share_rod2, row.share_friction, row.share_residual})
    cells.push_back(shortest(v));
  for (std::size_t v : {row.stick_intervals, row.slip_intervals, row.switches}) cells.push_back(failed ? "" : std::to_string(v));
}

}  // namespace

std::vector<std::string> sweep_cells(const SweepSpec& spec, const SweepRow& row) {
  std::vector<std::string> cells{std::to_string(row.index)};
  const auto coordinates = spec.coordinates(row.index);
  for (std::size_t k = 0; k < spec.axes.size(); ++k) cells.push_back(spec.axes[k].values[coordinates[k]].label);
  cells.push_back(spec.motions[coordinates.back()].label);
  cells.push_back(row.units);
  if (spec.building()) {
    for (std::size_t i = 0; i < spec.channel_columns.size(); ++i) cells.push_back(i < row.channels.size() ? row.channels[i] : "");
  } else {
    append_two_block_cells(row, cells);
  }
  cells.push_back(shortest(row.pga_g));
  for (std::size_t i = 0; i < spec.im_periods.size(); ++i) cells.push_back(i < row.sa_g.size() ? shortest(row.sa_g[i]) : "");
  cells.push_back(shortest(row.wall_seconds));
  cells.push_back(one_line(row.error));
  return cells;
}

SweepTable sweep_table(const SweepSpec& spec, const std::vector<SweepRow>& rows) {
  SweepTable table;
  table.columns = sweep_columns(spec);
  std::vector<const SweepRow*> ordered;
  for (const auto& r : rows) ordered.push_back(&r);
  std::sort(ordered.begin(), ordered.end(), [](const SweepRow* a, const SweepRow* b) { return a->index < b->index; });
  for (const auto* r : ordered) table.rows.push_back(sweep_cells(spec, *r));
  return table;
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

bool split_csv_line(const std::string& line, std::vector<std::string>* cells) {
  cells->clear();
  std::string cell;
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') { cell += '"'; ++i; }
        else quoted = false;
      } else {
        cell += c;
      }
    } else if (c == ',') {
      cells->push_back(std::move(cell));
      cell.clear();
      was_quoted = false;
    } else if (c == '"' && cell.empty() && !was_quoted) {
      quoted = was_quoted = true;
    } else if (c == '"' || was_quoted) {
      return false;  // a quote inside an unquoted cell, or text after a closing quote
    } else {
      cell += c;
    }
  }
  if (quoted) return false;
  cells->push_back(std::move(cell));
  return true;
}

std::string sweep_csv(const SweepTable& table) {
  std::vector<std::string> header;
  for (const auto& c : table.columns) header.push_back(c.name);
  std::string out = csv_line(header) + "\n";
  for (const auto& r : table.rows) out += csv_line(r) + "\n";
  return out;
}

namespace {

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
      if (parse_size(cell, &v)) return v;
      break;
    }
    case ColumnType::number: {
      double v = 0;
      if (parse_double(cell, &v)) return v;
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
      if (row.empty() || !parse_size(row[0], &index) || index >= first.runs)
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
  if (!parse_size(cells[0], index) || cells[0] != std::to_string(*index))
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
  for (std::size_t i = units + 1; i + 1 < cells.size(); ++i) {
    const std::string& cell = cells[i];
    const auto bad = [&](const char* expected) {
      return columns[i].name + " = " + escaped_excerpt(cell) + "; expected " + expected;
    };
    double number = 0.0;
    std::size_t count = 0;
    switch (columns[i].type) {
      case ColumnType::number:
        // An empty cell is a value the run did not have (a failed run, or no input energy).
        if (!cell.empty() && !(parse_double(cell, &number) && std::isfinite(number))) return bad("a finite number or nothing");
        break;
      case ColumnType::integer:
        if (cell.empty() ? !(failed || columns[i].may_be_empty) : !parse_size(cell, &count))
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
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
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

}  // namespace adjoin
