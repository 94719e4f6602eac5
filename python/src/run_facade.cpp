// The run pipeline as the Python bindings see it (run_facade.hpp): today's two scene kinds and
// their file writers, wrapped so that a merge with the unified RunSpec / run / Report changes
// this file only.
#include "run_facade.hpp"

#include <cstdio>
#include <map>
#include <sstream>
#include <system_error>

#include <toml++/toml.h>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/io/timeseries_csv.hpp"
#include "adjoin/io/building_scene.hpp"
#include "adjoin/io/run_files.hpp"
#include "adjoin/io/run_outputs.hpp"
#include "adjoin/io/scene.hpp"
#include "adjoin/io/structure_file.hpp"
#include "adjoin/io/summary.hpp"
#include "adjoin/study/builder.hpp"
#include "adjoin/study/run.hpp"
#include "adjoin/study/run_watch.hpp"
#include "adjoin/study/seismic_joint.hpp"
// The rules of structure edits are private to io (src/io/structure_edits.hpp).
#include "../../src/io/structure_edits.hpp"

namespace adjoin::python {

namespace fs = std::filesystem;

struct LoadedScene::Impl {
  Scene spec;
};

bool LoadedScene::building() const { return !impl_->spec.two_block(); }

const std::string& LoadedScene::name() const { return impl_->spec.name; }

const std::vector<std::string>& LoadedScene::warnings() const { return impl_->spec.warnings; }

namespace {

LoadedScene wrap(Scene s) { return LoadedScene(std::make_shared<const LoadedScene::Impl>(LoadedScene::Impl{std::move(s)})); }

// A building scene is one with a [building] table: the rule of io/structure_file.cpp
// is_building_scene, applied to text. A text that is not TOML goes to the two-block reader,
// which reports the syntax error with its line.
bool text_is_building_scene(const std::string& text, const fs::path& file) {
  try {
    return toml::parse(text, file.string()).contains("building");
  } catch (const toml::parse_error&) {
    return false;
  }
}

// The texts a run wrote.
RunTexts texts_in(const MemoryOutputs& out) {
  RunTexts texts;
  texts.summary_json = out.text("summary.json");
  texts.timeseries_csv = out.text("timeseries.csv");
  texts.impacts_csv = out.text("impacts.csv");
  texts.spectra_csv = out.text("spectra.csv");
  texts.energy_csv = out.text("energy.csv");
  return texts;
}

// The watch `adjoin run` gives every run: it refuses a run estimated at more than 2 hours
// (unless allowed) and shows nothing.
RunWatch::Options watching(const RunRequest& request) {
  RunWatch::Options o;
  if (request.allow_long) o.refuse_seconds = 0.0;
  return o;
}

// One run as `adjoin run` makes it (io/run_files.hpp), its files' texts kept in memory.
RunTexts run_scene(Scene scene, const RunRequest& request) {
  scene.output.timeseries = scene.output.timeseries && request.timeseries;
  if (request.every > 0) scene.output.every = request.every;
  check_memory(scene);
  RunWatch::Options o = watching(request);
  o.time_scale = scene.scales.time;
  o.h_unit = scene.scales.si ? " s" : " (dimensionless)";
  RunWatch watch(std::move(o));
  scene.watch = &watch;
  MemoryOutputs out;
  const RunFiles files = run_to(scene, out);
  RunTexts texts = texts_in(out);
  texts.brief = brief_report(scene, files.report, files.estimate ? &*files.estimate : nullptr,
                             files.tolerant ? &*files.tolerant : nullptr);
  return texts;
}

}  // namespace

LoadedScene load_scene_file(const fs::path& file, const std::vector<std::string>& overrides,
                            const std::vector<std::string>& unsets) {
  return wrap(load_scene(file, overrides, unsets));
}

LoadedScene parse_scene_text(const std::string& text, const fs::path& file, const std::vector<std::string>& overrides,
                             const std::vector<std::string>& unsets) {
  if (text_is_building_scene(text, file)) return wrap(parse_building_scene(text, file, overrides, unsets));
  return wrap(parse_scene(text, file.string(), overrides, unsets));
}

bool is_structure_edit(const std::string& key) { return detail::is_structure_key(key); }

void edit_structure_keys(toml::table& root, const std::vector<std::string>& overrides,
                         const std::vector<std::string>& unsets) {
  std::map<std::string, std::string> origins;  // (for the reader's messages; not needed here)
  detail::edit_structure(root, overrides, unsets, origins);
}

RunTexts run(const LoadedScene& scene, const RunRequest& request) { return run_scene(scene.impl().spec, request); }

RunTexts run_structure(const structure::Structure& structure, const StructureRun& how, const RunRequest& request) {
  BuildingRunOptions options;
  options.name = how.name;
  options.h = how.h;
  options.t_end = how.t_end;
  options.tolerance = how.tolerance;
  return run_scene(building_run_spec(structure, scale_ground(record_ground(how.record, how.scale_pga), how.scale), options), request);
}

const structure::Structure* structure_of(const LoadedScene& scene) {
  return scene.building() ? &scene.impl().spec.structure : nullptr;
}

JointOut joint(const LoadedScene& scene, int contact, double tol, bool allow_long) {
  SeismicJointOptions options;
  options.contact = contact;
  options.tol = tol;
  RunWatch watch(watching(RunRequest{true, 0, allow_long}));
  SeismicJoint j;
  if (scene.building()) {
    Scene s = scene.impl().spec;
    check_memory(s);
    const std::size_t n = s.structure.contacts.size();
    if (n == 0) throw InputError(s.name + ": no contact pair: the joint is the gap of a [[contact]] with floors = [i, j]", "contact");
    if (contact < 1 || static_cast<std::size_t>(contact) > n)
      throw InputError("contact = " + std::to_string(contact) + ": the scene has " + std::to_string(n) +
                           " contact pair(s) (expected 1.." + std::to_string(n) + ")", "contact");
    s.watch = &watch;
    j = seismic_joint(s, options);
  } else {
    if (contact != 1)
      throw InputError("contact = " + std::to_string(contact) + ": a two-block scene has one contact pair, the blocks' "
                       "(its gap is model.gap0; expected 1)", "contact");
    j = seismic_joint(scene.impl().spec, options);
  }
  return JointOut{j.scene, j.gap_key, j.length_unit, j.time_unit, j.contact, j.floor_a, j.floor_b, j.joint,
                  j.joint_low, j.tol, j.bracket_top, j.runs, j.widenings, j.s_max, j.t_critical, j.difference,
                  j.agree, j.peak_a, j.t_peak_a, j.peak_b, j.t_peak_b, j.srss, j.abs_sum, j.wall_seconds, j.notes};
}

}  // namespace adjoin::python
