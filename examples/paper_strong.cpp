// The paper's strong-excitation case through the library API, in a few dozen lines:
// load the scene, attach an observer that streams what we want to see, simulate, report.
//
//     paper_strong [SCENE.toml]       (default records/scenes/paper-strong.toml)
#include <adjoin/core/errors.hpp>
#include <adjoin/io/scene.hpp>
#include <adjoin/study/run.hpp>
#include <cmath>
#include <cstdio>

namespace {

// An observer that prints the blocks every 2 time units and remembers the largest |x1 - x2|.
// The scene runs as its 1 + 1 structure, in the scene's units: floor 0 is block 1 (A.x1),
// floor 1 block 2 (B.x1), link 0 the damper.
class Printer final : public adjoin::StructureObserver {
 public:
  void observe(const adjoin::StructureState& s) override {
    max_stroke = std::max(max_stroke, std::abs(s.x[0] - s.x[1]));
    if (std::fmod(s.t + 1e-9, 2.0) < 1e-6)
      std::printf("t = %5.2f  x1 = %+.5f  x2 = %+.5f  q = %+.4f  %s\n", s.t, s.x[0], s.x[1], s.link_force[0],
                  adjoin::to_string(s.link_phase[0]));
  }
  double max_stroke = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  const char* file = argc > 1 ? argv[1] : "records/scenes/paper-strong.toml";
  try {
    const adjoin::Scene scene = adjoin::load_scene(file);
    Printer printer;
    const adjoin::Report report = adjoin::run(scene, {&printer});

    std::printf("\n%zu phases; the damper sticks for good at t* = %.3f\n", report.phases.size(),
                report.phases.back().t_start);
    std::printf("max |x1| = %.5f, max |x2| = %.5f, max damper stroke = %.5f\n", report.peak("A.x1").max_abs,
                report.peak("B.x1").max_abs, printer.max_stroke);
    std::printf("min gap = %.5f at t = %.3f; friction dissipated %.5f of %.5f input\n", report.contacts.at(0).min_gap,
                report.contacts.at(0).t_min_gap, report.link_energy(0), report.energy.input);
    // The paper's qualitative result, checked: the structures never pound.
    return report.contacts.at(0).contact ? 1 : 0;
  } catch (const adjoin::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return adjoin::kExitInputError;
  }
}
