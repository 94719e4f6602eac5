#include "adjoin/io/record_writer.hpp"

#include <charconv>
#include <ostream>

#include "adjoin/core/units.hpp"
#include "adjoin/io/atomic_file.hpp"

namespace adjoin {

void write_record_g(const Record& record, const std::filesystem::path& path, const std::vector<std::string>& header) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  for (const std::string& line : header) out << "# " << line << "\n";
  // What the readers take back without options (record_file.cpp: "# units:").
  out << "# units: g\n";
  std::string text;
  text.reserve(record.accel.size() * 36);
  char buffer[80];
  for (std::size_t i = 0; i < record.accel.size(); ++i) {
    auto r = std::to_chars(buffer, buffer + 32, static_cast<double>(i) * record.dt);
    *r.ptr++ = ' ';
    r = std::to_chars(r.ptr, buffer + sizeof buffer - 1, record.accel[i] / kStandardGravity);
    *r.ptr++ = '\n';
    text.append(buffer, r.ptr);
  }
  out << text;
  file.commit();
}

}  // namespace adjoin
