#pragma once
// The figure of `adjoin fragility` (io/plots.hpp lists the figures): probability of the event
// against IM, one colour per design: the fitted lognormal curve (solid), the IM-at-first-event
// curve of IDA traces (dashed), and the observed fraction at each level as a point whose area
// grows with the level's run count (one design: each point also labelled k/n). A chosen IM
// (--at) is a vertical line.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adjoin/io/plot_style.hpp"
#include "adjoin/post/fragility.hpp"

namespace adjoin {

struct FragilityCurve {
  std::string label;
  std::vector<FragilityLevel> levels;
  FragilityFit fit;                  // drawn when fitted
  std::optional<FirstEventFit> first_event;  // drawn when fitted
};

void plot_fragility(const std::vector<FragilityCurve>& curves, const std::string& title, std::optional<double> at,
                    const std::filesystem::path& image, const PlotStyle& style);

}  // namespace adjoin
