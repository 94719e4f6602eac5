#pragma once
// Writing files so that nothing is lost, half-written or mixed.
//
// AtomicFile: the content goes to a temporary file beside the target ("<target>.tmp.<pid>"),
// which replaces the target (rename) only on commit(). If the writer is destroyed without
// commit() (an exception, a numerical failure), the temporary is removed and any previous file
// at the target is left untouched. Temporaries left by processes that died (killed, power
// cut) are removed when a new writer opens the same target.
//
// A target that exists and is not a regular file (a character device such as /dev/null or
// /dev/full, a FIFO, a socket; or a symbolic link to one) is written in place: renaming over
// it would replace the device or pipe with a plain file. Its content cannot be taken back, so
// restart() is refused, and a write error is reported like any other (InputError with the
// system's reason: "No space left on device").
//
// FileSet: the files of one run (or one command) that belong together. Each member is written
// in full to its temporary first; only when every one of them has been written without error
// are they renamed into place, and members of the set that this run did not write (left by an
// earlier run with other outputs) are removed, so a folder never holds a new summary beside an
// old time series (a device or pipe of a member's name is the user's and stays). A failure
// while writing (disk full) leaves the previous set as it was.
// The folder is created (with its missing parents) when the first member is opened, and
// removed again if the set is not committed (io/output_place.hpp).
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include "adjoin/io/output_place.hpp"

namespace adjoin {

namespace detail {
// An output buffer over a file descriptor that keeps the reason (errno) of the first write that
// failed, so a full disk or device is reported as such.
class FdOutBuffer final : public std::streambuf {
 public:
  FdOutBuffer();
  ~FdOutBuffer() override;
  FdOutBuffer(const FdOutBuffer&) = delete;
  FdOutBuffer& operator=(const FdOutBuffer&) = delete;

  void attach(int fd) { fd_ = fd; }
  int fd() const { return fd_; }
  // Drops what is buffered and empties the file (a regular file only).
  bool truncate();
  // Writes out what is buffered and closes the descriptor; false on any failure.
  bool close();
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  bool drain();
  int fd_ = -1;
  int error_ = 0;
  std::vector<char> buffer_;
};
}  // namespace detail

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
  // Where the content is until publish(): the temporary (the target when written in place).
  // After finish(), a command may read it back (to draw a figure from a table before the
  // table is committed).
  const std::filesystem::path& content() const { return in_place_ ? target_ : temporary_; }
  // True for a target written in place (a device or a pipe, see above).
  bool in_place() const { return in_place_; }

 private:
  void open_temporary();
  [[noreturn]] void write_failed(int error) const;
  std::filesystem::path target_, temporary_;
  std::string kind_;  // what the target is, when written in place ("a character device")
  detail::FdOutBuffer buffer_;
  std::ostream out_{&buffer_};
  bool in_place_ = false;
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
  // Finishes every opened member (AtomicFile::finish) without moving anything into place, and
  // returns where member `name`'s content can be read (AtomicFile::content).
  std::filesystem::path finish(const std::string& name);
  // All or none: finishes every opened member, then renames them all into place and removes
  // the members that were not opened. Returns the paths written, in the order opened.
  std::vector<std::filesystem::path> commit();

 private:
  std::filesystem::path dir_;
  std::vector<std::string> members_;
  std::optional<OutputFolder> folder_;  // destroyed after the files (their temporaries first)
  std::vector<std::pair<std::string, std::unique_ptr<AtomicFile>>> files_;
};

}  // namespace adjoin
