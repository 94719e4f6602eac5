#pragma once
// The two presentations of a run's report that io/summary.hpp's summary_json and brief_report
// choose between: a structure's (its channels, links and contact pairs by their own names;
// structure_summary.cpp) and, for a scene written with the two-block keys, SPEC §3's frozen
// names (summary.cpp).
#include <string>

#include "adjoin/study/error_estimate.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin::detail {

std::string structure_summary_json(const RunSpec& scene, const Report& report, const ErrorEstimate* estimate,
                                   const TolerantRun* tolerant);
std::string structure_brief_report(const RunSpec& scene, const Report& report, const ErrorEstimate* estimate,
                                   const TolerantRun* tolerant);

}  // namespace adjoin::detail
