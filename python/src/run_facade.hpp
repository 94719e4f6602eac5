#pragma once
// The one place the Python bindings touch the run pipeline (reading a scene, running it, turning
// its report into summary.json, timeseries.csv and impacts.csv). Everything else in python/src
// binds stable, typed parts of the library (records, spectra, modes).
//
// A scene is one RunSpec (study/run_spec.hpp: a building, or the paper's two blocks), read by
// io/scene.hpp load_scene and run by study/run.hpp run(). The texts are the very ones `adjoin
// run` writes (bit for bit): io/run_files.hpp run_to writes them into memory
// (io/run_outputs.hpp MemoryOutputs) instead of a folder; no file is touched.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "adjoin/structure/building.hpp"

namespace adjoin::python {

// A scene read and checked by the library's own scene readers (opaque: either kind of scene).
class LoadedScene {
 public:
  struct Impl;
  explicit LoadedScene(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  const Impl& impl() const { return *impl_; }
  bool building() const;
  const std::string& name() const;
  // Valid but probably unintended choices the reader noticed ("warning: ..." on the CLI).
  const std::vector<std::string>& warnings() const;

 private:
  std::shared_ptr<const Impl> impl_;
};

// Reads a scene file as `adjoin run FILE --set ... --unset ...` does (either kind).
LoadedScene load_scene_file(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                            const std::vector<std::string>& unsets);
// The same from TOML text; `file` names it in messages and its folder is where the scene's
// relative paths (ground.file) start.
LoadedScene parse_scene_text(const std::string& text, const std::filesystem::path& file,
                             const std::vector<std::string>& overrides, const std::vector<std::string>& unsets);

// The --set/--unset edits of a building scene's structure keys (building.*, link.*, contact.*)
// made on its TOML tree by io's own rules (a key replacing its alternative: `period` for
// `stiffness`, a contact model dropping the keys it does not take); the other edits are left
// to the caller. For Scene.to_dict().
bool is_structure_edit(const std::string& key);
void edit_structure_keys(toml::table& root, const std::vector<std::string>& overrides,
                         const std::vector<std::string>& unsets);

// What `adjoin run` would write, as text ("" for a file it would not write).
struct RunTexts {
  std::string summary_json;
  std::string timeseries_csv;
  std::string impacts_csv;
  std::string spectra_csv;
  std::string energy_csv;
  std::string brief;  // what `adjoin run` prints on stdout (without the "wrote ..." line)
};

// Options of one run from Python. `every` 0 keeps the scene's output.every.
struct RunRequest {
  bool timeseries = true;
  std::size_t every = 0;
  // As `adjoin run --allow-long`: run even when the run is estimated at more than 2 hours
  // (refused otherwise, InputError, from the run's first steps: study/run_watch.hpp).
  bool allow_long = false;
};

// Runs the scene as `adjoin run` does (the same step choice, error estimate and files).
// Throws InputError / NumericalError as the library does. Safe to call from several threads at
// once (each run has its own folder).
RunTexts run(const LoadedScene& scene, const RunRequest& request);

// A structure built in code (structure/builder.hpp) run on a record as study/builder.hpp's
// building_run_spec makes the run: the step and horizon given, or chosen by a scene's rules.
// Errors name the fields as that does ("solver.h", "ground.scale_pga").
struct StructureRun {
  std::string name = "building";
  std::filesystem::path record;      // a record file (its format from the file)
  std::optional<double> scale_pga;   // [g]
  double scale = 1.0;                // ground.scale: a plain factor, after scale_pga
  std::optional<double> h, t_end;    // [s]
  std::optional<double> tolerance;   // the peaks' relative error the step is chosen for (not with h)
};
RunTexts run_structure(const structure::Structure& structure, const StructureRun& how, const RunRequest& request);

// The structure of a building scene (its buildings, links, contact pairs); null for a
// two-block scene. Valid as long as `scene` is.
const structure::Structure* structure_of(const LoadedScene& scene);

// The minimum seismic joint of the scene (study/seismic_joint.hpp), as `adjoin joint` finds it:
// of contact pair `contact` (1-based; two-block scenes: 1, the blocks' model.gap0), to the
// bisection tolerance `tol` in the scene's length unit (NaN: 1e-6 of s_max).
struct JointOut {
  std::string scene, gap_key, length_unit, time_unit;
  int contact = 1, floor_a = 1, floor_b = 1;
  double joint = 0.0, joint_low = 0.0, tol = 0.0, bracket_top = 0.0;
  std::size_t runs = 0, widenings = 0;
  double s_max = 0.0, t_critical = 0.0, difference = 0.0;
  bool agree = false;
  double peak_a = 0.0, t_peak_a = 0.0, peak_b = 0.0, t_peak_b = 0.0, srss = 0.0, abs_sum = 0.0, wall_seconds = 0.0;
  std::vector<std::string> notes;
};
JointOut joint(const LoadedScene& scene, int contact, double tol, bool allow_long);

}  // namespace adjoin::python
