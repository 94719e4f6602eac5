#include "adjoin/fractional/history.hpp"

#include "adjoin/fractional/direct_history.hpp"
#include "adjoin/fractional/fft_history.hpp"

namespace adjoin {

std::unique_ptr<ConvolutionHistory> make_history(HistoryEngine engine, std::vector<double> weights) {
  if (engine == HistoryEngine::fft) return std::make_unique<FftHistory>(std::move(weights));
  return std::make_unique<DirectHistory>(std::move(weights));
}

}  // namespace adjoin
