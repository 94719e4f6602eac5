#pragma once
// Streams the time history to CSV as the solver runs (nothing is kept in memory), in the
// scene's units, with the header of SPEC §3:
//
//     t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase
//
// Numbers are written in the shortest form that reads back to the same double.
#include <ostream>

#include "adjoin/model/units.hpp"
#include "adjoin/observe/observer.hpp"

namespace adjoin {

class TimeSeriesCsvWriter final : public Observer {
 public:
  // Writes every `every`-th grid point and always the last one.
  TimeSeriesCsvWriter(std::ostream& out, const Scales& scales, std::size_t every = 1);
  void begin(const RunInfo& info) override;
  void observe(const State& s) override;
  void end() override;

 private:
  std::ostream& out_;
  Scales scales_;
  std::size_t every_, steps_ = 0, count_ = 0;
  double gap0_ = 0.0;
  std::string buffer_;
};

}  // namespace adjoin
