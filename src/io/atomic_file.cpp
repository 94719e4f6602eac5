#include "adjoin/io/atomic_file.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <string>
#include <system_error>

#include "adjoin/errors.hpp"

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
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) || digits.size() > 9)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid == ::getpid()) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  remove_stale_temporaries(target_);
  temporary_ = target_;
  temporary_ += ".tmp." + std::to_string(::getpid());
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(target_.string() + ": cannot write here (check the folder exists and is writable)");
}

void AtomicFile::restart() {
  out_.close();
  out_.clear();
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(target_.string() + ": cannot write here (check the folder exists and is writable)");
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::finish() {
  if (!out_.is_open()) return;
  out_.flush();
  if (!out_) throw InputError(target_.string() + ": write failed (disk full?); nothing was replaced");
  out_.close();
  if (!out_) throw InputError(target_.string() + ": write failed (disk full?); nothing was replaced");
}

void AtomicFile::publish() {
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
  files_.emplace_back(name, std::make_unique<AtomicFile>(dir_ / name));
  return files_.back().second->stream();
}

void FileSet::restart() {
  for (auto& [name, file] : files_) file->restart();
}

std::vector<std::filesystem::path> FileSet::commit() {
  for (auto& [name, file] : files_) file->finish();  // every byte written before anything moves
  std::vector<std::filesystem::path> written;
  for (auto& [name, file] : files_) {
    file->publish();
    written.push_back(file->target());
  }
  for (const auto& member : members_) {
    const bool opened = std::any_of(files_.begin(), files_.end(), [&](const auto& f) { return f.first == member; });
    std::error_code ignored;
    if (!opened) std::filesystem::remove(dir_ / member, ignored);
  }
  return written;
}

}  // namespace adjoin
