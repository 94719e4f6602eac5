#pragma once
// Internal to io: reading a scene's parsed TOML (scene.cpp, ground_sources/). Typed values by
// dotted key, and errors worded with the file and line of the key or the --set that put it
// there.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "adjoin/core/errors.hpp"

namespace adjoin::detail {

// The type a scene key takes (the schema's, scene.cpp; a ground source's keys).
enum class Kind { number, integer, string, boolean, numbers, strings };

// Reads typed values out of the parsed (and overridden) TOML, and words errors with the file
// and line of the key, or the --set option that put it there. `lines`: the parsed file the
// table was copied from (a copy's nodes do not keep their lines), or null.
class SceneReader {
 public:
  SceneReader(toml::table table, std::string name, std::map<std::string, std::string> origins,
              const toml::table* lines = nullptr)
      : table_(std::move(table)), name_(std::move(name)), origins_(std::move(origins)), lines_(lines) {}

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw InputError(where(key) + message, field_path(key));
  }

  // "FILE:LINE: " for the key (or its nearest existing parent), or "--set K=V: ".
  std::string where(const std::string& key) const {
    for (std::string k = key; !k.empty();) {
      if (auto it = origins_.find(k); it != origins_.end()) return it->second + ": ";
      if (auto node = table_.at_path(k); node) {
        // A key no edit made is the file's: its line is in the parsed file.
        const toml::node* original = lines_ ? lines_->at_path(k).node() : nullptr;
        const auto& source = (original ? original : node.node())->source();
        if (source.begin.line > 0) return name_ + ":" + std::to_string(source.begin.line) + ": ";
      }
      const auto dot = k.rfind('.');
      k = dot == std::string::npos ? std::string() : k.substr(0, dot);
    }
    return name_ + ": ";
  }

  bool has(const std::string& key) const { return static_cast<bool>(table_.at_path(key)); }
  bool overridden(const std::string& key) const { return origins_.count(key) > 0; }
  const std::string& name() const { return name_; }

  double number(const std::string& key) const {
    auto node = table_.at_path(key);
    if (!node) fail(key, "missing key " + key + " (a number)");
    return *node.value<double>();  // types were checked against the schema
  }
  double number(const std::string& key, double fallback) const {
    return has(key) ? number(key) : fallback;
  }
  std::string string(const std::string& key, const std::string& fallback) const {
    auto node = table_.at_path(key);
    return node ? *node.value<std::string>() : fallback;
  }
  bool boolean(const std::string& key, bool fallback) const {
    auto node = table_.at_path(key);
    return node ? *node.value<bool>() : fallback;
  }
  std::int64_t integer(const std::string& key, std::int64_t fallback) const {
    auto node = table_.at_path(key);
    return node ? *node.value<std::int64_t>() : fallback;
  }
  std::vector<double> numbers(const std::string& key) const {
    std::vector<double> out;
    if (auto node = table_.at_path(key); node && node.is_array())
      for (const auto& v : *node.as_array()) out.push_back(*v.value<double>());
    return out;
  }
  std::vector<std::string> strings(const std::string& key) const {
    std::vector<std::string> out;
    if (auto node = table_.at_path(key); node && node.is_array())
      for (const auto& v : *node.as_array()) out.push_back(*v.value<std::string>());
    return out;
  }
  const toml::table& table() const { return table_; }

 private:
  toml::table table_;
  std::string name_;
  std::map<std::string, std::string> origins_;
  const toml::table* lines_;
};

// A number as the scene's messages write it (scene.cpp's format_number).
std::string format_scene_number(double v);

}  // namespace adjoin::detail
