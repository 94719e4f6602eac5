#pragma once
// Streams the time history to CSV as the solver runs (nothing is kept in memory), in the
// scene's units, with the header of SPEC §3:
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
#include <ostream>

#include "adjoin/core/units.hpp"
#include "adjoin/structure/observer.hpp"

namespace adjoin {

class TimeSeriesCsvWriter final : public Observer {
 public:
  // Writes every `every`-th grid point and always the last one.
  TimeSeriesCsvWriter(std::ostream& out, const Scales& scales, std::size_t every = 1, bool flag_outside_model = false);
  void begin(const RunInfo& info) override;
  void observe(const State& s) override;
  void end() override;
  // Takes effect at the next begin().
  void set_flag_outside_model(bool flag) { flag_outside_model_ = flag; }

 private:
  std::ostream& out_;
  Scales scales_;
  std::size_t every_, steps_ = 0, count_ = 0;
  double gap0_ = 0.0;
  bool flag_outside_model_ = false;
  bool contact_law_ = false, outside_ = false;
  std::string buffer_;
};

}  // namespace adjoin
