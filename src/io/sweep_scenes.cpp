#include "adjoin/io/sweep_scenes.hpp"

#include <filesystem>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/two_block_names.hpp"
#include "sweep_scene_tree.hpp"
#include "toml_text.hpp"

namespace adjoin {
namespace {

// The run's edits as --set / --unset strings, with the unsets an edit implies (ground.source
// to another source drops the base's [ground] keys; io/scene.hpp implied_unsets), the ground
// source being the one the edits so far leave.
void gather_edits(const std::string& base_source, const std::vector<SweepSetting>& settings,
                  std::vector<std::string>& overrides, std::vector<std::string>& unsets) {
  std::string source = base_source;
  for (const auto& s : settings) {
    for (auto& o : s.overrides()) overrides.push_back(std::move(o));
    unsets.insert(unsets.end(), s.unset.begin(), s.unset.end());
    for (const auto& [key, value] : s.set) {
      for (auto& k : implied_unsets(key, value.text, source)) unsets.push_back(std::move(k));
      if (key == "ground.source") {
        const auto* text = std::get_if<std::string>(&value.value);
        source = text ? *text : std::string();
      }
    }
  }
}

// An edit's value as the scene reader takes it: {"v" = value}.
toml::table typed_value(const SweepValue& value) {
  toml::table holder;
  if (const auto* items = std::get_if<std::vector<SweepScalar>>(&value.value)) {
    toml::array list;
    for (const auto& item : *items) std::visit([&](const auto& v) { list.push_back(v); }, item);
    holder.insert("v", std::move(list));
    return holder;
  }
  std::visit(
      [&](const auto& v) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(v)>, std::vector<SweepScalar>>) holder.insert("v", v);
      },
      value.value);
  return holder;
}

std::string at(const SweepSpec& spec, std::size_t line) {
  return spec.file.string() + (line ? ":" + std::to_string(line) : std::string()) + ": ";
}

// Whether `field` (InputError::field) is the key `key` edits or lies inside or above it: an
// edit of link.1.slip_ratio is blamed for an error about link[1].slip_ratio, and an edit of
// link.1 (or an unset of contact.1.stiffness) for one about link[1] (contact[1]).
bool touches(const std::string& key, const std::string& field) {
  if (field.empty()) return false;
  const std::string path = field_path(key);
  const auto below = [](const std::string& inner, const std::string& outer) {
    return inner.size() > outer.size() && inner.rfind(outer, 0) == 0 && (inner[outer.size()] == '.' || inner[outer.size()] == '[');
  };
  return path == field || below(field, path) || below(path, field);
}

// The sweep file's line of the first axis value or motion whose edit touches `field` (0: none).
std::size_t line_of_edit(const std::vector<SweepSetting>& settings, const std::string& field) {
  for (const auto& s : settings) {
    for (const auto& [key, value] : s.set)
      if (touches(key, field)) return s.line;
    for (const auto& key : s.unset)
      if (touches(key, field)) return s.line;
  }
  return 0;
}

}  // namespace

// The base scene's tree, parsed once: each run reads a copy with its edits (a two-block scene's
// set as typed values; a building scene's made as --set makes them, io/structure_edits.hpp),
// and messages cite the lines of this tree.
struct SceneSweepScenes::Base {
  std::filesystem::path file;
  std::string name;  // file, as messages spell it
  std::string source;  // its ground.source ("" if it has none)
  bool building = false;
  toml::table tree;
};

SceneSweepScenes::SceneSweepScenes(const SweepSpec& spec, const std::string& base_text) {
  auto base = std::make_unique<Base>();
  base->file = spec.base;
  base->name = spec.base.string();
  base->tree = detail::parse_toml_text(base_text, base->name);
  base->source = base->tree.at_path("ground.source").value_or(std::string());
  base->building = base->tree.contains("building");
  base_ = std::move(base);
}

SceneSweepScenes::~SceneSweepScenes() = default;

bool SceneSweepScenes::building() const { return base_->building; }

const std::vector<SweepChannel>* SceneSweepScenes::presented_channels() const {
  return building() ? nullptr : &two_block_sweep_channels();
}

RunSpec SceneSweepScenes::base() const {
  if (base_->building) return detail::building_scene_from_tree(base_->tree, base_->file, {}, {});
  return detail::scene_from_tree(base_->tree, base_->name, {}, {}, &base_->tree);
}

RunSpec SceneSweepScenes::scene(const SweepSpec& spec, std::size_t index) const {
  if (base_->building) return building_scene(spec, index);
  const auto settings = spec.settings(index);
  std::vector<std::string> overrides, unset;
  gather_edits(base_->source, settings, overrides, unset);
  // The same edits typed (overrides holds them in this order), set on a copy of the base tree.
  std::vector<toml::table> values;
  std::vector<bool> keyed;  // a key with '=' in it is split as --set splits it: its text is read
  for (const auto& s : settings)
    for (const auto& [key, value] : s.set) {
      values.push_back(typed_value(value));
      keyed.push_back(key.find('=') == std::string::npos);
    }
  std::vector<detail::SceneEdit> edits;
  for (std::size_t i = 0; i < overrides.size(); ++i) edits.push_back({overrides[i], keyed[i] ? &values[i] : nullptr});
  try {
    RunSpec scene = detail::scene_from_tree(base_->tree, base_->name, edits, unset, &base_->tree);
    scene.file = spec.base;
    return scene;
  } catch (const InputError& e) {
    throw InputError(at(spec, line_of_edit(settings, e.field())) + "run " + std::to_string(index) + " (" +
                         spec.describe(index) + "): " + e.what(),
                     e.field());
  }
}

RunSpec SceneSweepScenes::building_scene(const SweepSpec& spec, std::size_t index) const {
  const auto settings = spec.settings(index);
  std::vector<std::string> overrides, unsets;
  gather_edits(base_->source, settings, overrides, unsets);
  try {
    return detail::building_scene_from_tree(base_->tree, spec.base, overrides, unsets);
  } catch (const InputError& e) {
    throw InputError(at(spec, line_of_edit(settings, e.field())) + "run " + std::to_string(index) + " (" +
                         spec.describe(index) + "): " + e.what(),
                     e.field());
  }
}

}  // namespace adjoin
