#include "adjoin/io/output_place.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "adjoin/core/errors.hpp"

namespace adjoin {
namespace {

namespace fs = std::filesystem;

// The parent of `p` as a path that names a place: "." for a bare relative name.
fs::path parent_of(const fs::path& p) {
  const fs::path parent = p.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// The deepest part of `dir` that exists (dir itself or one of its parents), and what it is;
// `error` is set (errno) when a part cannot be looked at for another reason than its absence.
struct Existing {
  fs::path path;
  fs::file_status status;
  int error = 0;
};

Existing deepest_existing(const fs::path& dir) {
  Existing e{dir, {}, 0};
  for (;;) {
    struct stat st {};
    if (::stat(e.path.c_str(), &st) == 0) {
      e.status = fs::status(e.path);
      return e;
    }
    if ((errno != ENOENT && errno != ENOTDIR) || e.path == parent_of(e.path)) {
      e.error = errno;
      return e;
    }
    e.path = parent_of(e.path);
  }
}

// The parts of `dir` that do not exist, outermost first.
std::vector<fs::path> missing_parts(const fs::path& dir) {
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = dir; !fs::exists(fs::symlink_status(p, ec)) && p != parent_of(p); p = parent_of(p)) missing.push_back(p);
  std::reverse(missing.begin(), missing.end());
  return missing;
}

}  // namespace

std::string file_kind(const fs::file_status& status) {
  switch (status.type()) {
    case fs::file_type::regular: return "a file";
    case fs::file_type::directory: return "a folder";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::symlink: return "a symbolic link";
    default: return "not a file or folder";
  }
}

void check_output_folder(const fs::path& dir, const std::string& option) {
  if (dir.empty()) throw InputError(option + ": expected a folder name, got nothing");
  const std::string where = option + " " + dir.string() + ": ";
  const Existing e = deepest_existing(dir);
  const bool self = e.path == dir;
  if (e.error != 0)
    throw InputError(where + "cannot be the output folder: " + (self ? "" : e.path.string() + ": ") + std::strerror(e.error));
  if (!fs::is_directory(e.status)) {
    if (self) throw InputError(where + "is " + file_kind(e.status) + ", not a folder");
    throw InputError(where + "cannot create the output folder: " + e.path.string() + " is " + file_kind(e.status) +
                     ", not a folder");
  }
  if (::access(e.path.c_str(), W_OK | X_OK) != 0) {
    const std::string why = std::strerror(errno);
    if (self) throw InputError(where + "cannot write into this folder: " + why);
    throw InputError(where + "cannot create the output folder: cannot write into " + e.path.string() + ": " + why);
  }
}

OutputFolder::OutputFolder(const fs::path& dir, const std::string& option) {
  check_output_folder(dir, option);
  for (const fs::path& part : missing_parts(dir)) {
    if (::mkdir(part.c_str(), 0777) == 0) {
      created_.push_back(part);
    } else if (errno != EEXIST) {
      const std::string why = std::strerror(errno);
      remove_created();
      throw InputError(option + " " + dir.string() + ": cannot create the output folder: " + part.string() + ": " + why);
    }
  }
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {  // made a file by someone else in the meantime
    remove_created();
    throw InputError(option + " " + dir.string() + ": cannot create the output folder: it is not a folder");
  }
}

OutputFolder::~OutputFolder() {
  if (!kept_) remove_created();
}

void OutputFolder::remove_created() {
  for (auto it = created_.rbegin(); it != created_.rend(); ++it)
    if (::rmdir(it->c_str()) != 0) break;  // not empty: someone else's files are in it
  created_.clear();
}

}  // namespace adjoin
