#include "adjoin/io/timeseries_csv.hpp"

#include <charconv>

#include "../detail/finite_output.hpp"

namespace adjoin {

TimeSeriesCsvWriter::TimeSeriesCsvWriter(std::ostream& out, const Scales& scales, std::size_t every,
                                         bool flag_outside_model)
    : out_(out), scales_(scales), every_(every == 0 ? 1 : every), flag_outside_model_(flag_outside_model) {}

void TimeSeriesCsvWriter::begin(const RunInfo& info) {
  steps_ = info.steps;
  count_ = 0;
  gap0_ = info.model.gap0;
  contact_law_ = info.model.contact.model != structure::ContactModel::none;
  outside_ = false;
  buffer_.clear();
  buffer_.reserve(1 << 16);
  if (contact_law_) out_ << "t,x1,x2,v1,v2,f1,f2,q,ag,gap,fc,phase\n";
  else if (flag_outside_model_) out_ << "t,x1,x2,v1,v2,f1,f2,q,ag,gap,outside_model,phase\n";
  else out_ << "t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase\n";
}

void TimeSeriesCsvWriter::observe(const State& s) {
  const std::size_t index = count_++;
  // The same test as the pounding margin's first contact (observe/pounding.cpp), at every
  // grid point, written or not.
  if (gap0_ + s.x2 - s.x1 <= 0.0) outside_ = true;
  if (index % every_ != 0 && index != steps_) return;
  const Scales& k = scales_;
  const double values[] = {s.t * k.time,     s.x1 * k.length,   s.x2 * k.length,
                           s.v1 * k.velocity, s.v2 * k.velocity, s.f1 * k.force,
                           s.f2 * k.force,   s.q * k.force,     s.ag * k.acceleration,
                           (gap0_ + s.x2 - s.x1) * k.length};
  static const char* const columns[] = {"t", "x1", "x2", "v1", "v2", "f1", "f2", "q", "ag", "gap"};
  char number[32];
  for (std::size_t i = 0; i < std::size(values); ++i) {
    const double v = values[i];
    detail::require_finite_output(v, "timeseries.csv", columns[i], s.t * k.time, s.t);
    auto [end, ec] = std::to_chars(number, number + sizeof number, v);
    buffer_.append(number, end);
    buffer_.push_back(',');
  }
  if (contact_law_) {
    const double fc = s.fc * k.force;
    detail::require_finite_output(fc, "timeseries.csv", "fc", s.t * k.time, s.t);
    auto [end, ec] = std::to_chars(number, number + sizeof number, fc);
    buffer_.append(number, end);
    buffer_.push_back(',');
  } else if (flag_outside_model_) {
    buffer_.append(outside_ ? "1," : "0,");
  }
  buffer_.append(to_string(s.phase));
  buffer_.push_back('\n');
  if (buffer_.size() > (1 << 16) - 512) { out_ << buffer_; buffer_.clear(); }
}

void TimeSeriesCsvWriter::end() {
  out_ << buffer_;
  buffer_.clear();
  out_.flush();
}

}  // namespace adjoin
