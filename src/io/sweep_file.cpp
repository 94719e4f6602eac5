// The sweep file's reader (io/sweep_file.hpp): the sweep's
// axes and motions as typed edits, the base scene read once, and io's SweepScenes.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>
#include <toml++/toml.h>

#include "../detail/nearest.hpp"
#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/file_name.hpp"
#include "adjoin/io/sweep_file.hpp"
#include "adjoin/io/sweep_scenes.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/io/two_block_names.hpp"
#include "adjoin/study/sweep_columns.hpp"
#include "adjoin/study/sweep.hpp"

namespace adjoin {
namespace {

// The column names every two-block sweep table has (an axis may not take one of them).
const std::vector<std::string>& fixed_column_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"index", "motion", "units"};
    for (const auto& c : two_block_sweep_channels()) n.push_back(c.name);
    for (const char* last : {"pga_g", "wall_seconds", "error"}) n.push_back(last);
    return n;
  }();
  return names;
}

std::string shortest(double v) { return sweep_number_cell(v); }

std::uint64_t fnv1a(std::uint64_t hash, const std::string& text) {
  for (const char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
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
    const std::string best = detail::nearest(k.substr(0, 200), known);
    r.fail(&node, "unknown key " + text_excerpt(k) + " in " + where_name + "; did you mean " + best + "? (expected one of: " + [&] {
      std::string list;
      for (const auto& c : known) list += (list.empty() ? "" : ", ") + c;
      return list;
    }() + ")");
  }
}

// A scene key an axis, a `set` or an `unset` names: short enough to be quoted in messages whole
// (the scene's longest key is under 40 characters).
void check_key_length(const SweepReader& r, const toml::node* node, const std::string& key) {
  if (key.size() > 200) r.fail(node, "scene key " + escaped_excerpt(key) + " is not a scene key (over 200 characters)");
}

// One scalar of the sweep file: a number, a string or true/false.
SweepScalar scalar_of(const SweepReader& r, const toml::node& node, const std::string& key) {
  if (auto v = node.as_integer()) return v->get();
  if (auto v = node.as_floating_point()) {
    if (!std::isfinite(v->get())) r.fail(&node, key + ": the value must be finite");
    return v->get();
  }
  if (auto v = node.as_boolean()) return v->get();
  if (auto v = node.as_string()) return v->get();
  r.fail(&node, key + ": expected a number, a string, true/false or a list of them (e.g. [3, 3])");
}

// A value (typed, with its TOML text: what a --set of it would say) and its label; a list of
// numbers, strings or true/false is one value (link.1.floors = [3, 3]), labelled as written.
std::pair<SweepValue, std::string> value_text(const SweepReader& r, const toml::node& node, const std::string& key,
                                              std::optional<double>* number) {
  if (auto list = node.as_array()) {
    std::vector<SweepScalar> items;
    for (const auto& item : *list) {
      if (item.is_array() || item.is_table())
        r.fail(&item, key + ": a list value holds numbers, strings or true/false, not lists or tables");
      items.push_back(scalar_of(r, item, key));
    }
    SweepValue value = sweep_value(std::move(items));
    std::string label = value.text;
    return {std::move(value), std::move(label)};
  }
  const SweepScalar v = scalar_of(r, node, key);
  if (const auto* i = std::get_if<std::int64_t>(&v)) {
    *number = static_cast<double>(*i);
    return {sweep_value(*i), shortest(static_cast<double>(*i))};
  }
  if (const auto* d = std::get_if<double>(&v)) {
    *number = *d;
    return {sweep_value(*d), shortest(*d)};
  }
  if (const auto* b = std::get_if<bool>(&v)) return {sweep_value(*b), *b ? "true" : "false"};
  return {sweep_value(std::get<std::string>(v)), std::get<std::string>(v)};
}

// A string value as an edit's value.
SweepValue string_value(const std::string& text) { return sweep_value(text); }

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
      check_key_length(r, value, key);
      std::optional<double> unused;
      auto [edit, label] = value_text(r, *value, key, &unused);
      if (key == "ground.file" && value->is_string())
        edit = string_value(resolve_path_value(key, value->as_string()->get(), folder));
      s.set.emplace_back(key, std::move(edit));
    }
  }
  if (auto node = table.get("unset")) {
    auto a = node->as_array();
    if (!a) r.fail(node, "unset must be an array of scene keys, e.g. unset = [\"model.rod1.order\"]");
    for (const auto& k : *a) {
      if (!k.is_string()) r.fail(&k, "unset: expected scene keys as strings");
      check_key_length(r, &k, k.as_string()->get());
      s.unset.push_back(k.as_string()->get());
    }
  }
}

// An axis value written as a table, or a [[variant]]: {name = label, set = {...}, unset = [...]}.
SweepSetting table_value(const SweepReader& r, const toml::table& t, const std::filesystem::path& folder,
                         const std::string& what, const std::string& where_name) {
  check_keys(r, t, {"name", "set", "unset"}, where_name);
  SweepSetting s;
  s.line = r.line(&t);
  auto label = t.get("name");
  if (!label || !label->is_string() || label->as_string()->get().empty())
    r.fail(&t, what + " needs name = \"label\" (and set = {...}, unset = [...])");
  s.label = label->as_string()->get();
  // A name that is a number ({name = "0", unset = ["link"]}: "no damper" as slip 0) keeps
  // the axis a number column when its other values are numbers.
  if (double number = 0.0; parse_finite(s.label, &number)) s.number = number;
  read_edits(r, t, folder, s);
  return s;
}

// [[variant]] tables: sugar for a first axis named "variant" whose values are those tables
// (design variants as named sets of edits).
SweepAxis read_variants(const SweepReader& r, const toml::node& node, const std::filesystem::path& folder,
                        std::set<std::string>& column_names) {
  auto variants = node.as_array();
  if (!variants || !variants->is_array_of_tables())
    r.fail(&node, "variant must be written as [[variant]] tables, each name = \"...\", set = {...}, unset = [...]");
  SweepAxis axis;
  axis.name = "variant";
  axis.line = r.line(&node);
  column_names.insert(axis.name);
  std::set<std::string> labels;
  for (auto& element : *variants) {
    SweepSetting s = table_value(r, *element.as_table(), folder, "[[variant]]", "[[variant]]");
    if (!labels.insert(s.label).second) r.fail(element.as_table()->get("name"), "variant \"" + s.label + "\" appears twice");
    axis.values.push_back(std::move(s));
  }
  return axis;
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
  if (const std::string problem = sweep_axis_memory_problem(n, fixed_column_names().size()); !problem.empty())
    r.fail(n_node, "axis " + name + ": n = " + std::to_string(n) + " points " + problem + "; use fewer points");
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


// The scene keys the values of one axis (or motion) set.
std::set<std::string> keys_set(const std::vector<SweepSetting>& values) {
  std::set<std::string> keys;
  for (const auto& v : values)
    for (const auto& [key, value] : v.set) keys.insert(key);
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
      for (const auto& [key, value] : motion.set)
        if (later.count(key))
          throw InputError(at(motion.line) + ": motion " + motion.label + " sets " + key + ", and so does axis " +
                           spec.axes[b].name + " (" + at(spec.axes[b].line) +
                           "); the motion's value would replace the axis' in every run: set " + key +
                           " on the axis or in the motions, not both");
  }
}

// One [[axis]] table: its key or name (a new column of the table) and its values, listed or
// a range.
SweepAxis read_axis(const SweepReader& r, const toml::table& t, const std::filesystem::path& folder,
                    std::set<std::string>& column_names) {
  check_keys(r, t, {"key", "name", "values", "from", "to", "n", "spacing"}, "[[axis]]");
  SweepAxis axis;
  axis.line = r.line(&t);
  if (auto k = t.get("key")) {
    if (!k->is_string() || k->as_string()->get().empty()) r.fail(k, "axis key must be a dotted scene key (a string), e.g. \"model.mu\"");
    axis.key = k->as_string()->get();
    check_key_length(r, k, axis.key);
  }
  if (auto n = t.get("name")) {
    if (!n->is_string() || n->as_string()->get().empty()) r.fail(n, "axis name must be a non-empty string");
    axis.name = n->as_string()->get();
    if (axis.name.size() > 200) r.fail(n, "axis name " + escaped_excerpt(axis.name) + " is longer than 200 characters");
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
      s.set.emplace_back(axis.key, sweep_value(v));
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
        s = table_value(r, *vt, folder, "axis " + axis.name + ": a value written as a table", "an axis value");
      } else {
        if (axis.key.empty()) r.fail(&v, "axis " + axis.name + ": a plain value needs the axis' key = \"dotted.scene.key\"");
        auto [edit, label] = value_text(r, v, axis.key, &s.number);
        if (axis.key == "ground.file" && v.is_string())
          edit = string_value(resolve_path_value(axis.key, v.as_string()->get(), folder));
        s.label = label;
        s.set.emplace_back(axis.key, std::move(edit));
      }
      if (!labels.insert(s.label).second) r.fail(&v, "axis " + axis.name + ": the value " + s.label + " appears twice");
      axis.values.push_back(std::move(s));
    }
  }
  return axis;
}

// The [[motion]] tables (the table's motion column), or the base scene's own ground as "base".
void read_motions(const SweepReader& r, const toml::table& root, const std::filesystem::path& folder, SweepSpec& spec) {
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
}

// [output]: the periods of the Sa columns and their damping.
void read_output(const SweepReader& r, const toml::table& root, SweepSpec& spec) {
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
  check_keys(r, root, {"name", "base", "set", "unset", "variant", "axis", "motion", "output"}, "the sweep file");
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
  if (auto node = root.get("variant")) spec.axes.push_back(read_variants(r, *node, folder, column_names));
  if (auto node = root.get("axis")) {
    auto axes = node->as_array();
    if (!axes || !axes->is_array_of_tables()) r.fail(node, "axis must be written as [[axis]] tables");
    for (auto& element : *axes) spec.axes.push_back(read_axis(r, *element.as_table(), folder, column_names));
  }
  read_motions(r, root, folder, spec);
  read_output(r, root, spec);
  const double total = [&] {
    double n = static_cast<double>(spec.motions.size());
    for (const auto& a : spec.axes) n *= static_cast<double>(a.values.size());
    return n;
  }();
  if (total > 1e9) r.fail(nullptr, "the sweep has " + shortest(total) + " runs; at most 1e9");
  check_axis_keys(r, spec);

  // The base scene: read once, and checked on its own (its errors name its file and line).
  std::string base_text;
  try {
    base_text = read_text_file(spec.base, "scene");
  } catch (const InputError& e) {
    throw InputError(r.where(base) + "base: " + e.what());
  }
  const auto scenes = std::make_shared<const SceneSweepScenes>(spec, base_text);
  spec.scenes = scenes;
  if (scenes->building()) {
    // Checked whole, as `adjoin run` would read it (its own errors name its file and line).
    prepare_building_sweep(spec, scenes->base().structure);
    for (const auto& axis : spec.axes)
      for (const auto& c : spec.channel_columns)
        if (axis.name == c.name)
          throw InputError(r.name() + ":" + std::to_string(axis.line) + ": axis name \"" + axis.name +
                           "\" is already a column of the table; give the axis another name = \"...\"");
  } else {
    (void)scenes->base();
  }
  spec.fingerprint = sweep_fingerprint(text, base_text);
  return spec;
}

std::string sweep_fingerprint(const std::string& text, const std::string& base_text) {
  std::uint64_t hash = 14695981039346656037ull;
  hash = fnv1a(hash, text);
  hash = fnv1a(hash, std::string(1, '\0') + base_text);
  hash = fnv1a(hash, std::string(1, '\0') + ADJOIN_VERSION);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

SweepSpec load_sweep(const std::filesystem::path& file) {
  SweepSpec spec = parse_sweep(read_text_file(file, "sweep"), file.string());
  spec.file = file;
  return spec;
}

}  // namespace adjoin
