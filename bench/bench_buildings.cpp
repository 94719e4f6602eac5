// The structure step on buildings (solver/structure_solver.hpp):
//
//     build/bench/bench_buildings
//
// targets/: two 20-storey buildings, modal 5 % damping, a fractional Zener device in every
// storey, three friction dampers, the 40 s Newhall record at h = 0.005 s (8,000 steps), with the
// fft, the direct and the soe history, and with springs only (no history). storeys/N: the same with N
// storeys each and the fft history, for the cost per step against the storey count;
// storeys_springs/N: the same without the Zener devices (the mechanics alone). viscous/: the
// springs-only pair with three alpha = 0.4 viscous dampers instead of the friction dampers, and
// beside them.
// targets/2x20/bilinear: the springs pair with bilinear storeys (yield drift 5 mm, 5 %
// hardening; SPEC §7): the target is at most 2x targets/2x20/springs. Its counter
// "yields" is the storeys' yield events in a run. targets/2x20/bouc-wen: the same with the
// Bouc-Wen law (n = 2, beta = gamma = 1/2; a yield: |z| reaching 0.9 u_y).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "adjoin/ground/record_file.hpp"
#include "adjoin/ground/record_motion.hpp"
#include "adjoin/core/units.hpp"
#include "adjoin/solver/structure_solver.hpp"

namespace {

using namespace adjoin;
using namespace adjoin::structure;

Structure pair_of(int storeys, bool zener, bool bilinear = false) {
  Structure s;
  auto building = [&](const char* name, double mass, double k) {
    Building b;
    b.name = name;
    b.masses = Eigen::VectorXd::Constant(storeys, mass);
    b.springs = Eigen::VectorXd::Constant(storeys, k);
    b.damping = {DampingModel::modal, 0.05, 1, 2};
    if (zener) {
      StoreyDevice d;
      d.type = DeviceType::zener;
      for (int i = 1; i <= storeys; ++i) d.storeys.push_back(i);
      d.zener = {0.2 * k, 0.5, 0.2, 0.01};
      b.devices.push_back(d);
    }
    if (bilinear) {
      b.hysteresis.model = HysteresisModel::bilinear;
      b.hysteresis.yield_forces = Eigen::VectorXd::Constant(storeys, 0.005 * k);
      b.hysteresis.hardening = 0.05;
    }
    return b;
  };
  s.a = building("A", 5e5, 8e8);
  s.b = building("B", 4e5, 6e8);
  for (int floor : {storeys / 3, 2 * storeys / 3, storeys}) {
    Link l;
    l.type = LinkType::friction;
    l.floor_a = l.floor_b = std::max(floor, 1);
    l.slip_force = 2e5;
    s.links.push_back(l);
  }
  return s;
}

const RecordMotion& newhall() {
  static const RecordMotion motion(read_record(std::string(ADJOIN_SOURCE_DIR) + "/records/real/peer/RSN1044_DirRot2.AT2"), 1.0,
                                   kStandardGravity);
  return motion;
}

class Nothing final : public StructureObserver {
 public:
  void observe(const StructureState& s) override { benchmark::DoNotOptimize(s.x[0]); }
};

void run(benchmark::State& state, const Structure& s, HistoryEngine history) {
  StructureSolverOptions o;
  o.h = 0.005;
  o.t_end = 40.0;
  o.history = history;
  Nothing sink;
  for (auto _ : state) simulate_structure(o, s, newhall(), sink);
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(o.steps()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_zener_fft(benchmark::State& st) { run(st, pair_of(20, true), HistoryEngine::fft); }
void BM_zener_direct(benchmark::State& st) { run(st, pair_of(20, true), HistoryEngine::direct); }
void BM_zener_soe(benchmark::State& st) { run(st, pair_of(20, true), HistoryEngine::soe); }
void BM_springs(benchmark::State& st) { run(st, pair_of(20, false), HistoryEngine::fft); }
class Yields final : public StructureObserver {
 public:
  void observe(const StructureState& s) override {
    for (double t : s.hyst_yield) count += std::isnan(t) ? 0 : 1;
  }
  int count = 0;
};
void BM_bilinear(benchmark::State& state) {
  const Structure s = pair_of(20, false, true);
  run(state, s, HistoryEngine::fft);
  StructureSolverOptions o;
  o.h = 0.005;
  o.t_end = 40.0;
  Yields yields;
  simulate_structure(o, s, newhall(), yields);
  state.counters["yields"] = yields.count;
}
void BM_bouc_wen(benchmark::State& state) {
  Structure s = pair_of(20, false, true);
  s.a.hysteresis.model = s.b->hysteresis.model = HysteresisModel::bouc_wen;
  run(state, s, HistoryEngine::fft);
  StructureSolverOptions o;
  o.h = 0.005;
  o.t_end = 40.0;
  Yields yields;
  simulate_structure(o, s, newhall(), yields);
  state.counters["yields"] = yields.count;
}
void BM_storeys(benchmark::State& st) { run(st, pair_of(static_cast<int>(st.range(0)), true), HistoryEngine::fft); }
// The mechanics alone (no Zener devices, no history): with modal damping C is dense, so its
// per-step cost grows as n^2 (one product with [A^-1; C A^-1] per building), the rest as n.
void BM_storeys_springs(benchmark::State& st) { run(st, pair_of(static_cast<int>(st.range(0)), false), HistoryEngine::fft); }

}  // namespace

// Nonlinear viscous dampers (alpha = 0.4) in place of the three friction dampers, and beside
// them (the two local solves in turn): against targets/2x20/springs.
Structure with_viscous(Structure s, bool keep_friction) {
  if (!keep_friction) s.links.clear();
  for (int floor : {7, 14, 20}) {
    Link l;
    l.type = LinkType::dashpot;
    l.floor_a = l.floor_b = floor;
    l.c = 1e6;
    l.alpha = 0.4;
    s.links.push_back(l);
  }
  return s;
}
void BM_viscous(benchmark::State& st) { run(st, with_viscous(pair_of(20, false), false), HistoryEngine::fft); }
void BM_viscous_friction(benchmark::State& st) { run(st, with_viscous(pair_of(20, false), true), HistoryEngine::fft); }

BENCHMARK(BM_zener_fft)->Name("targets/2x20/zener/fft")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_zener_direct)->Name("targets/2x20/zener/direct")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_zener_soe)->Name("targets/2x20/zener/soe")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_springs)->Name("targets/2x20/springs")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_viscous)->Name("viscous/2x20/alpha0.4")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_viscous_friction)->Name("viscous/2x20/alpha0.4+friction")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_bilinear)->Name("targets/2x20/bilinear")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_bouc_wen)->Name("targets/2x20/bouc-wen")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_storeys)->Name("storeys")->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_storeys_springs)->Name("storeys_springs")->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
