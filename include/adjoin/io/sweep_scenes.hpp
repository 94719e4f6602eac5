#pragma once
// io's SweepScenes (study/sweep.hpp): the description of a sweep's run from its base scene and
// the run's edits, read exactly as `adjoin run BASE --set KEY=VALUE ... --unset KEY ...` reads
// it (the edits' implied unsets too: io/scene.hpp implied_unsets), with messages prefixed by
// the sweep file, the line of the axis value or motion whose edit caused them, and the run.
// parse_sweep() (io/sweep_file.hpp) gives every spec one.
#include <memory>
#include <string>

#include "adjoin/study/sweep.hpp"

namespace adjoin {

class SceneSweepScenes final : public SweepScenes {
 public:
  // Parses the base scene's text (spec.base names it in messages): its syntax errors are
  // InputError "BASE:LINE: not valid TOML: ...".
  SceneSweepScenes(const SweepSpec& spec, const std::string& base_text);
  ~SceneSweepScenes() override;
  // True if the base is a building scene (SPEC §5: it has a [building] table).
  bool building() const;
  // The base scene without edits, checked as `adjoin run BASE` checks it.
  RunSpec base() const;
  RunSpec scene(const SweepSpec& spec, std::size_t index) const override;
  // A two-block base: SPEC §3's columns (io/two_block_names.hpp two_block_sweep_channels).
  const std::vector<SweepChannel>* presented_channels() const override;

 private:
  // A building base's run: its edits made as --set makes them (io/structure_edits.hpp).
  RunSpec building_scene(const SweepSpec& spec, std::size_t index) const;
  struct Base;
  std::unique_ptr<const Base> base_;
};

}  // namespace adjoin
