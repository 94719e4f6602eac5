// The run facade of the Python package (python/src/run_facade.hpp) from C++, without Python:
// runs made from several threads at once (as adjoin.run_many makes them) give the texts of
// serial runs. CI's ThreadSanitizer stage runs this program.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "adjoin/core/errors.hpp"
#include "run_facade.hpp"

namespace {

using adjoin::python::LoadedScene;
using adjoin::python::RunTexts;

// summary.json without its lines of wall-clock times (the only values that are the clock's).
std::string without_wall_time(const std::string& json) {
  std::istringstream lines(json);
  std::string out, line;
  while (std::getline(lines, line))
    if (line.find("wall_seconds") == std::string::npos) out += line + "\n";
  return out;
}

std::vector<LoadedScene> scenes() {
  const std::string dir = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/";
  std::vector<LoadedScene> out;
  for (const char* mu : {"0.1", "0.2", "0.3", "0.4", "0.5", "0.6"})
    out.push_back(adjoin::python::load_scene_file(dir + "paper-strong.toml",
                                                  {std::string("model.mu=") + mu, "solver.t_end=4", "output.timeseries=true"}, {}));
  for (const char* ratio : {"0.05", "0.1"})
    out.push_back(adjoin::python::load_scene_file(dir + "buildings/two-frames.toml",
                                                  {std::string("link.1.slip_ratio=") + ratio, "solver.t_end=3"}, {}));
  return out;
}

}  // namespace

TEST_CASE("run facade: 8 runs on 2 threads give the serial runs' texts", "[python]") {
  const std::vector<LoadedScene> all = scenes();
  std::vector<RunTexts> serial;
  for (const auto& s : all) serial.push_back(adjoin::python::run(s, {}));

  std::vector<RunTexts> threaded(all.size());
  const auto work = [&](std::size_t first) {
    for (std::size_t i = first; i < all.size(); i += 2) threaded[i] = adjoin::python::run(all[i], {});
  };
  std::thread other(work, 1);
  work(0);
  other.join();

  for (std::size_t i = 0; i < all.size(); ++i) {
    INFO("scene " << i << " (" << all[i].name() << ")");
    CHECK(without_wall_time(threaded[i].summary_json) == without_wall_time(serial[i].summary_json));
    CHECK(threaded[i].timeseries_csv == serial[i].timeseries_csv);
    CHECK(!serial[i].timeseries_csv.empty());
  }
  CHECK(all.back().building());
  CHECK(serial[0].summary_json != serial[1].summary_json);  // the scenes differ, so must their runs
}

TEST_CASE("run facade: a scene's errors are the reader's, with the field", "[python]") {
  const std::string file = std::string(ADJOIN_SOURCE_DIR) + "/records/scenes/buildings/two-frames.toml";
  try {
    adjoin::python::load_scene_file(file, {"link.1.slip_ratio=-1"}, {});
    FAIL("a negative slip ratio was accepted");
  } catch (const adjoin::InputError& e) {
    CHECK(e.field() == "link[1].slip_ratio");
  }
}
