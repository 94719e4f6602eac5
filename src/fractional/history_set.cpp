#include "adjoin/fractional/history_set.hpp"

#include <algorithm>
#include <map>

#include "adjoin/fractional/soe_bank.hpp"

namespace adjoin {

HistorySet::HistorySet() = default;
HistorySet::~HistorySet() = default;
HistorySet::HistorySet(HistorySet&&) noexcept = default;
HistorySet& HistorySet::operator=(HistorySet&&) noexcept = default;

HistorySet::HistorySet(HistoryEngine engine, WeightRule rule, const std::vector<double>& orders, std::size_t count,
                       double tolerance)
    : lag_(orders.size(), 0.0) {
  // soe: the elements of one compression (one order) share a bank; an order met once gets its
  // own SoeHistory (a bank of one would step three empty lanes).
  std::map<const SoeCompression*, std::vector<std::size_t>> groups;
  std::map<const SoeCompression*, std::shared_ptr<const SoeCompression>> compressions;
  for (std::size_t e = 0; e < orders.size(); ++e) {
    if (std::isnan(orders[e])) continue;
    if (engine != HistoryEngine::soe) {
      singles_.push_back({e, make_history(engine, rule, orders[e], count, tolerance)});
      continue;
    }
    auto c = soe_compression(rule, orders[e], tolerance, count);
    groups[c.get()].push_back(e);
    compressions[c.get()] = std::move(c);
  }
  for (auto& [key, elements] : groups) {
    if (elements.size() == 1) {
      singles_.push_back({elements.front(), std::make_unique<SoeHistory>(compressions[key], count)});
      continue;
    }
    Bank b;
    b.bank = std::make_unique<SoeBank>(compressions[key], count, elements.size());
    b.elements = elements;
    b.contiguous = elements.back() - elements.front() + 1 == elements.size();  // (ascending, distinct)
    b.y.assign(elements.size(), 0.0);
    banks_.push_back(std::move(b));
  }
  std::sort(singles_.begin(), singles_.end(), [](const Single& a, const Single& b) { return a.element < b.element; });
}

void HistorySet::push(const double* y) {
  for (const Single& s : singles_) lag_[s.element] = s.history->push(y[s.element]);
  if (!banks_.empty()) push_banks(y);
}

void HistorySet::push_banks(const double* y) {
  for (Bank& b : banks_) {
    const std::size_t n = b.elements.size(), first = b.elements.front();
    if (b.contiguous) {  // (every Zener storey of one order: the usual case)
      b.bank->push_all(y + first);
      std::copy_n(b.bank->lag_sums(), n, lag_.data() + first);
      continue;
    }
    for (std::size_t k = 0; k < n; ++k) b.y[k] = y[b.elements[k]];
    b.bank->push_all(b.y.data());
    for (std::size_t k = 0; k < n; ++k) lag_[b.elements[k]] = b.bank->lag_sum(k);
  }
}

std::size_t HistorySet::bytes() const {
  std::size_t total = 0;
  for (const Single& s : singles_) total += s.history->bytes();
  for (const Bank& b : banks_) total += b.bank->bytes();
  return total;
}

double HistorySet::weight_error() const {
  double error = 0.0;
  for (const Single& s : singles_) error = std::max(error, s.history->weight_error());
  for (const Bank& b : banks_) error = std::max(error, b.bank->compression().error);
  return error;
}

std::size_t HistorySet::modes() const {
  std::size_t modes = 0;
  for (const Single& s : singles_) modes = std::max(modes, s.history->modes());
  for (const Bank& b : banks_) modes = std::max(modes, b.bank->compression().modes());
  return modes;
}

}  // namespace adjoin
