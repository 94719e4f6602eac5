#pragma once
// Writing an accelerogram as a text file (`adjoin synth`, `adjoin record process`): the
// ground layer makes records, io writes them.
#include <filesystem>
#include <string>
#include <vector>

#include "adjoin/ground/record.hpp"

namespace adjoin {

// Writes a record as text: the header lines (each prefixed with "# "), then "t a" per line,
// t = i dt and a in g, both in the shortest form that reads back to the same double
// (std::to_chars), so read_record(path, {two_column, g}) gives the same dt and accelerations
// equal to within one rounding of the unit conversion. Temporary file, then rename.
void write_record_g(const Record& record, const std::filesystem::path& path,
                    const std::vector<std::string>& header);

}  // namespace adjoin
