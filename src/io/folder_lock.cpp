#include "adjoin/io/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/text_file.hpp"

namespace adjoin {
namespace {

// The holder's own words, from the lock file: "pid 123 (adjoin sweep a.toml)".
std::string holder(int fd) {
  std::string text(4096, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  std::string pid, command;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(pos, end - pos);
    if (line.rfind("pid=", 0) == 0) pid = line.substr(4);
    if (line.rfind("command=", 0) == 0) command = line.substr(8);
    pos = end + 1;
  }
  if (pid.empty()) return "another process (it has not written its pid yet)";
  const bool digits = pid.find_first_not_of("0123456789") == std::string::npos;
  return "pid " + (digits ? pid : escaped_excerpt(pid, 20)) +
         (command.empty() ? std::string() : " (" + escaped_excerpt(command, 200) + ")");
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& dir, const std::string& name, const std::string& command)
    : path_(dir / name) {
  // O_NONBLOCK: a FIFO of that name must not block the command; it is refused below.
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd_ < 0) {
    const int error = errno;
    throw InputError(path_.string() + ": cannot create the lock file of the output folder: " + std::strerror(error));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw InputError(path_.string() + ": the lock file of the output folder is not a regular file; remove it (the "
                     "command makes its own) or give another --out");
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string who = error == EWOULDBLOCK ? holder(fd_) : std::string();
    ::close(fd_);
    fd_ = -1;
    if (error != EWOULDBLOCK)
      throw InputError(path_.string() + ": cannot lock the output folder: " + std::strerror(error));
    throw InputError(path_.string() + ": the output folder is in use by " + who +
                     ", which writes the same files; wait for it to finish, or give this one another --out");
  }
  const std::string text = "pid=" + std::to_string(::getpid()) + "\ncommand=" + command + "\n";
  // Best effort: the lock holds whether or not the note is written.
  bool noted = ::ftruncate(fd_, 0) == 0;
  noted = noted && ::pwrite(fd_, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size());
  (void)noted;
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace adjoin
