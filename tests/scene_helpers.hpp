#pragma once
// The paper's scenes and their trajectories, for the solver's tests.
#include <string>
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"
#include "state_recorder.hpp"

namespace adjoin::test {

// records/scenes/paper-<which>.toml ("strong" or "weak") with `--set` style overrides.
inline Scene paper_scene(const char* which, std::vector<std::string> overrides = {}) {
  return load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-" + which + ".toml", overrides);
}

// Every grid point of a run of the scene: a two-block scene's as its 1 + 1 structure's states
// (state_recorder.hpp), in the scene's units.
inline std::vector<StructureState> trajectory(const Scene& scene) {
  StateRecorder recorder;
  run(scene, {&recorder});
  return recorder.states;
}

}  // namespace adjoin::test
