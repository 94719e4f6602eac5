#pragma once
// The paper's scenes and their trajectories, for the solver's tests.
#include <string>
#include <vector>

#include "adjoin/io/scene.hpp"
#include "adjoin/observe/time_series.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin::test {

// records/scenes/paper-<which>.toml ("strong" or "weak") with `--set` style overrides.
inline Scene paper_scene(const char* which, std::vector<std::string> overrides = {}) {
  return load_scene(std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/paper-" + which + ".toml", overrides);
}

// Every grid point of a run of the scene.
inline std::vector<State> trajectory(const Scene& scene) {
  TimeSeriesRecorder recorder;
  run(scene, {nullptr, &recorder});
  return recorder.states();
}

}  // namespace adjoin::test
