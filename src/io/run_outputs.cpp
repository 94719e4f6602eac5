#include "adjoin/io/run_outputs.hpp"

namespace adjoin {

std::ostream& MemoryOutputs::open(const std::string& name) {
  for (auto& [file, stream] : files_)
    if (file == name) return *stream;
  files_.emplace_back(name, std::make_unique<std::ostringstream>());
  return *files_.back().second;
}

void MemoryOutputs::restart() {
  for (auto& file : files_) {
    file.second->str("");
    file.second->clear();
  }
}

std::vector<std::filesystem::path> MemoryOutputs::commit() {
  std::vector<std::filesystem::path> names;
  for (const auto& file : files_) names.emplace_back(file.first);
  return names;
}

std::string MemoryOutputs::text(const std::string& name) const {
  for (const auto& [file, stream] : files_)
    if (file == name) return stream->str();
  return "";
}

}  // namespace adjoin
