#include "adjoin/io/atomic_file.hpp"

#include <unistd.h>

#include <system_error>

#include "adjoin/errors.hpp"

namespace adjoin {

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  temporary_ = target_;
  temporary_ += ".tmp." + std::to_string(::getpid());
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

void AtomicFile::commit() {
  out_.flush();
  if (!out_) throw InputError(target_.string() + ": write failed (disk full?)");
  out_.close();
  std::error_code error;
  std::filesystem::rename(temporary_, target_, error);
  if (error) throw InputError(target_.string() + ": cannot move the finished file into place: " + error.message());
  committed_ = true;
}

}  // namespace adjoin
