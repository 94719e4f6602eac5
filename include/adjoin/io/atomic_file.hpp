#pragma once
// Writing files so that nothing is lost, half-written or mixed.
//
// AtomicFile: the content goes to a temporary file beside the target ("<target>.tmp.<pid>"),
// which replaces the target (rename) only on commit(). If the writer is destroyed without
// commit() (an exception, a numerical failure), the temporary is removed and any previous file
// at the target is left untouched. Temporaries left by processes that died (killed, power
// cut) are removed when a new writer opens the same target.
//
// FileSet: the files of one run (or one command) that belong together. Each member is written
// in full to its temporary first; only when every one of them has been written without error
// are they renamed into place, and members of the set that this run did not write (left by an
// earlier run with other outputs) are removed, so a folder never holds a new summary beside an
// old time series. A failure while writing (disk full) leaves the previous set as it was.
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace adjoin {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Empties the temporary to write it again from the start (the stream stays the same
  // object, so writers holding it go on writing into the new content).
  void restart();
  // Flushes, checks for write errors (InputError naming the file) and renames into place.
  void commit();
  // The two halves of commit(): finish() flushes and closes the temporary and checks that
  // everything was written; publish() renames it into place.
  void finish();
  void publish();
  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

class FileSet {
 public:
  // `members`: the names (in `dir`) that make up the set, whether this run writes them or not.
  FileSet(std::filesystem::path dir, std::vector<std::string> members);
  // Starts writing member `name`; the stream stays valid until commit().
  std::ostream& open(const std::string& name);
  // Empties every opened member (AtomicFile::restart).
  void restart();
  // All or none: finishes every opened member, then renames them all into place and removes
  // the members that were not opened. Returns the paths written, in the order opened.
  std::vector<std::filesystem::path> commit();

 private:
  std::filesystem::path dir_;
  std::vector<std::string> members_;
  std::vector<std::pair<std::string, std::unique_ptr<AtomicFile>>> files_;
};

}  // namespace adjoin
