#include "tests/test_support.h"

#include <atomic>
#include <fstream>
#include <random>
#include <stdexcept>

#include <fcntl.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

namespace gmg::testing {

std::string shared_data_dir() {
  std::filesystem::path dir(GMG_SHARED_DATA_DIR);
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return "";
  return std::filesystem::canonical(dir, ec).string();
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  for (int attempt = 0; attempt < 100; ++attempt) {
    auto candidate =
        std::filesystem::temp_directory_path() / ("gmg_test_" + std::to_string(::getpid()) + "_" +
                                                  std::to_string(counter++) + "_" + std::to_string(rd() % 100000));
    if (std::filesystem::create_directory(candidate)) {
      path_ = candidate;
      return;
    }
  }
  throw std::runtime_error("cannot create a temporary folder");
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

SmallDisk::SmallDisk(int size_kb, bool read_only, const std::function<void(const std::filesystem::path&)>& fill) {
  const std::string options = "size=" + std::to_string(size_kb) + "k,mode=0777";
  if (::mount("tmpfs", dir_.path().c_str(), "tmpfs", 0, options.c_str()) != 0) {
    why_ = std::string("cannot mount a small tmpfs (") + std::strerror(errno) + "): needs root";
    return;
  }
  mounted_ = true;
  if (fill) fill(dir_.path());
  if (read_only && ::mount("tmpfs", dir_.path().c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, options.c_str()) != 0) {
    why_ = std::string("cannot make the tmpfs read-only (") + std::strerror(errno) + ")";
    ::umount2(dir_.path().c_str(), MNT_DETACH);
    mounted_ = false;
  }
}

SmallDisk::~SmallDisk() {
  if (mounted_) ::umount2(dir_.path().c_str(), MNT_DETACH);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::size_t present_pages(const void* p, std::size_t size) {
  const long page = ::sysconf(_SC_PAGESIZE);
  const int fd = ::open("/proc/self/pagemap", O_RDONLY);
  if (fd < 0) return 0;
  std::size_t present = 0;
  for (std::size_t off = 0; off < size; off += static_cast<std::size_t>(page)) {
    std::uint64_t entry = 0;
    const auto at =
        static_cast<off_t>((reinterpret_cast<std::uintptr_t>(p) + off) / static_cast<std::size_t>(page) * 8);
    if (::pread(fd, &entry, sizeof entry, at) == static_cast<ssize_t>(sizeof entry) && (entry >> 63) != 0) ++present;
  }
  ::close(fd);
  return present;
}

}  // namespace gmg::testing
