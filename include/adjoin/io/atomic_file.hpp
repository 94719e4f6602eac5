#pragma once
// Writes a file so that nothing is lost or half-written: the content goes to a temporary file
// beside the target, which replaces the target (rename) only on commit(). If the writer is
// destroyed without commit() (an exception, a numerical failure), the temporary is removed and
// any previous file at the target is left untouched.
#include <filesystem>
#include <fstream>

namespace adjoin {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Flushes, checks for write errors (InputError naming the file) and renames into place.
  void commit();

 private:
  std::filesystem::path target_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace adjoin
