#include "adjoin/fractional/soe_bank.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "../detail/simd_clones.hpp"

namespace adjoin {
namespace {

constexpr std::size_t L = SoeBank::kLanes;
constexpr std::size_t kShift = 223;  // rows kept past the window before the line is shifted back (as SoeHistory)

// One step of one block of four members: SoeHistory::push's arithmetic (soe_history.cpp), lane
// by lane, with the same partial sums in the same order, so each lane's lag sum equals the
// SoeHistory's bit for bit. `rows` are the block's values y_{m-n0-1}..y_{m-1}, one row of four
// lanes each; the inner loops over the lanes are one vector operation each. (Plain restrict
// parameters: GCC honours those, not restrict members of a struct.)
ADJOIN_SIMD_CLONES
void step_block_kernel(const double* __restrict decay, const double* __restrict gain, std::size_t single,
                       const double* __restrict pa, const double* __restrict pb, const double* __restrict pp,
                       const double* __restrict pr, std::size_t paired, const double* __restrict w, std::size_t n0,
                       double* __restrict s, double* __restrict s1, double* __restrict s2, const double* __restrict rows,
                       double* __restrict lag) {
  double y[L], y_before[L];
  for (std::size_t l = 0; l < L; ++l) {
    y_before[l] = rows[l];  // y_{m-n0-1}
    y[l] = rows[L + l];     // y_{m-n0}
  }
  double sum[4][L] = {};
  for (std::size_t q = 0; q < single; q += 4)
#pragma GCC unroll 4
    for (std::size_t k = 0; k < 4; ++k) {
      const double* d = decay + (q + k) * L;  // (the coefficients spread over the lanes)
      const double* g = gain + (q + k) * L;
      double* sq = s + (q + k) * L;
      for (std::size_t l = 0; l < L; ++l) {
        const double v = sq[l] + (g[l] * y[l] - d[l] * sq[l]);
        sq[l] = v;
        sum[k][l] += v;
      }
    }
  double far[L];
  for (std::size_t l = 0; l < L; ++l) far[l] = (sum[0][l] + sum[1][l]) + (sum[2][l] + sum[3][l]);
  if (paired > 0) {
    double two[4][L] = {};
    for (std::size_t q = 0; q < paired; q += 4)
#pragma GCC unroll 4
      for (std::size_t k = 0; k < 4; ++k) {
        const double* a = pa + (q + k) * L;
        const double* b = pb + (q + k) * L;
        const double* p = pp + (q + k) * L;
        const double* r = pr + (q + k) * L;
        double* last = s1 + (q + k) * L;
        double* before = s2 + (q + k) * L;
        for (std::size_t l = 0; l < L; ++l) {
          const double v = (a[l] * last[l] + b[l] * before[l]) + (p[l] * y[l] + r[l] * y_before[l]);
          before[l] = last[l];
          last[l] = v;
          two[k][l] += v;
        }
      }
    for (std::size_t l = 0; l < L; ++l) far[l] += (two[0][l] + two[1][l]) + (two[2][l] + two[3][l]);
  }
  // The window: detail::dot's eight partial sums over y_{m-n0}..y_{m-1} and 0, w_{n0-1}..w_1.
  const double* window = rows + L;
  double dot[8][L] = {};
  std::size_t i = 0;
  for (; i + 8 <= n0; i += 8)
#pragma GCC unroll 8
    for (std::size_t k = 0; k < 8; ++k)
      for (std::size_t l = 0; l < L; ++l) dot[k][l] += window[(i + k) * L + l] * w[(i + k) * L + l];
  for (; i < n0; ++i)
    for (std::size_t l = 0; l < L; ++l) dot[0][l] += window[i * L + l] * w[i * L + l];
  for (std::size_t l = 0; l < L; ++l)
    lag[l] = far[l] + (((dot[0][l] + dot[1][l]) + (dot[2][l] + dot[3][l])) + ((dot[4][l] + dot[5][l]) + (dot[6][l] + dot[7][l])));
}

// One member of a bank, seen as a ConvolutionHistory.
class BankMember final : public ConvolutionHistory {
 public:
  BankMember(std::shared_ptr<SoeBank> bank, std::size_t e) : bank_(std::move(bank)), e_(e) {}
  double lag_sum() const override { return bank_->lag_sum(e_); }
  void push(double y) override { bank_->push(e_, y); }
  std::size_t size() const override { return bank_->size() + (bank_->staged(e_) ? 1 : 0); }
  // The bank's bytes shared among its members (the first takes the remainder).
  std::size_t bytes() const override {
    const std::size_t all = bank_->bytes(), n = bank_->members();
    return all / n + (e_ == 0 ? all % n : 0);
  }
  double weight_error() const override { return bank_->compression().error; }
  std::size_t modes() const override { return bank_->compression().modes(); }

 private:
  std::shared_ptr<SoeBank> bank_;
  std::size_t e_;
};

}  // namespace

SoeBank::SoeBank(std::shared_ptr<const SoeCompression> compression, std::size_t count, std::size_t members)
    : c_(std::move(compression)),
      count_(count),
      members_(members),
      blocks_((members + L - 1) / L),
      staged_(members, 0),
      incoming_(blocks_ * L, 0.0),
      line_(c_->window + 1 + kShift),
      end_(c_->window + 1),  // y_{-n0-1}..y_{-1} = 0: the modes read y_{m-n0-1} from the start
      recent_(blocks_ * line_ * L, 0.0),
      s_(blocks_ * c_->decay.size() * L, 0.0),
      s1_(blocks_ * c_->a.size() * L, 0.0),
      s2_(blocks_ * c_->a.size() * L, 0.0),
      lag_(blocks_ * L, 0.0) {
  if (members == 0) throw std::invalid_argument("SoeBank: no members");
  auto spread = [](const std::vector<double>& v) {
    std::vector<double> out(v.size() * L);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = v[i / L];
    return out;
  };
  wide_ = Wide{spread(c_->decay), spread(c_->gain), spread(c_->a), spread(c_->b), spread(c_->p), spread(c_->r),
               spread(c_->near_reversed)};
}

void SoeBank::push(std::size_t e, double y) {
  if (staged_[e]) throw std::logic_error("SoeBank: a member pushed twice before the others pushed once");
  if (pushed_ >= count_) throw std::logic_error("SoeBank: more values pushed than weights were given");
  incoming_[e] = y;
  staged_[e] = 1;
  if (++staged_count_ == members_) step();
}

void SoeBank::step() {
  const std::size_t keep = c_->window + 1;
  if (end_ == line_) {  // keep the last n0 + 1 rows of each block, at the front
    for (std::size_t blk = 0; blk < blocks_; ++blk) {
      double* line = recent_.data() + blk * line_ * L;
      std::copy(line + (line_ - keep) * L, line + line_ * L, line);
    }
    end_ = keep;
  }
  for (std::size_t blk = 0; blk < blocks_; ++blk)
    std::copy_n(incoming_.data() + blk * L, L, recent_.data() + (blk * line_ + end_) * L);
  ++end_;
  std::fill(staged_.begin(), staged_.end(), 0);
  staged_count_ = 0;
  if (++pushed_ >= count_) {
    std::fill(lag_.begin(), lag_.end(), 0.0);
    return;
  }
  for (std::size_t blk = 0; blk < blocks_; ++blk) step_block(blk);
}

void SoeBank::step_block(std::size_t blk) {
  const std::size_t n0 = c_->window;
  const std::size_t single = c_->decay.size(), paired = c_->a.size();  // (padded, as SoeHistory steps them)
  const Wide& w = wide_;
  step_block_kernel(w.decay.data(), w.gain.data(), single, w.a.data(), w.b.data(), w.p.data(), w.r.data(), paired,
                    w.near_reversed.data(), n0, s_.data() + blk * single * L, s1_.data() + blk * paired * L,
                    s2_.data() + blk * paired * L, recent_.data() + (blk * line_ + end_ - n0 - 1) * L, lag_.data() + blk * L);
}

std::size_t SoeBank::bytes() const {
  return sizeof(*this) + c_->bytes() +
         (incoming_.capacity() + recent_.capacity() + s_.capacity() + s1_.capacity() + s2_.capacity() + lag_.capacity() +
          wide_.decay.capacity() + wide_.gain.capacity() + wide_.a.capacity() + wide_.b.capacity() + wide_.p.capacity() +
          wide_.r.capacity() + wide_.near_reversed.capacity()) *
             sizeof(double) +
         staged_.capacity();
}

std::vector<std::unique_ptr<ConvolutionHistory>> make_soe_histories(WeightRule rule, const std::vector<double>& orders,
                                                                    std::size_t count, double tolerance) {
  // Members by compression (equal orders share one: soe_compression caches it).
  std::vector<std::shared_ptr<const SoeCompression>> compressions;
  std::map<const SoeCompression*, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < orders.size(); ++i) {
    compressions.push_back(soe_compression(rule, orders[i], tolerance, count));
    groups[compressions.back().get()].push_back(i);
  }
  std::vector<std::unique_ptr<ConvolutionHistory>> histories(orders.size());
  for (const auto& [key, members] : groups) {
    const auto& c = compressions[members.front()];
    if (members.size() == 1) {
      histories[members.front()] = std::make_unique<SoeHistory>(c, count);
      continue;
    }
    auto bank = std::make_shared<SoeBank>(c, count, members.size());
    for (std::size_t e = 0; e < members.size(); ++e) histories[members[e]] = std::make_unique<BankMember>(bank, e);
  }
  return histories;
}

}  // namespace adjoin
