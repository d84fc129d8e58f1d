// Reading input files: regular files read whole, with one wording for every "cannot read" error,
// and nothing but a regular file opened, so a FIFO or a device given as input cannot hang.
#pragma once

#include <cstddef>
#include <string>

#include <sys/types.h>
#include <unistd.h>

namespace gmg {

// Whole file as bytes: the one file reader of the engine (WAV, BVH, transcripts, lexicons, JSON
// all come through it), so every "cannot read" error has one wording, "path: what":
//   "x.wav: cannot open (No such file or directory)"
//   "x: is a folder, not a file"
//   "x: is a FIFO (named pipe), not a regular file"   (also: a character or block device, a socket)
//   "x: read error (Input/output error)"
//   "x: out of memory reading 123456789 bytes"      (engine/core/error.h naming_memory_errors)
// Anything but a regular file is refused before it is opened for reading (and the open itself
// cannot block), so a FIFO or a device given as input cannot hang or stream forever.
std::string read_file_bytes(const std::string& path);

// Throws read_file_bytes's error when path exists and is not a regular file (a missing file is
// left to the reader's "cannot open").
void check_input_file(const std::string& path);

// Throws read_file_bytes's error when path cannot be opened for reading or is not a regular
// file; reads nothing. For checking every input of a job before its long steps.
void check_readable_file(const std::string& path);

// What a file that is not regular is, for "x: is a FIFO (named pipe), not a regular file": "a FIFO
// (named pipe)", "a character device", "a block device", "a socket", else "not a regular file".
const char* file_kind(mode_t mode);

// An open file descriptor, closed when it goes (unless released).
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  FileDescriptor& operator=(FileDescriptor&&) = delete;
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

// Opens a regular file for reading; *out_size gets its size. Anything else is refused before
// the open (read_file_bytes's errors), and O_NONBLOCK makes the open return at once should the
// file have become a FIFO since the check (fstat then refuses it).
FileDescriptor open_regular(const std::string& path, std::size_t* out_size);

}  // namespace gmg
