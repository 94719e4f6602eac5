#pragma once
// impacts.csv. A structure run's (any scene not written with the two-block keys) is made from
// its report once the run is done (impacts_csv below): one row per impact in the order they
// started, with its pair first (contact, 1-based), SI. A two-block run's is streamed: its
// impacts (SPEC §6) to CSV as the solver reports them (one row per
// StructureObserver::impact, in order), in the scene's units like timeseries.csv (dimensionless, or s,
// N, m, m/s and N s for SI scenes):
//
//     t_start,duration,force_max,t_force_max,penetration_max,approach_speed,rebound_speed,impulse,complete
//
// complete is true or false (false: still in contact at the end of the run). Written only
// for a model with a contact law (io/run_files.cpp); numbers in the shortest form that reads
// back to the same double.
#include <ostream>
#include <string>

#include "adjoin/core/units.hpp"
#include "adjoin/structure/observer.hpp"
#include "adjoin/study/report.hpp"

namespace adjoin {

inline constexpr const char* kImpactsCsvHeader =
    "t_start,duration,force_max,t_force_max,penetration_max,approach_speed,rebound_speed,impulse,complete";

// One row (no newline) of impacts.csv for an impact in the solver's dimensionless units.
std::string impact_csv_row(const Impact& impact, const Scales& scales);

// A structure run's impacts.csv: contact,t_start,duration,force_max,t_force_max,penetration_max,
// approach_speed,rebound_speed,impulse,complete (SI; contact 1-based).
std::string impacts_csv(const Report& report);

class ImpactsCsvWriter final : public StructureObserver {
 public:
  ImpactsCsvWriter(std::ostream& out, const Scales& scales) : out_(out), scales_(scales) {}
  void begin(const structure::Structure& s, const StructureSolverOptions& o) override;
  void observe(const StructureState& /*state*/) override {}
  void impact(const Impact& impact) override;
  void end() override { out_.flush(); }

 private:
  std::ostream& out_;
  Scales scales_;
};

}  // namespace adjoin
