#include "structure_edits.hpp"

#include <cctype>
#include <set>
#include <sstream>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"
#include "adjoin/io/text_file.hpp"
#include "adjoin/structure/contact_rules.hpp"
#include "element_keys.hpp"
#include "toml_text.hpp"

namespace adjoin::detail {
namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

std::vector<std::string> split_path(const std::string& key, const std::string& origin) {
  std::vector<std::string> parts;
  std::stringstream stream(key);
  for (std::string part; std::getline(stream, part, '.');) {
    if (part.empty()) throw InputError(origin + ": empty component in key " + escaped_excerpt(key));
    parts.push_back(part);
  }
  if (parts.empty()) throw InputError(origin + ": expected a dotted key, e.g. link.1.slip_ratio");
  return parts;
}

// A table's number in a key path (link.2): up to six digits.
bool is_index(const std::string& part, std::size_t* n = nullptr) {
  std::size_t value = 0;
  if (part.size() > 6 || !parse_count(part, &value)) return false;
  if (n) *n = value;
  return true;
}

// Walks `parts` from `root` to the parent of the last part: a table, and the reader's path of it
// ("building.A.device[2]"). Arrays of tables are indexed by a number counted from 1.
struct Parent {
  toml::node* node = nullptr;  // a table or an array
  std::string path;
};

// The lists of tables a --set may lengthen: `link.N.KEY`, `contact.N.KEY` and
// `building.X.device.N.KEY` with N one more than the tables there are add a table (the first
// one creates the list), so that a sweep can add a damper the base lacks.
bool is_growable(const std::string& name) { return name == "link" || name == "contact" || name == "device"; }

std::string tables_text(std::size_t n, const std::string& path) {
  return std::to_string(n) + " [[" + path + "]] table" + (n == 1 ? "" : "s");
}

// `grow`: a --set, which may add the next table of a growable list (see is_growable).
Parent walk(toml::table& root, const std::vector<std::string>& parts, const std::string& origin, bool grow = false) {
  toml::node* current = &root;
  std::string path;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& part = parts[i];
    toml::node* next = nullptr;
    if (toml::array* array = current->as_array()) {
      std::size_t n = 0;
      if (!is_index(part, &n))
        throw InputError(origin + ": " + path + " is a list of tables: number them from 1, e.g. " + path + ".1");
      const bool growable = grow && is_growable(parts[i - 1]) && (array->empty() || array->is_array_of_tables());
      if (growable && n == array->size() + 1) array->push_back(toml::table{});
      if (n < 1 || n > array->size()) {
        const std::string next_one =
            growable && n > array->size() ? " (a --set adds the next one, number " + std::to_string(array->size() + 1) + ")" : "";
        throw InputError(origin + ": the scene has " + tables_text(array->size(), path) + ", not a number " +
                         text_excerpt(part) + next_one);
      }
      next = array->get(n - 1);
      path += "[" + part + "]";
    } else if (toml::table* table = current->as_table()) {
      next = table->get(part);
      if (!next && grow && is_growable(part) && i + 2 < parts.size() && parts[i + 1] == "1") {
        table->insert(part, toml::array{});
        next = table->get(part);
      }
      if (!next) throw InputError(origin + ": the scene has no " + text_excerpt(path.empty() ? part : path + "." + part));
      path += (path.empty() ? "" : ".") + part;
    } else {
      throw InputError(origin + ": " + path + " is a value, not a table");
    }
    current = next;
  }
  return {current, path};
}

// The alternatives a key replaces in its table.
std::vector<std::string> alternatives(const std::string& key) {
  if (key == "stiffness") return {"stiffnesses", "period"};
  if (key == "stiffnesses") return {"stiffness", "period"};
  if (key == "period") return {"stiffness", "stiffnesses"};
  if (key == "mass") return {"masses"};
  if (key == "masses") return {"mass"};
  if (key == "height") return {"heights"};
  if (key == "heights") return {"height"};
  if (key == "slip_force") return {"slip_ratio", "of"};
  if (key == "slip_ratio") return {"slip_force"};
  if (key == "yield_force") return {"yield_forces", "yield_drift_ratio"};  // (building.X.hysteresis)
  if (key == "yield_forces") return {"yield_force", "yield_drift_ratio"};
  if (key == "yield_drift_ratio") return {"yield_force", "yield_forces"};
  return {};
}

void unset(toml::table& root, const std::string& key) {
  const std::string origin = "--unset " + text_excerpt(key);
  const auto parts = split_path(key, origin);
  const Parent parent = walk(root, parts, origin);
  const std::string& leaf = parts.back();
  if (toml::array* array = parent.node->as_array()) {
    std::size_t n = 0;
    if (!is_index(leaf, &n)) throw InputError(origin + ": number the [[" + parent.path + "]] tables from 1");
    if (n < 1 || n > array->size())
      throw InputError(origin + ": the scene has " + tables_text(array->size(), parent.path) + ", no number " +
                       text_excerpt(leaf) + " to remove");
    array->erase(array->begin() + static_cast<std::ptrdiff_t>(n - 1));
  } else if (toml::table* table = parent.node->as_table()) {
    if (!table->contains(leaf))
      throw InputError(origin + ": the scene has no key or section " + text_excerpt(key));
    table->erase(leaf);
  } else {
    throw InputError(origin + ": " + parent.path + " is a value, not a table");
  }
}

// A link's or device's new `type` drops the keys that type does not take (element_keys.hpp),
// not those another --set put there (a contradiction the reader reports, naming that --set).
void drop_other_type_keys(toml::table& table, const std::string& path, const toml::table& holder,
                          const std::map<std::string, std::string>& origins) {
  const auto word = holder["v"].value<std::string>();
  if (!word) return;  // the reader names a type that is not a word
  const bool link = path.rfind("link[", 0) == 0;
  const bool device = path.find(".device[") != std::string::npos;
  std::set<std::string> keys;
  if (structure::LinkType type; link && parse_enum(*word, &type)) keys = link_keys(type);
  if (structure::DeviceType type; device && parse_enum(*word, &type)) keys = device_keys(type);
  if (keys.empty()) return;  // not a link or device, or an unknown type (the reader lists the types)
  std::vector<std::string> dropped;
  for (const auto& [key, node] : table)
    if (!keys.count(std::string(key.str())) && !origins.count(path + "." + std::string(key.str())))
      dropped.emplace_back(key.str());
  for (const auto& key : dropped) table.erase(key);
}

void set(toml::table& root, const std::string& text, std::map<std::string, std::string>& origins) {
  const std::string origin = "--set " + text_excerpt(text);
  const auto eq = text.find('=');
  const std::string key = trim(text.substr(0, eq)), value = trim(text.substr(eq + 1));
  if (eq == std::string::npos || key.empty())
    throw InputError(origin + ": expected KEY=VALUE with a dotted key, e.g. building.A.mass=4.5e4");
  const auto parts = split_path(key, origin);
  const Parent parent = walk(root, parts, origin, true);
  toml::table* table = parent.node->as_table();
  if (!table) throw InputError(origin + ": " + parent.path + " is a list: name one of its tables by number");
  const toml::table holder = toml_value_of(value);
  if (parts.back() == "type") drop_other_type_keys(*table, parent.path, holder, origins);
  const bool contact = parent.path.rfind("contact[", 0) == 0;
  if (!contact)
    for (const auto& other : alternatives(parts.back())) table->erase(other);
  // A contact law's restitution and damping replace each other, and a model drops the keys
  // it does not take (structure/contact_rules.hpp), as editing the file would; not those another --set
  // put there (that is a contradiction the reader reports).
  if (contact) {
    std::vector<std::string> dropped;
    if (parts.back() == "restitution") dropped = {"damping"};
    if (parts.back() == "damping") dropped = {"restitution"};
    structure::ContactModel model;
    if (parts.back() == "model")
      if (const auto word = holder["v"].value<std::string>(); word && parse_enum(*word, &model))
        dropped = structure::contact_keys_refused(model);
    for (const auto& other : dropped)
      if (!origins.count(parent.path + "." + other)) table->erase(other);
  }
  table->insert_or_assign(parts.back(), *holder.get("v"));
  origins[parent.path + "." + parts.back()] = origin;
}

}  // namespace

bool is_structure_key(const std::string& key) {
  const std::string k = trim(key);
  for (const char* section : {"building", "link", "contact"}) {
    const std::string s(section);
    if (k == s || k.rfind(s + ".", 0) == 0) return true;
  }
  return false;
}

void edit_structure(toml::table& root, const std::vector<std::string>& overrides, const std::vector<std::string>& unsets,
                    std::map<std::string, std::string>& origins) {
  // An edit that cannot be made is an error about the key it names (its field).
  const auto about = [](const std::string& key, auto&& edit) {
    try {
      edit();
    } catch (const InputError& e) {
      if (!e.field().empty()) throw;
      throw InputError(e.what(), field_path(trim(key)));
    }
  };
  for (const auto& key : unsets)
    if (is_structure_key(key)) about(key, [&] { unset(root, trim(key)); });
  for (const auto& o : overrides) {
    const std::string key = o.substr(0, o.find('='));
    if (is_structure_key(key)) about(key, [&] { set(root, o, origins); });  // (one without '=' is refused there)
  }
}

}  // namespace adjoin::detail
