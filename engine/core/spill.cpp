#include "engine/core/spill.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/core/error.h"
#include "engine/core/interrupt.h"

namespace gmg {

SpillFile::SpillFile(std::string folder, std::size_t memory_limit)
    : folder_(std::move(folder)), limit_(memory_limit), memory_(std::make_shared<std::vector<char>>()) {}

SpillFile::~SpillFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!path_.empty() && !file_) ::unlink(path_.c_str());
  if (slot_ >= 0) unregister_temporary_file(slot_);
}

void SpillFile::append(const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  if (file_) throw Error("SpillFile: append after finish");
  if (fd_ < 0 && !folder_.empty() && size_ + bytes > limit_) spill();
  if (fd_ >= 0) {
    write(data, bytes);
  } else {
    const char* p = static_cast<const char*>(data);
    memory_->insert(memory_->end(), p, p + bytes);
  }
  size_ += bytes;
}

// Moves what is in memory to a new temporary file; appends go there from now on.
void SpillFile::spill() {
  path_ = temporary_name_for(folder_ + "/gmg-build.spill");
  slot_ = register_temporary_file(path_);  // before the file exists, so a signal never misses it
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd_ < 0) throw Error(folder_ + ": cannot write a temporary file (" + std::strerror(errno) + ")");
  write(memory_->data(), memory_->size());
  std::vector<char>().swap(*memory_);
}

void SpillFile::write(const void* data, std::size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd_, p, bytes);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      throw Error(folder_ + ": cannot write a temporary file (" + std::strerror(err) + ")");
    }
    p += n;
    bytes -= static_cast<std::size_t>(n);
  }
}

SpillFile::Bytes SpillFile::finish() {
  Bytes b;
  if (file_ || fd_ >= 0) {
    if (!file_) {
      ::close(fd_);
      fd_ = -1;
      file_ = std::make_shared<const MappedFile>(path_);
      ::unlink(path_.c_str());  // the mapping keeps the pages
      unregister_temporary_file(slot_);
      slot_ = -1;
    }
    b.data = file_->data();
    b.size = file_->size();
    b.owner = file_;
    b.file = file_;
    return b;
  }
  b.data = memory_->data();
  b.size = memory_->size();
  b.owner = memory_;
  return b;
}

}  // namespace gmg
