#include "adjoin/io/energy_csv.hpp"

#include <charconv>
#include <iterator>

#include "../detail/finite_output.hpp"
#include "adjoin/io/two_block_names.hpp"

namespace adjoin {

EnergyCsvWriter::EnergyCsvWriter(std::ostream& out, const Scales& scales, std::size_t every)
    : out_(out), scales_(scales), every_(every == 0 ? 1 : every) {}

void EnergyCsvWriter::begin(const structure::Structure& s, const StructureSolverOptions& o) {
  energy_.begin(s, o);
  steps_ = o.steps();
  count_ = 0;
  buffer_.clear();
  contact_law_ = s.contacts.at(0).law.model != structure::ContactModel::none;
  out_ << (contact_law_ ? "t,input,kinetic,rod1,rod2,friction,contact,contact_dissipated,residual\n"
                        : "t,input,kinetic,rod1,rod2,friction,residual\n");
}

void EnergyCsvWriter::observe(const StructureState& s) {
  energy_.observe(s);
  const std::size_t index = count_++;
  if (index % every_ != 0 && index != steps_) return;
  const TwoBlockEnergy e = two_block_energy(energy_.terms());
  const double t = energy_.terms().t;
  const double k = scales_.energy;
  const double values[] = {t * scales_.time, e.input * k,   e.kinetic * k, e.rod1 * k,
                           e.rod2 * k,         e.friction * k, e.contact * k, e.contact_dissipated * k,
                           e.residual * k};
  static const char* const columns[] = {"t",    "input",    "kinetic", "rod1",    "rod2",
                                        "friction", "contact", "contact_dissipated", "residual"};
  char number[32];
  for (std::size_t i = 0; i < std::size(values); ++i) {
    if (!contact_law_ && (i == 6 || i == 7)) continue;
    detail::require_finite_output(values[i], "energy.csv", columns[i], t * scales_.time, t);
    auto [end, ec] = std::to_chars(number, number + sizeof number, values[i]);
    buffer_.append(number, end);
    buffer_.push_back(i + 1 < std::size(values) ? ',' : '\n');
  }
  if (buffer_.size() > (1 << 16)) { out_ << buffer_; buffer_.clear(); }
}

void EnergyCsvWriter::end() {
  out_ << buffer_;
  buffer_.clear();
  out_.flush();
}

}  // namespace adjoin
