#include "engine/core/file_read.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>

#include "engine/core/error.h"

namespace gmg {

const char* file_kind(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

namespace {

void refuse_non_regular(const std::string& path, mode_t mode) {
  if (S_ISREG(mode)) return;
  if (S_ISDIR(mode)) throw Error(path + ": is a folder, not a file");
  const std::string kind = file_kind(mode);
  throw Error(path + ": is " + kind + ", not a regular file");
}

std::string read_all(const std::string& path, int fd, std::size_t size_hint) {
  std::string bytes;
  bytes.reserve(size_hint);
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(path + ": read error (" + std::strerror(errno) + ")");
    }
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  return bytes;
}

}  // namespace

void check_input_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) refuse_non_regular(path, st.st_mode);
}

FileDescriptor open_regular(const std::string& path, std::size_t* out_size) {
  check_input_file(path);
  FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  refuse_non_regular(path, st.st_mode);
  *out_size = static_cast<std::size_t>(st.st_size);
  return fd;
}

void check_readable_file(const std::string& path) {
  std::size_t size = 0;
  open_regular(path, &size);
}

std::string read_file_bytes(const std::string& path) {
  std::size_t size = 0;
  const FileDescriptor fd = open_regular(path, &size);
  return naming_memory_errors(path, "reading " + std::to_string(size) + " bytes",
                              [&] { return read_all(path, fd.get(), size); });
}

}  // namespace gmg
