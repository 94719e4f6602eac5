#pragma once
// Where a command's files go (--out DIR): checked before any work, created only to commit the
// files, and left as it was when the command fails.
//
//     check_output_folder(dir, "--out");     // before the runs: InputError "--out DIR: why"
//     ... runs ...
//     OutputFolder folder(dir, "--out");     // creates DIR and its missing parents
//     ... write the files, commit them ...
//     folder.keep();                         // otherwise the folders it made are removed again
//
// FileSet (io/atomic_file.hpp) holds an OutputFolder of its own: a set's folder exists only
// once the set is committed.
#include <filesystem>
#include <string>
#include <vector>

namespace adjoin {

// InputError "OPTION DIR: cannot ... : why" (exit 2) unless `dir` is a folder this process may
// write into, or can be made one: every part of it that exists is a folder, and the deepest
// one that exists is writable (a read-only file system is refused even for root).
void check_output_folder(const std::filesystem::path& dir, const std::string& option = "--out");

// What a path is, in words for messages: "a file", "a folder", "a character device", ...
std::string file_kind(const std::filesystem::file_status& status);

class OutputFolder {
 public:
  // Creates `dir` and its missing parents (InputError naming `option` and why, if it cannot).
  explicit OutputFolder(const std::filesystem::path& dir, const std::string& option = "--out");
  // Removes the folders it created, deepest first, unless keep() was called; a folder that is
  // no longer empty (someone else wrote into it) stays.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  void keep() { kept_ = true; }

 private:
  void remove_created();
  std::vector<std::filesystem::path> created_;  // outermost first
  bool kept_ = false;
};

}  // namespace adjoin
