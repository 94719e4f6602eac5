#pragma once
// timeseries.csv, streamed as the solver runs (nothing is kept in memory). Two writers, one per
// presentation of a run's states:
//  - ChannelCsvWriter (any structure, SI): t, a_g, then every channel the channel table marks
//    for the time series (structure/channels.hpp), in its order;
//  - TimeSeriesCsvWriter: a scene written with the two-block keys, under the names of SPEC §3.
//
// The two-block writer: in the scene's units, with the header of SPEC §3:
//
//     t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase
//
// Pounding (SPEC §6) adds one column between gap and phase:
//  - fc, the contact force (compressive > 0), when the model has a contact law;
//  - outside_model, 0 up to the first grid point where the gap is <= 0 and 1 from there on,
//    when the writer is asked for it (flag_outside_model; io/run_files.cpp asks only for a run
//    without a contact law whose gap closed, so a run that never pounds keeps the SPEC header).
//
// Numbers are written in the shortest form that reads back to the same double.
#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "adjoin/core/units.hpp"
#include "adjoin/observe/channel_values.hpp"
#include "adjoin/observe/pair_phase.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/study/run_spec.hpp"

namespace adjoin {

// Of a two-block run's 1 + 1 structure (solver/simulate.hpp simulate_as_structure): x1, x2 =
// A.x1, B.x1; v1, v2 their velocities; f1, f2 = A.shear1, B.shear1; q = link1.force (0 without
// a link); gap = contact pair 1's; fc its force; phase link 1's (observe/pair_phase.hpp).
class TimeSeriesCsvWriter final : public StructureObserver {
 public:
  // Writes every `every`-th grid point and always the last one.
  TimeSeriesCsvWriter(std::ostream& out, const Scales& scales, std::size_t every = 1, bool flag_outside_model = false);
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& s) override;
  void end() override;
  // Takes effect at the next begin().
  void set_flag_outside_model(bool flag) { flag_outside_model_ = flag; }

 private:
  std::ostream& out_;
  Scales scales_;
  std::size_t every_, steps_ = 0, count_ = 0;
  PairPhase phase_;
  double gap0_ = 0.0;
  bool flag_outside_model_ = false;
  bool link_ = false, contact_law_ = false, outside_ = false;
  std::string buffer_;
};

// The rows of a structure's timeseries.csv: every output.every-th grid point when the scene
// gives it; else, with a step the scene gives (solver.h), every grid point; else (a step chosen
// for a tolerance) a row every output_interval: 1/200 s (200 Hz: 10 samples a cycle up to
// 20 Hz, above a building's modes of interest), 1/1000 s when a contact pair has a law (impacts
// last milliseconds), in whole steps of h (the row interval is at most that). The summary's
// peaks are taken at every step whatever the rows. 0 when the rule does not apply.
double output_interval(const RunSpec& scene);
std::size_t output_every(const RunSpec& scene, double h);

// Streams every `every`-th grid point of a structure run (output_every, from each run's own
// step): t, a_g and every floor's displacement and absolute acceleration, each link's force and
// stroke, each contact pair's gap and force (the channel table's time-series channels), and
// `outside_model` (0, then 1 from the first overlap of a pair without a contact law) when a pair
// has model none; SI units. No NaN or Inf is written (exit 3). Before a run whose file would
// exceed 50 MB it tells `warn` the size.
class ChannelCsvWriter final : public StructureObserver {
 public:
  using Warning = std::function<void(const std::string&)>;
  ChannelCsvWriter(std::ostream& out, const RunSpec& scene, Warning warn) : out_(out), scene_(scene), warn_(std::move(warn)) {}
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& st) override;
  void end() override;

 private:
  void write_row(const StructureState& st);
  void warn_if_large(double h);

  std::ostream& out_;
  const RunSpec& scene_;
  Warning warn_;
  double warned_bytes_ = 0.0;
  std::size_t every_ = 1, steps_ = 0, count_ = 0;
  const structure::Structure* s_ = nullptr;
  ChannelValues columns_;
  std::vector<structure::Channel> gaps_;
  std::vector<double> values_;
  std::string buffer_;
  // The last grid point observed and not written (the run's last, if it stops early): the
  // stepper's own state, still valid at end(), which the time loop calls right after the
  // last observe (solver/time_loop.hpp); not a copy, which would cost more than the step.
  const StructureState* last_ = nullptr;
  bool pending_ = false;
  bool flagged_ = false, unmodelled_ = false;
};

}  // namespace adjoin
