#include "engine/core/files.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "engine/core/error.h"

namespace gmg {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary) {
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
  if (!in) throw Error(path + ": cannot open file (" + std::strerror(errno) + ")");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error(path + ": read error");
  return ss.str();
}

}  // namespace gmg
