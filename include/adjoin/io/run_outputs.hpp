#pragma once
// Where a run's files go (io/run_files.hpp): a folder, committed as one set (io/atomic_file.hpp
// FileSet: all or none), or memory (the Python package's results: the same texts, no files).
#include <filesystem>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "adjoin/io/atomic_file.hpp"

namespace adjoin {

class RunOutputs {
 public:
  virtual ~RunOutputs() = default;
  // Starts writing the file `name`; the stream stays valid until commit().
  virtual std::ostream& open(const std::string& name) = 0;
  // Empties every opened file (a tolerance ladder's next rung streams afresh).
  virtual void restart() = 0;
  // Finishes the set; returns what was written (paths in a folder, names in memory), in the
  // order opened.
  virtual std::vector<std::filesystem::path> commit() = 0;
};

// A folder's files, committed as one set: `members` are every name the set may hold (those
// this run does not write are removed at commit).
class FolderOutputs final : public RunOutputs {
 public:
  FolderOutputs(std::filesystem::path dir, std::vector<std::string> members) : set_(std::move(dir), std::move(members)) {}
  std::ostream& open(const std::string& name) override { return set_.open(name); }
  void restart() override { set_.restart(); }
  std::vector<std::filesystem::path> commit() override { return set_.commit(); }

 private:
  FileSet set_;
};

// The files' texts in memory.
class MemoryOutputs final : public RunOutputs {
 public:
  std::ostream& open(const std::string& name) override;
  void restart() override;
  std::vector<std::filesystem::path> commit() override;
  // The text written to `name` ("" if it was not written).
  std::string text(const std::string& name) const;

 private:
  std::vector<std::pair<std::string, std::unique_ptr<std::ostringstream>>> files_;
};

}  // namespace adjoin
