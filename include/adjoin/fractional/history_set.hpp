#pragma once
// The histories of many elements pushed together once per step (a structure's Zener elements):
// every lag sum read from one array at a step's start, every value given in one call at its
// end. With the soe engine the elements of one order share a SoeBank (soe_bank.hpp) and are
// pushed to it at once; the other engines keep one history per element. Against one
// ConvolutionHistory per element this saves two virtual calls and the bank's per-member
// bookkeeping per element and step (about a tenth of a 2 x 20 Zener-storey pair's run), with
// the same sums bit for bit.
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "adjoin/fractional/history.hpp"

namespace adjoin {

class SoeBank;

class HistorySet {
 public:
  HistorySet();
  // One element per entry of `orders`, with the weights of `rule` at that order and `count`
  // pushes (y_0..y_{count-1}); a NaN order is an element without a history (an elastic rod:
  // its lag sum stays 0, its values are not kept). `tolerance`: soe's (history.hpp).
  HistorySet(HistoryEngine engine, WeightRule rule, const std::vector<double>& orders, std::size_t count, double tolerance);
  ~HistorySet();
  HistorySet(HistorySet&&) noexcept;
  HistorySet& operator=(HistorySet&&) noexcept;

  std::size_t size() const { return lag_.size(); }
  // sum_{j=1}^{m} w_j y_{m-j} of each element after m steps' pushes.
  const double* lag_sums() const { return lag_.data(); }
  // Every element's value y_m (size() of them; an element without a history ignores its own).
  void push(const double* y);

  std::size_t bytes() const;
  double weight_error() const;   // the largest of the elements'
  std::size_t modes() const;     // the largest of the elements'

 private:
  // The elements outside a bank, each with its own history, in element order (pushed by one
  // virtual call each, which returns the lag sum).
  struct Single {
    std::size_t element;
    std::unique_ptr<ConvolutionHistory> history;
  };
  std::vector<Single> singles_;
  struct Bank {
    std::unique_ptr<SoeBank> bank;
    std::vector<std::size_t> elements;  // the bank's members' elements, in member order
    bool contiguous = false;            // ... elements[0], elements[0] + 1, ...: pushed and read in place
    std::vector<double> y;              // the step's values in member order (when not contiguous)
  };
  std::vector<Bank> banks_;
  std::vector<double> lag_;

  // push()'s part for the banks (a function of its own: its copies need registers that push
  // would otherwise save and restore at every step of a run without a bank).
  void push_banks(const double* y);
};

}  // namespace adjoin
