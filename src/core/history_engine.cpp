#include "adjoin/core/history_engine.hpp"

namespace adjoin {

std::string to_string(HistoryEngine engine) {
  switch (engine) {
    case HistoryEngine::direct: return "direct";
    case HistoryEngine::fft: return "fft";
    case HistoryEngine::soe: return "soe";
  }
  return "fft";
}

bool parse_history_engine(const std::string& name, HistoryEngine* engine) {
  if (name == "direct") { *engine = HistoryEngine::direct; return true; }
  if (name == "fft") { *engine = HistoryEngine::fft; return true; }
  if (name == "soe") { *engine = HistoryEngine::soe; return true; }
  return false;
}

}  // namespace adjoin
