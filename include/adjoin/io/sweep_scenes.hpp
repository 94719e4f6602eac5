#pragma once
// io's SweepScenes (study/sweep.hpp): the description of a sweep's run from its base scene and
// the run's edits, read exactly as `adjoin run BASE --set KEY=VALUE ... --unset KEY ...` reads
// it (the edits' implied unsets too: io/scene.hpp implied_unsets), with messages prefixed by
// the sweep file, the line of the axis value or motion whose edit caused them, and the run.
// parse_sweep() gives every spec one.
#include <memory>

#include "adjoin/study/sweep.hpp"

namespace adjoin {

class SceneSweepScenes final : public SweepScenes {
 public:
  // Reads spec.base_text (spec.base names it in messages): its syntax errors are InputError
  // "BASE:LINE: not valid TOML: ...".
  explicit SceneSweepScenes(const SweepSpec& spec);
  ~SceneSweepScenes() override;
  // The base scene without edits (a two-block base), checked as `adjoin run BASE` checks it.
  RunSpec base() const;
  RunSpec scene(const SweepSpec& spec, std::size_t index) const override;
  BuildingRunSpec building_scene(const SweepSpec& spec, std::size_t index) const override;

 private:
  struct Base;
  std::unique_ptr<const Base> base_;
};

}  // namespace adjoin
