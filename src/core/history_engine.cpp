#include "adjoin/core/history_engine.hpp"

namespace adjoin {

std::string to_string(HistoryEngine engine) {
  return engine == HistoryEngine::direct ? "direct" : "fft";
}

bool parse_history_engine(const std::string& name, HistoryEngine* engine) {
  if (name == "direct") { *engine = HistoryEngine::direct; return true; }
  if (name == "fft") { *engine = HistoryEngine::fft; return true; }
  return false;
}

}  // namespace adjoin
