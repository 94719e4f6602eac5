#pragma once
// One writer per output: a command that builds its files over minutes (a sweep, with its
// journal) locks them first, so a second command writing the same files into the same folder
// at the same time is refused instead of mixing its rows into the first one's table.
//
// FolderLock takes an exclusive flock() on `dir/name` (created if needed) and holds it until it
// is destroyed; the file says who holds it ("pid=..." and "command=..." lines). The kernel
// releases the lock when the process ends, however it ends, so a killed command never leaves a
// stale lock behind; the file itself stays (removing it could let two processes lock two
// different files of the same name).
#include <filesystem>
#include <string>

namespace adjoin {

class FolderLock {
 public:
  // InputError "DIR/NAME: in use by pid N (COMMAND) ..." if another open file holds the lock
  // (another process, or another FolderLock of this one), or if the file cannot be made.
  FolderLock(const std::filesystem::path& dir, const std::string& name, const std::string& command);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace adjoin
