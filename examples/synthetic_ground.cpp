// Two adjacent frames in SI units shaken by synthetic ground motion, through the library API
// alone (no scene file): synthesize a Clough-Penzien motion, scale the structure to the
// solver's dimensionless form, simulate with streaming observers, report in SI.
//
//     synthetic_ground [SEED]
#include <adjoin/ground/record_motion.hpp>
#include <adjoin/ground/synthesis.hpp>
#include <adjoin/core/units.hpp>
#include <adjoin/observe/peaks.hpp>
#include <adjoin/observe/pounding.hpp>
#include <adjoin/solver/simulate.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  // The structures [kg, N/m, N, m] and their fractional Zener rods [s^order].
  const double m1 = 2.0e5, m2 = 4.0e5, k1 = 8.0e6, k2 = 1.6e7, slip_force = 2.0e5, gap = 0.10;
  const adjoin::Scales si = adjoin::Scales::SI(m1, k1);  // T0 = sqrt(m1/k1), X0 = m1 g / k1

  adjoin::Model model;
  model.rho = m1 / m2;
  model.eps = k2 / k1;
  model.mu = slip_force / (m1 * adjoin::kStandardGravity);
  model.gap0 = gap / si.length;
  auto rod = [&](double order, double tau_x, double tau_f) {  // one time scale for both rods
    const double to_dimensionless = std::pow(si.time, -order);
    return adjoin::Rod{order, tau_x * to_dimensionless, tau_f * to_dimensionless, false};
  };
  model.rod1 = rod(0.23, 0.77, 0.0026);
  model.rod2 = rod(0.53, 1.51, 0.075);

  // 20 s of Clough-Penzien noise under a Jennings-Housner-Tsai envelope, PGA 0.3 g.
  adjoin::SynthesisOptions noise;
  noise.target_pga = 0.3;
  noise.duration = 20.0;
  noise.seed = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1;
  const adjoin::RecordMotion ground(adjoin::synthesize(noise), si.time, adjoin::kStandardGravity);

  adjoin::SolverOptions options;  // the default implicit scheme
  options.h = 0.002 / si.time;
  options.t_end = 25.0 / si.time;

  // The two blocks as their 1 + 1 structure (frames A and B, damper link 1, contact pair 1),
  // watched by its peaks and its pounding margin.
  adjoin::PeakObserver peaks;
  adjoin::PoundingObserver pounding;
  struct Both final : adjoin::StructureObserver {
    adjoin::StructureObserver *a, *b;
    Both(adjoin::StructureObserver* x, adjoin::StructureObserver* y) : a(x), b(y) {}
    void begin(const adjoin::structure::Structure& s, const adjoin::StructureSolverOptions& o) override { a->begin(s, o); b->begin(s, o); }
    void observe(const adjoin::StructureState& st) override { a->observe(st); b->observe(st); }
    void impact(const adjoin::Impact& i) override { a->impact(i); b->impact(i); }
    void end() override { a->end(); b->end(); }
  } observers(&peaks, &pounding);
  const adjoin::SolverSummary summary = adjoin::simulate_as_structure(options, model, ground, observers);

  std::printf("%s\n%zu steps in %.3f s\n", ground.describe().c_str(), summary.steps, summary.wall_seconds);
  // The peaks by the 1 + 1 structure's channels: the frames' floors and the damper's stroke.
  const std::vector<adjoin::ChannelPeak> p = peaks.peaks();
  std::printf("max |x1| = %.4f m, max |x2| = %.4f m, max damper stroke = %.4f m\n",
              adjoin::find_peak(p, "A.x1").max_abs * si.length, adjoin::find_peak(p, "B.x1").max_abs * si.length,
              adjoin::find_peak(p, "link1.stroke").max_abs * si.length);
  std::printf("min gap = %.4f m at t = %.2f s: %s\n", pounding.margin().min_gap * si.length,
              pounding.margin().t_min_gap * si.time, pounding.margin().contact ? "the frames pound" : "no pounding");
  return pounding.margin().contact ? 1 : 0;
}
