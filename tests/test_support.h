// Helpers shared by the tests: temporary folders, the shared data folder.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

namespace gmg::testing {

// Absolute path of ../shared/data, or "" when it is absent (tests then GTEST_SKIP).
std::string shared_data_dir();

// A fresh, empty temporary folder removed when the object goes out of scope.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// A small file system of its own (tmpfs) for the cases a full or read-only disk makes: mounted on a
// fresh folder, `size_kb` large (at least a few KB), read-only when asked (after `fill`, called
// with the folder while it is still writable). Mounting needs root (CAP_SYS_ADMIN): ok() is false
// otherwise, and the test skips with why(). Unmounted and removed when the object goes.
class SmallDisk {
 public:
  explicit SmallDisk(int size_kb, bool read_only = false,
                     const std::function<void(const std::filesystem::path&)>& fill = {});
  ~SmallDisk();
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  bool ok() const { return mounted_; }
  const std::string& why() const { return why_; }
  const std::filesystem::path& path() const { return dir_.path(); }
  std::string file(const std::string& name) const { return dir_.file(name); }

 private:
  TempDir dir_;
  bool mounted_ = false;
  std::string why_;
};

// Writes text (bytes as given) to a file.
void write_text(const std::string& path, const std::string& text);

// How many pages of [p, p + size) are mapped in this process (/proc/self/pagemap's present bit;
// 0 when it cannot be read).
std::size_t present_pages(const void* p, std::size_t size);

}  // namespace gmg::testing

// Skips the current test when ../shared/data is absent.
#define GMG_REQUIRE_SHARED_DATA()                                              \
  do {                                                                         \
    if (gmg::testing::shared_data_dir().empty())                               \
      GTEST_SKIP() << "../shared/data is absent: skipping the real-data test"; \
  } while (0)
