#include "adjoin/io/timeseries_csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "../detail/finite_output.hpp"

namespace adjoin {

TimeSeriesCsvWriter::TimeSeriesCsvWriter(std::ostream& out, const Scales& scales, std::size_t every,
                                         bool flag_outside_model)
    : out_(out), scales_(scales), every_(every == 0 ? 1 : every), flag_outside_model_(flag_outside_model) {}

void TimeSeriesCsvWriter::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  phase_.begin(s, o);
  steps_ = o.steps();
  count_ = 0;
  gap0_ = s.contacts.at(0).gap;
  link_ = !s.links.empty();
  contact_law_ = s.contacts.at(0).law.model != structure::ContactModel::none;
  outside_ = false;
  buffer_.clear();
  buffer_.reserve(1 << 16);
  if (contact_law_) out_ << "t,x1,x2,v1,v2,f1,f2,q,ag,gap,fc,phase\n";
  else if (flag_outside_model_) out_ << "t,x1,x2,v1,v2,f1,f2,q,ag,gap,outside_model,phase\n";
  else out_ << "t,x1,x2,v1,v2,f1,f2,q,ag,gap,phase\n";
}

void TimeSeriesCsvWriter::observe(const StructureState& s) {
  const std::size_t index = count_++;
  // (At every grid point: a located switch needs the point before.)
  phase_.update(s);
  // The same test as the pounding margin's first contact (observe/pounding.cpp), at every
  // grid point, written or not.
  const double gap = gap0_ + s.x[1] - s.x[0];
  if (gap <= 0.0) outside_ = true;
  if (index % every_ != 0 && index != steps_) return;
  const Scales& k = scales_;
  const double q = link_ ? s.link_force[0] : 0.0;
  const double values[] = {s.t * k.time,           s.x[0] * k.length,       s.x[1] * k.length,
                           s.v[0] * k.velocity,    s.v[1] * k.velocity,     s.storey_force[0] * k.force,
                           s.storey_force[1] * k.force, q * k.force,        s.ag * k.acceleration,
                           gap * k.length};
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
    const double fc = s.contact_force[0] * k.force;
    detail::require_finite_output(fc, "timeseries.csv", "fc", s.t * k.time, s.t);
    auto [end, ec] = std::to_chars(number, number + sizeof number, fc);
    buffer_.append(number, end);
    buffer_.push_back(',');
  } else if (flag_outside_model_) {
    buffer_.append(outside_ ? "1," : "0,");
  }
  buffer_.append(to_string(phase_.phase));
  buffer_.push_back('\n');
  if (buffer_.size() > (1 << 16) - 512) { out_ << buffer_; buffer_.clear(); }
}

void TimeSeriesCsvWriter::end() {
  out_ << buffer_;
  buffer_.clear();
  out_.flush();
}

// ---- any structure: the channel table's time-series channels ----

namespace {

// A CSV value as to_chars writes it (about 17 digits, sign, exponent) and its comma: the
// size estimate of a time series before it is written.
constexpr double kBytesPerCsvValue = 20.0;
constexpr double kLargeCsvBytes = 50e6;  // warned before writing

}  // namespace

double output_interval(const RunSpec& scene) {
  if (scene.output.every > 0 || scene.accuracy.h_rule == "given") return 0.0;
  const auto& contacts = scene.structure.contacts;
  const bool impacts = std::any_of(contacts.begin(), contacts.end(),
                                   [](const structure::Contact& c) { return c.law.model != structure::ContactModel::none; });
  return impacts ? 1e-3 : 5e-3;
}

std::size_t output_every(const RunSpec& scene, double h) {
  if (scene.output.every > 0) return scene.output.every;
  const double interval = output_interval(scene);
  if (!(interval > 0.0 && h > 0.0)) return 1;
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(interval / h * (1.0 + 1e-9))));
}

void ChannelCsvWriter::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  s_ = &s;
  steps_ = o.steps();
  every_ = output_every(scene_, o.h);
  count_ = 0;
  pending_ = false;
  last_ = nullptr;
  std::vector<structure::Channel> columns;
  for (auto& c : structure::channels(s))
    if (structure::info(c.quantity).timeseries) columns.push_back(std::move(c));
  columns_ = ChannelValues(s, std::move(columns));
  unmodelled_ = false;
  flagged_ = std::any_of(s.contacts.begin(), s.contacts.end(),
                         [](const structure::Contact& c) { return c.law.model == structure::ContactModel::none; });
  warn_if_large(o.h);
  out_ << "t,ag";
  for (const auto& c : columns_.channels()) out_ << "," << c.name;
  if (flagged_) out_ << ",outside_model";
  out_ << "\n";
  // The gap of each pair without a law, read at every grid point (not only the written
  // ones): its first overlap puts every later row outside the model.
  gaps_.clear();
  for (std::size_t k = 0; k < s.contacts.size(); ++k)
    if (s.contacts[k].law.model == structure::ContactModel::none)
      gaps_.push_back({"", structure::Quantity::contact_gap, 'A', static_cast<int>(k + 1), -1});
}

void ChannelCsvWriter::observe(const StructureState& st) {
  const std::size_t index = count_++;
  for (const auto& gap : gaps_)
    if (channel_value(*s_, gap, st) <= 0.0) unmodelled_ = true;
  if (index % every_ != 0 && index != steps_) {
    last_ = &st;  // written at end() if the run ends here (a collapse stops it early)
    pending_ = true;
    return;
  }
  pending_ = false;
  write_row(st);
}

void ChannelCsvWriter::write_row(const StructureState& st) {
  values_.resize(2 + columns_.size());
  values_[0] = st.t;
  values_[1] = st.ag;
  columns_.read(st, values_.data() + 2);
  if (flagged_) values_.push_back(unmodelled_ ? 1.0 : 0.0);
  char number[32];
  for (std::size_t i = 0; i < values_.size(); ++i) {
    detail::require_finite_output(values_[i], "timeseries.csv", "a value", st.t, st.t);
    auto [end, ec] = std::to_chars(number, number + sizeof number, values_[i]);
    buffer_.append(number, end);
    buffer_.push_back(i + 1 < values_.size() ? ',' : '\n');
  }
  if (buffer_.size() > (1 << 16)) { out_ << buffer_; buffer_.clear(); }
}

void ChannelCsvWriter::end() {
  if (pending_ && last_) write_row(*last_);
  pending_ = false;
  out_ << buffer_;
  buffer_.clear();
}

// Once per size: a run to a tolerance begins again with each rung.
void ChannelCsvWriter::warn_if_large(double h) {
  const double rows = static_cast<double>(steps_ / every_ + 2);
  const double columns = static_cast<double>(2 + columns_.size() + (flagged_ ? 1 : 0));
  const double bytes = rows * columns * kBytesPerCsvValue;
  if (!warn_ || bytes <= kLargeCsvBytes || bytes <= 2.0 * warned_bytes_) return;
  warned_bytes_ = bytes;
  char text[400];
  std::snprintf(text, sizeof text,
                "timeseries.csv will be about %.0f MB (%.0f rows of %.0f columns: a row every %zu steps of h = %.4g s); "
                "set output.every (a row every output.every steps) to write fewer rows",
                bytes / 1e6, rows, columns, every_, h);
  warn_(text);
}

}  // namespace adjoin
