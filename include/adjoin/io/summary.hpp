#pragma once
// The run's report in the scene's units: summary.json (SPEC §3; keys may be added, never
// renamed) and a short human summary for the terminal.
#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {

// summary.json text (pretty-printed, ends with a newline).
std::string summary_json(const Scene& scene, const RunReport& report);
// A few lines: scene, solver, phases, peaks, pounding margin, energy.
std::string brief_report(const Scene& scene, const RunReport& report);
// spectra.csv: signal,period,damping,sd,sv,sa,psv,psa (the scene's units; sa and psa in g).
std::string spectra_csv(const RunReport& report);

}  // namespace adjoin
