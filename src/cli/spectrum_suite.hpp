#pragma once
// `adjoin spectrum --suite RECORD|FOLDER... --out DIR`: the spectra of a suite of records and
// their statistics, optionally scaled to a target (spectrum_suite.cpp). spectrum.cpp parses
// the options the single spectrum shares and hands them over here.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "adjoin/ground/record_file.hpp"
#include "adjoin/post/spectrum_matching.hpp"
#include "adjoin/io/plots.hpp"
#include "adjoin/io/plot_style.hpp"
#include "adjoin/post/spectrum.hpp"
#include "adjoin/post/suite.hpp"

namespace adjoin::cli {

struct SuiteRequest {
  std::vector<std::string> inputs;  // record files and folders, as given
  RecordFormat format;              // kind automatic unless --format named one
  SpectrumOptions options;
  std::optional<TargetSpectrum> target;
  std::optional<SuiteScalingOptions> scaling;  // --t1 or --band given
  std::string out, plot;
  PlotStyle style;
};

int suite_command(const SuiteRequest& request);

// The single spectrum's CSV, `period,damping,sd,sv,sa,psv,psa` (spectrum.cpp).
void write_spectrum_csv(std::ostream& out, const ResponseSpectrum& spectrum);

}  // namespace adjoin::cli
