#pragma once
// The run's report in the scene's units: summary.json (SPEC §3; keys may be added, never
// renamed) and a short human summary for the terminal. A scene written with the two-block keys
// is presented under SPEC §3's names; any other structure by its channels, links and contact
// pairs (src/io/structure_summary.cpp: modes, peaks by channel, links, contacts, energy).
#include <string>

#include "adjoin/io/scene.hpp"
#include "adjoin/study/error_estimate.hpp"
#include "adjoin/study/run.hpp"

namespace adjoin {

// summary.json text (pretty-printed, ends with a newline). With an estimate, the section
// "error_estimate"; with a tolerant run, "solver" says the tolerance, the steps tried and
// whether it was met.
std::string summary_json(const Scene& scene, const Report& report, const ErrorEstimate* estimate = nullptr,
                         const TolerantRun* tolerant = nullptr);
// A few lines: scene, solver, phases, peaks, pounding margin, energy, error estimate.
std::string brief_report(const Scene& scene, const Report& report, const ErrorEstimate* estimate = nullptr,
                         const TolerantRun* tolerant = nullptr);
// spectra.csv: signal,period,damping,sd,sv,sa,psv,psa (the scene's units; sa and psa in g).
std::string spectra_csv(const Report& report);
std::string spectra_csv(const std::vector<SignalSpectrum>& spectra);

}  // namespace adjoin
