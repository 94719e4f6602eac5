#pragma once
// Which engine sums a fractional element's history (fractional/history.hpp). The choice is
// part of a run's description (solver options, what an observer's begin() is told), which lower layers
// than fractional/ hold, so the name lives here.
// The enum and its names ("direct", "fft") are in the one table of enum names.
#include "adjoin/core/enum_names.hpp"
