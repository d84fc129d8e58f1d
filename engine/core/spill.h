// Arrays too large to keep in memory while a job builds them (the motion and pose features of hours
// of reference): appended in pieces, held in memory up to a limit, then moved to a temporary file
// in a given folder (the job's output folder: the same disk as the result, not a /tmp that may be
// memory). Read back through a read-only mapping whose pages a pass over them can give back
// (MappedFile::release), so what stays resident is what is being read. The file is unlinked as
// soon as it is mapped (and removed on an interrupt before that), so none outlives the job.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/files.h"

namespace gmg {

class SpillFile {
 public:
  // folder "" keeps everything in memory.
  SpillFile(std::string folder, std::size_t memory_limit);
  ~SpillFile();
  SpillFile(const SpillFile&) = delete;
  SpillFile& operator=(const SpillFile&) = delete;

  // Appends `bytes` bytes. Throws gmg::Error naming the folder when the temporary file cannot be
  // written (a full disk).
  void append(const void* data, std::size_t bytes);
  std::size_t size() const { return size_; }
  bool spilled() const { return fd_ >= 0 || file_ != nullptr; }

  // The bytes appended, after the last append: in memory, or the file's mapping. `owner` keeps
  // them alive; `file` is the mapping (null in memory), for giving pages back.
  struct Bytes {
    const char* data = nullptr;
    std::size_t size = 0;
    std::shared_ptr<const void> owner;
    std::shared_ptr<const MappedFile> file;
  };
  Bytes finish();

 private:
  void spill();
  void write(const void* data, std::size_t bytes);

  std::string folder_;
  std::size_t limit_;
  std::size_t size_ = 0;
  std::shared_ptr<std::vector<char>> memory_;
  std::string path_;
  int fd_ = -1;
  int slot_ = -1;
  std::shared_ptr<const MappedFile> file_;
};

}  // namespace gmg
