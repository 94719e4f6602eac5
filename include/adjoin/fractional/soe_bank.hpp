#pragma once
// Many soe histories of one order, stepped together (issue 24 Part 3: the state of all modes of
// all elements laid out for the vector units).
//
// A building with a Zener device in every storey carries one history per device, usually all of
// one order, so all of one compression (soe_history.hpp): the same decays and gains for every
// device, only the states differ. A SoeBank keeps the states of its members side by side, four
// members to a block (a block is one AVX2 register wide):
//
//     state of mode q of member e:   s[(e / 4) * Q + q][e % 4]
//
// so one step updates four members per vector operation, with the coefficients loaded once for
// the four. The modes are advanced a few steps at a time (soe_kernels.hpp), all blocks in one
// call. At Q = 56 (GL weights of order 0.53, 2^14 steps) a member's step is about 150
// instructions with the virtual push and lag_sum and the caller's loop (BM_soe_bank40's loop
// under callgrind), against 230 for a SoeHistory.
//
// Each member's arithmetic is the SoeHistory's, operation for operation (the same partial sums
// in the same order): a member's lag sums equal those of a SoeHistory pushed the same values,
// bit for bit (tests/test_soe_bank.cpp).
//
// Use: every member pushes one value per step (push, or all at once by push_all); the step is
// taken when the last member has pushed, and only then are the members' lag sums those of the
// next step. HistorySet (history_set.hpp) groups a structure's elements into banks by order and
// pushes each bank at once.
#include <cstddef>
#include <memory>
#include <vector>

#include "adjoin/fractional/soe_history.hpp"

namespace adjoin {

class SoeBank {
 public:
  static constexpr std::size_t kLanes = 4;  // members per block

  // `members` histories accepting `count` pushes each (y_0..y_{count-1}).
  SoeBank(std::shared_ptr<const SoeCompression> compression, std::size_t count, std::size_t members);

  std::size_t members() const { return members_; }
  // Steps pushed by every member so far.
  std::size_t size() const { return pushed_; }
  // sum_{j=1}^{m} w_j y_{m-j} of member e, m = size().
  double lag_sum(std::size_t e) const { return lag_[e]; }
  const double* lag_sums() const { return lag_.data(); }  // every member's, in member order
  // Member e's value y_m; once every member has given its own, the bank steps.
  void push(std::size_t e, double y) {
    if (staged(e) || pushed_ >= count_) refuse();
    recent_[(e / kLanes) * pitch_ + end_ * kLanes + e % kLanes] = y;  // the line's next row, the member's lane
    staged_at_[e] = pushed_ + 1;
    if (++staged_count_ == members_) step();
  }
  // Every member's value y_m at once (members() of them, in member order), then the step: the
  // same as push(e, y[e]) for each e, without the per-member bookkeeping.
  void push_all(const double* y) {
    if (staged_count_ != 0 || pushed_ >= count_) refuse();
    double* row = recent_.data() + end_ * kLanes;  // block 0's row; each next block's is pitch_ on
    std::size_t e = 0;
    for (; e + kLanes <= members_; e += kLanes, row += pitch_)
      for (std::size_t l = 0; l < kLanes; ++l) row[l] = y[e + l];
    for (std::size_t l = 0; e + l < members_; ++l) row[l] = y[e + l];
    step();
  }
  bool staged(std::size_t e) const { return staged_at_[e] > pushed_; }
  std::size_t bytes() const;
  const SoeCompression& compression() const { return *c_; }

 private:
  void step();
  [[noreturn]] void refuse() const;  // std::logic_error: a member pushed twice in a step, or past the weights

  std::shared_ptr<const SoeCompression> c_;
  // The compression's coefficients, each repeated over the four lanes (soe_bank.cpp's kernel
  // reads them as vectors).
  struct Wide {
    std::vector<double> decay, gain, a, b, p, r, window;  // window: SoeCompression::near_shifted
  };
  Wide wide_;
  std::size_t count_, members_, blocks_;
  std::size_t pushed_ = 0, staged_count_ = 0;
  std::vector<std::size_t> staged_at_;  // per member: the step its last value is for, plus one
  std::size_t line_;              // values kept per lane: n0 + 1 + the shift's slack
  std::size_t pitch_;             // doubles from one block's line to the next (with padding: soe_bank.cpp)
  std::size_t end_;               // the line's next free row (as SoeHistory's end_), where pushes go
  std::vector<double> recent_;    // per block, its line of values: [block][row][lane]
  std::vector<double> s_;         // one-term states: [block][mode][lane]
  std::vector<double> s1_, s2_;   // two-term states: the last and the one before, likewise
  std::vector<double> far_;       // the far sums of the steps made ahead: [block][step][lane]
  std::vector<double> lag_;       // per lane
};

}  // namespace adjoin
