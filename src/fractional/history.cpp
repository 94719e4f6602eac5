#include "adjoin/fractional/history.hpp"

#include <stdexcept>

#include "adjoin/fractional/direct_history.hpp"
#include "adjoin/fractional/fft_history.hpp"
#include "adjoin/fractional/soe_history.hpp"

namespace adjoin {

std::unique_ptr<ConvolutionHistory> make_history(HistoryEngine engine, std::vector<double> weights) {
  if (engine == HistoryEngine::fft) return std::make_unique<FftHistory>(std::move(weights));
  if (engine == HistoryEngine::soe)
    throw std::logic_error("make_history: the soe engine is made from its rule and order, not from weights");
  return std::make_unique<DirectHistory>(std::move(weights));
}

std::unique_ptr<ConvolutionHistory> make_history(HistoryEngine engine, WeightRule rule, double order, std::size_t count,
                                                 double tolerance) {
  if (engine == HistoryEngine::soe)
    return std::make_unique<SoeHistory>(soe_compression(rule, order, tolerance, count), count);
  return make_history(engine, convolution_weights(rule, order, count));
}

}  // namespace adjoin
