#include "adjoin/fractional/weights.hpp"

#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>

namespace adjoin {

std::vector<double> grunwald_letnikov_weights(double order, std::size_t count) {
  std::vector<double> w(count);
  if (count == 0) return w;
  w[0] = 1.0;
  for (std::size_t j = 1; j < count; ++j)
    w[j] = (1.0 - (order + 1.0) / static_cast<double>(j)) * w[j - 1];
  return w;
}

std::vector<double> bdf2_weights(double order, std::size_t count) {
  // P(zeta) = p0 + p1 zeta + p2 zeta^2; a_n = 1/(n p0) sum_{k=1}^{min(n,2)} ((order+1) k - n) p_k a_{n-k}.
  const double p[3] = {1.5, -2.0, 0.5};
  std::vector<double> w(count);
  if (count == 0) return w;
  w[0] = std::pow(p[0], order);
  for (std::size_t n = 1; n < count; ++n) {
    const double dn = static_cast<double>(n);
    double s = ((order + 1.0) - dn) * p[1] * w[n - 1];
    if (n >= 2) s += ((order + 1.0) * 2.0 - dn) * p[2] * w[n - 2];
    w[n] = s / (dn * p[0]);
  }
  return w;
}

namespace {

std::vector<double> computed(WeightRule rule, double order, std::size_t count) {
  return rule == WeightRule::bdf2 ? bdf2_weights(order, count) : grunwald_letnikov_weights(order, count);
}

// The process's weights: per (rule, order) the longest sequence asked for so far. Each weight
// depends on the earlier ones only (a recurrence), so a prefix of a longer sequence is the
// shorter one bit for bit. The recurrences' divisions are latency-bound (about 40
// instructions a weight: for a short run of the strong scene as much as a fifth of the step's
// cost, paid again by every run of a sweep or a ladder at the same h).
class WeightCache {
 public:
  static constexpr std::size_t kDirect = 256;            // shorter sequences are computed directly
  static constexpr std::size_t kMaxBytes = 64u << 20;  // the least recently used go beyond this

  std::shared_ptr<const std::vector<double>> find(WeightRule rule, double order, std::size_t count) {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (Entry& e : entries_)
      if (e.rule == rule && e.order == order && e.w->size() >= count) {
        e.used = ++clock_;
        return e.w;
      }
    return nullptr;
  }
  void keep(WeightRule rule, double order, std::shared_ptr<const std::vector<double>> w) {
    const std::size_t bytes = w->size() * sizeof(double);
    if (bytes > kMaxBytes) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    std::erase_if(entries_, [&](const Entry& e) { return e.rule == rule && e.order == order && e.w->size() <= w->size(); });
    entries_.push_back({rule, order, std::move(w), ++clock_});
    auto total = [&] {
      std::size_t b = 0;
      for (const Entry& e : entries_) b += e.w->size() * sizeof(double);
      return b;
    };
    while (total() > kMaxBytes) {
      auto oldest = entries_.begin();
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (it->used < oldest->used) oldest = it;
      entries_.erase(oldest);
    }
  }

 private:
  struct Entry {
    WeightRule rule;
    double order;
    std::shared_ptr<const std::vector<double>> w;
    std::uint64_t used;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
  std::uint64_t clock_ = 0;
};

WeightCache& weight_cache() {
  static WeightCache cache;
  return cache;
}

}  // namespace

std::vector<double> convolution_weights(WeightRule rule, double order, std::size_t count) {
  if (count <= WeightCache::kDirect) return computed(rule, order, count);
  WeightCache& cache = weight_cache();
  auto w = cache.find(rule, order, count);
  if (!w) {
    w = std::make_shared<const std::vector<double>>(computed(rule, order, count));
    cache.keep(rule, order, w);
  }
  return std::vector<double>(w->begin(), w->begin() + static_cast<std::ptrdiff_t>(count));
}

}  // namespace adjoin
