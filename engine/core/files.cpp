#include "engine/core/files.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "engine/core/error.h"

namespace gmg {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
  static std::atomic<unsigned> counter{0};
  const std::string temp = path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  auto remove_temp = [&] {
    std::error_code ec;
    std::filesystem::remove(temp, ec);
  };
  {
    std::ofstream out(temp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
    if (!out) throw Error(path + ": cannot write file (" + std::strerror(errno) + ")");
    try {
      write(out);
    } catch (...) {
      out.close();
      remove_temp();
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      remove_temp();
      throw Error(path + ": write failed (disk full or unwritable?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    remove_temp();
    throw Error(path + ": cannot rename the finished file into place (" + ec.message() + ")");
  }
}

std::string read_file_bytes(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  // istream::read, not `out << in.rdbuf()`: the latter reports a failing read(2) on the output
  // stream and leaves `in` good, so a read error would pass as a short file.
  std::string bytes;
  if (const auto size = std::filesystem::file_size(path, ec); !ec) bytes.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  errno = 0;
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) bytes.append(buffer, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw Error(path + ": read error (" + std::strerror(errno) + ")");
  return bytes;
}

}  // namespace gmg
