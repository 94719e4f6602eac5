// io/scene.hpp and io/building_scene.hpp in Python: adjoin.Scene, adjoin.load_scene.
//
// A scene from a dict is turned into TOML text (toml++) and read by the scene readers
// themselves, so a dict is checked exactly as a file is and its errors are the reader's
// (InputError with the dotted key in .field). A Scene keeps the TOML it was read from and its
// `set`/`unset` edits, for to_dict() and to_toml().
#include <filesystem>
#include <optional>
#include <sstream>

#include <toml++/toml.h>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/text_file.hpp"
#include "bindings.hpp"
#include "run_facade.hpp"
#include "scene_object.hpp"

namespace adjoin::python {

namespace fs = std::filesystem;

namespace {

// ---- Python values -> TOML nodes (the scene's schema: nested dicts, lists of dicts) ----

toml::table table_from_dict(const py::dict& d, const std::string& path);

std::string child_path(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

std::unique_ptr<toml::node> node_from(const py::handle& value, const std::string& path) {
  if (py::isinstance<py::bool_>(value)) return std::make_unique<toml::value<bool>>(value.cast<bool>());
  if (py::isinstance<py::int_>(value)) {
    try {
      return std::make_unique<toml::value<int64_t>>(value.cast<int64_t>());
    } catch (const py::cast_error&) {
      throw InputError(path + ": the integer is too large for a scene value (64 bits)", path);
    }
  }
  if (py::isinstance<py::float_>(value)) return std::make_unique<toml::value<double>>(value.cast<double>());
  if (py::isinstance<py::str>(value)) return std::make_unique<toml::value<std::string>>(value.cast<std::string>());
  if (py::isinstance<py::dict>(value)) return std::make_unique<toml::table>(table_from_dict(value.cast<py::dict>(), path));
  if (py::hasattr(value, "dtype") && py::hasattr(value, "tolist")) return node_from(value.attr("tolist")(), path);
  if (py::isinstance<py::sequence>(value) && !py::isinstance<py::bytes>(value)) {
    auto array = std::make_unique<toml::array>();
    std::size_t i = 0;
    for (const py::handle item : value.cast<py::sequence>()) {
      auto node = node_from(item, path + "." + std::to_string(++i));
      array->push_back(std::move(*node));
    }
    return array;
  }
  if (value.is_none()) throw InputError(path + ": None is not a scene value (leave the key out)", path);
  if (py::hasattr(value, "__index__")) return node_from(py::int_(py::reinterpret_borrow<py::object>(value)), path);
  if (py::hasattr(value, "__float__")) return node_from(py::float_(py::reinterpret_borrow<py::object>(value)), path);
  throw InputError(path + ": a " + std::string(py::str(value.get_type().attr("__name__"))) +
                       " is not a scene value (expected a number, string, bool, list or dict)",
                   path);
}

toml::table table_from_dict(const py::dict& d, const std::string& path) {
  toml::table t;
  for (const auto& [key, value] : d) {
    if (!py::isinstance<py::str>(key))
      throw InputError(child_path(path, std::string(py::str(key))) + ": keys must be strings", path);
    const std::string k = key.cast<std::string>();
    auto node = node_from(value, child_path(path, k));
    t.insert(k, std::move(*node));
  }
  return t;
}

// ---- TOML nodes -> Python values ----

py::object object_from(const toml::node& node) {
  if (const auto* t = node.as_table()) {
    py::dict d;
    for (const auto& [k, v] : *t) d[py::str(std::string(k.str()))] = object_from(v);
    return d;
  }
  if (const auto* a = node.as_array()) {
    py::list l;
    for (const auto& v : *a) l.append(object_from(v));
    return l;
  }
  if (const auto* v = node.as_boolean()) return py::bool_(v->get());
  if (const auto* v = node.as_integer()) return py::int_(v->get());
  if (const auto* v = node.as_floating_point()) return py::float_(v->get());
  if (const auto* v = node.as_string()) return py::str(v->get());
  std::ostringstream text;  // dates and times: as written
  node.visit([&](const auto& n) { text << n; });
  return py::str(text.str());
}

std::string toml_text(const toml::table& t) {
  std::ostringstream out;
  out << t << "\n";
  return out.str();
}

// A Python value as the text of a --set value ("0.001", "'record'", "[1, 2]").
std::string value_text(const py::handle& value, const std::string& key) {
  toml::table holder;
  auto node = node_from(value, key);
  holder.insert("v", std::move(*node));
  std::string text = toml_text(holder);
  const std::size_t eq = text.find('=');
  text = text.substr(eq + 1);
  const std::size_t first = text.find_first_not_of(" "), last = text.find_last_not_of(" \n");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> overrides_of(const std::optional<py::dict>& set) {
  std::vector<std::string> out;
  if (!set) return out;
  for (const auto& [key, value] : *set) {
    const std::string k = py::str(key);
    out.push_back(k + "=" + value_text(value, k));
  }
  return out;
}

// ---- the edits of load_scene(set=, unset=) on the TOML tree, for to_dict() ----

// The node at a dotted path ("link.2.slip_ratio": lists counted from 1), its parent and leaf.
toml::node* child(toml::node* parent, const std::string& part) {
  if (auto* t = parent->as_table()) return t->get(part);
  if (auto* a = parent->as_array()) {
    const std::size_t i = part.find_first_not_of("0123456789") == std::string::npos ? std::stoul(part) : 0;
    return i >= 1 && i <= a->size() ? a->get(i - 1) : nullptr;
  }
  return nullptr;
}

std::vector<std::string> parts_of(const std::string& key) {
  std::vector<std::string> parts;
  std::stringstream s(key);
  for (std::string p; std::getline(s, p, '.');) parts.push_back(p);
  return parts;
}

void remove_path(toml::table& root, const std::string& key) {
  const auto parts = parts_of(key);
  if (parts.empty()) return;
  toml::node* parent = &root;
  for (std::size_t i = 0; i + 1 < parts.size() && parent; ++i) parent = child(parent, parts[i]);
  if (!parent) return;
  if (auto* t = parent->as_table()) t->erase(parts.back());
  if (auto* a = parent->as_array()) {
    const std::size_t i = parts.back().find_first_not_of("0123456789") == std::string::npos ? std::stoul(parts.back()) : 0;
    if (i >= 1 && i <= a->size()) a->erase(a->begin() + static_cast<std::ptrdiff_t>(i - 1));
  }
}

void set_path(toml::table& root, const std::string& key, const std::string& value) {
  toml::table holder;
  try {
    holder = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    holder.insert("v", value);  // a bare word is a string, as on the command line
  }
  const auto parts = parts_of(key);
  toml::node* current = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* next = child(current, parts[i]);
    if (!next && current->is_table()) {
      current->as_table()->insert(parts[i], toml::table{});
      next = current->as_table()->get(parts[i]);
    }
    if (!next) return;  // the reader refused this edit when the scene was loaded
    current = next;
  }
  if (auto* t = current->as_table()) t->insert_or_assign(parts.back(), *holder.get("v"));
}

std::string source_of(const toml::table& root) {
  const auto* s = root.at_path("ground.source").as_string();
  return s ? s->get() : std::string("decaying-sine");
}

// Relative record and table paths of the text are relative to its folder; in a dict they
// would be relative to the working folder, so to_dict() gives them whole.
void absolute_paths(toml::table& root, const fs::path& folder) {
  for (const char* key : {"ground.file", "ground.match_table"})
    if (auto* s = root.at_path(key).as_string(); s && fs::path(s->get()).is_relative())
      *s = (fs::absolute(folder) / s->get()).lexically_normal().string();
}

// The scene's tree with load_scene's edits: a building scene's structure keys by io's own
// rules (run_facade.hpp), the others as --set and --unset make them (dotted paths, and the
// keys a new ground source or contact law drops: implied_unsets).
toml::table edited_tree(const SceneObject& s) {
  toml::table root = toml::parse(s.text, s.file.string());
  absolute_paths(root, s.file.parent_path());
  const bool building = s.loaded.building();
  const auto by_io = [&](const std::string& key) { return building && is_structure_edit(key); };
  if (building) edit_structure_keys(root, s.overrides, s.unsets);
  for (const auto& key : s.unsets)
    if (!by_io(key)) remove_path(root, key);
  for (const auto& o : s.overrides) {
    const std::size_t eq = o.find('=');
    const std::string key = o.substr(0, eq), value = o.substr(eq + 1);
    if (by_io(key)) continue;
    for (const auto& k : implied_unsets(key, value, source_of(root))) remove_path(root, k);
    set_path(root, key, value);
  }
  return root;
}

SceneObject load_scene_py(const std::string& path, const std::optional<py::dict>& set,
                          const std::optional<std::vector<std::string>>& unset) {
  const std::vector<std::string> overrides = overrides_of(set);
  const std::vector<std::string> unsets = unset.value_or(std::vector<std::string>{});
  LoadedScene loaded = load_scene_file(path, overrides, unsets);  // first: its errors are the reader's
  return SceneObject{std::move(loaded), read_text_file(path, "scene"), fs::path(path), overrides, unsets};
}

SceneObject from_dict(const py::dict& d, const std::optional<std::string>& folder, const std::string& name) {
  const std::string text = toml_text(table_from_dict(d, ""));
  const fs::path file = fs::path(folder.value_or(fs::current_path().string())) / name;
  return SceneObject{parse_scene_text(text, file, {}, {}), text, file, {}, {}};
}

SceneObject from_toml(const std::string& text, const std::optional<std::string>& folder, const std::string& name) {
  const fs::path file = fs::path(folder.value_or(fs::current_path().string())) / name;
  return SceneObject{parse_scene_text(text, file, {}, {}), text, file, {}, {}};
}

}  // namespace

void bind_io(py::module_& m) {
  py::class_<SceneObject>(m, "Scene")
      .def_static("from_dict", &from_dict, py::arg("d"), py::kw_only(), py::arg("folder") = py::none(),
                  py::arg("name") = "<dict>")
      .def_static("from_toml", &from_toml, py::arg("text"), py::kw_only(), py::arg("folder") = py::none(),
                  py::arg("name") = "<text>")
      .def("to_dict", [](const SceneObject& s) { return object_from(edited_tree(s)); })
      .def("to_toml", [](const SceneObject& s) { return toml_text(edited_tree(s)); })
      .def_property_readonly("name", [](const SceneObject& s) { return s.loaded.name(); })
      .def_property_readonly("building", [](const SceneObject& s) { return s.loaded.building(); })
      .def_property_readonly("warnings", [](const SceneObject& s) { return s.loaded.warnings(); })
      .def_property_readonly("file", [](const SceneObject& s) { return s.file.string(); })
      .def("__repr__", [](const SceneObject& s) {
        return std::string("<adjoin.Scene '") + s.loaded.name() + "' (" + (s.loaded.building() ? "building" : "two-block") +
               ") from " + s.file.string() + ">";
      });
  m.def("load_scene", &load_scene_py, py::arg("path"), py::kw_only(), py::arg("set") = py::none(),
        py::arg("unset") = py::none());
}

}  // namespace adjoin::python
