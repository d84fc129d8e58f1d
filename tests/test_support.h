// Helpers shared by the tests: temporary folders, the shared data folder.
#pragma once

#include <filesystem>
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

// Writes text (bytes as given) to a file.
void write_text(const std::string& path, const std::string& text);

}  // namespace gmg::testing

// Skips the current test when ../shared/data is absent.
#define GMG_REQUIRE_SHARED_DATA()                                              \
  do {                                                                         \
    if (gmg::testing::shared_data_dir().empty())                               \
      GTEST_SKIP() << "../shared/data is absent: skipping the real-data test"; \
  } while (0)
