#include "adjoin/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"

namespace adjoin {
namespace {

// Removes "<target>.tmp.<pid>" files beside `target` whose process no longer exists.
void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::string prefix = target.filename().string() + ".tmp.";
  std::error_code ec;
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  for (auto it = std::filesystem::directory_iterator(dir, ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    std::size_t number = 0;
    if (digits.size() > 9 || !parse_count(digits, &number)) continue;
    const pid_t pid = static_cast<pid_t>(number);
    if (pid == ::getpid()) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

}  // namespace

namespace detail {

FdOutBuffer::FdOutBuffer() : buffer_(std::size_t{1} << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }

FdOutBuffer::~FdOutBuffer() {
  if (fd_ >= 0) ::close(fd_);
}

bool FdOutBuffer::drain() {
  const char* data = pbase();
  std::size_t left = static_cast<std::size_t>(pptr() - pbase());
  while (left > 0 && error_ == 0) {
    const ssize_t n = ::write(fd_, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error_ = n < 0 ? errno : EIO;
      break;
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  return error_ == 0;
}

FdOutBuffer::int_type FdOutBuffer::overflow(int_type c) {
  if (fd_ < 0 || !drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int FdOutBuffer::sync() { return fd_ >= 0 && drain() ? 0 : -1; }

bool FdOutBuffer::truncate() {
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  error_ = 0;
  if (::ftruncate(fd_, 0) != 0 || ::lseek(fd_, 0, SEEK_SET) != 0) error_ = errno;
  return error_ == 0;
}

bool FdOutBuffer::close() {
  if (fd_ < 0) return error_ == 0;
  drain();
  if (::close(fd_) != 0 && error_ == 0) error_ = errno;  // NFS and quotas report here
  fd_ = -1;
  return error_ == 0;
}

}  // namespace detail

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(target_, ec);  // through symbolic links
  if (std::filesystem::is_directory(status))
    throw InputError(target_.string() + ": is a folder; expected the name of a file to write");
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    // A device or a pipe: written in place, never replaced (a rename would put a plain file
    // where /dev/null was).
    in_place_ = true;
    kind_ = file_kind(status);
    const int fd = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) {
      const int error = errno;
      throw InputError(target_.string() + ": cannot write into this " + kind_.substr(kind_.find(' ') + 1) + ": " +
                       std::strerror(error));
    }
    buffer_.attach(fd);
    return;
  }
  remove_stale_temporaries(target_);
  temporary_ = target_;
  temporary_ += ".tmp." + std::to_string(::getpid());
  open_temporary();
}

void AtomicFile::open_temporary() {
  const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    throw InputError(target_.string() + ": cannot write here (" + std::strerror(error) +
                     "; check the folder exists and is writable)");
  }
  buffer_.attach(fd);
}

void AtomicFile::restart() {
  if (in_place_)
    throw InputError(target_.string() + ": is " + kind_ +
                     ", written in place, and this output is written again from the start (a run to a tolerance "
                     "streams each step it tries): write it to a regular file instead");
  out_.clear();
  if (!buffer_.truncate()) write_failed(buffer_.error());
}

AtomicFile::~AtomicFile() {
  if (!committed_ && !in_place_) {
    buffer_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::write_failed(int error) const {
  const std::string why = error != 0 ? std::strerror(error) : std::string("the stream failed");
  if (in_place_) throw InputError(target_.string() + ": write failed: " + why + " (" + kind_ + ", written in place)");
  throw InputError(target_.string() + ": write failed: " + why + "; nothing was replaced");
}

void AtomicFile::finish() {
  if (committed_ || buffer_.fd() < 0) return;
  out_.flush();
  const bool stream_ok = static_cast<bool>(out_);
  if (!buffer_.close() || !stream_ok) write_failed(buffer_.error());
}

void AtomicFile::publish() {
  if (in_place_) {
    committed_ = true;
    return;
  }
  std::error_code error;
  std::filesystem::rename(temporary_, target_, error);
  if (error) throw InputError(target_.string() + ": cannot move the finished file into place: " + error.message());
  committed_ = true;
}

void AtomicFile::commit() {
  finish();
  publish();
}

FileSet::FileSet(std::filesystem::path dir, std::vector<std::string> members)
    : dir_(std::move(dir)), members_(std::move(members)) {}

std::ostream& FileSet::open(const std::string& name) {
  if (!folder_) folder_.emplace(dir_);
  files_.emplace_back(name, std::make_unique<AtomicFile>(dir_ / name));
  return files_.back().second->stream();
}

void FileSet::restart() {
  for (auto& [name, file] : files_) file->restart();
}

std::filesystem::path FileSet::finish(const std::string& name) {
  std::filesystem::path content;
  for (auto& [member, file] : files_) {
    file->finish();
    if (member == name) content = file->content();
  }
  if (content.empty()) throw std::logic_error("FileSet::finish: " + name + " was not opened");
  return content;
}

std::vector<std::filesystem::path> FileSet::commit() {
  for (auto& [name, file] : files_) file->finish();  // every byte written before anything moves
  std::vector<std::filesystem::path> written;
  for (auto& [name, file] : files_) {
    file->publish();
    written.push_back(file->target());
  }
  if (folder_) folder_->keep();
  for (const auto& member : members_) {
    const bool opened = std::any_of(files_.begin(), files_.end(), [&](const auto& f) { return f.first == member; });
    std::error_code ignored;
    // An earlier run's file goes; a device or pipe of that name is the user's, not a run's.
    const auto status = std::filesystem::symlink_status(dir_ / member, ignored);
    const bool earlier_output = std::filesystem::is_regular_file(status) || std::filesystem::is_symlink(status);
    if (!opened && earlier_output) std::filesystem::remove(dir_ / member, ignored);
  }
  return written;
}

}  // namespace adjoin
