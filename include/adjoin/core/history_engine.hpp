#pragma once
// Which engine sums a fractional element's history (fractional/history.hpp). The choice is
// part of a run's description (solver options, an observer's RunInfo), which lower layers
// than fractional/ hold, so the name lives here.
#include <string>

namespace adjoin {

enum class HistoryEngine { direct, fft, soe };

// "direct" / "fft" / "soe"; parse returns false on an unknown name.
std::string to_string(HistoryEngine engine);
bool parse_history_engine(const std::string& name, HistoryEngine* engine);

}  // namespace adjoin
