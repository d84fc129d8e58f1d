// engine/core/files: the one reader and the atomic writer.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::error_of;
using testing::TempDir;
using testing::write_text;

std::size_t entries_in(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(Files, ReadReturnsEveryByte) {
  TempDir dir;
  const std::string bytes(
      "a\r\n\0\xFF\xEF\xBB\xBF"
      "z",
      9);
  write_text(dir.file("b.bin"), bytes);
  EXPECT_EQ(read_file_bytes(dir.file("b.bin")), bytes);
  write_text(dir.file("empty"), "");
  EXPECT_EQ(read_file_bytes(dir.file("empty")), "");
}

TEST(Files, ReadLargerThanOneBuffer) {
  TempDir dir;
  std::string bytes(200001, '\0');  // three 64 KiB reads and a partial fourth
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7 % 251);
  write_text(dir.file("big"), bytes);
  EXPECT_EQ(read_file_bytes(dir.file("big")), bytes);
}

TEST(Files, ReadErrorsHaveOneWording) {
  TempDir dir;
  const std::string missing = dir.file("x.wav");
  EXPECT_EQ(error_of([&] { read_file_bytes(missing); }), missing + ": cannot open (No such file or directory)");
  EXPECT_EQ(error_of([&] { read_file_bytes(dir.path().string()); }), dir.path().string() + ": is a folder, not a file");
  const std::string below_file = dir.file("x.wav") + "/y";
  write_text(dir.file("x.wav"), "RIFF");
  EXPECT_EQ(error_of([&] { read_file_bytes(below_file); }), below_file + ": cannot open (Not a directory)");
}

TEST(Files, AtomicWriteReplacesTheFile) {
  TempDir dir;
  const std::string path = dir.file("out.txt");
  write_file_atomically(path, [](std::ostream& os) { os << "first"; });
  EXPECT_EQ(read_file_bytes(path), "first");
  write_file_atomically(
      path, [](std::ostream& os) { os << "second\r\n"; }, true);
  EXPECT_EQ(read_file_bytes(path), "second\r\n");
  EXPECT_EQ(entries_in(dir.path()), 1u);  // no temporary file left beside it
}

TEST(Files, AtomicWriteLeavesNoTempFileWhenTheWriterThrows) {
  TempDir dir;
  const std::string path = dir.file("out.txt");
  // The writer's own exception comes through unchanged.
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& os) {
                                       os << "half";
                                       throw std::logic_error("writer failed");
                                     }),
               std::logic_error);
  EXPECT_EQ(entries_in(dir.path()), 0u);

  // An existing file is left as it was.
  write_text(path, "old");
  EXPECT_THROW(write_file_atomically(path, [](std::ostream&) { throw Error("stop"); }), Error);
  EXPECT_EQ(read_file_bytes(path), "old");
  EXPECT_EQ(entries_in(dir.path()), 1u);
}

TEST(Files, AtomicWriteStreamFailureNamesTheFile) {
  TempDir dir;
  const std::string path = dir.file("bad.txt");
  const std::string msg = error_of([&] {
    write_file_atomically(path, [](std::ostream& os) {
      os << "x";
      os.setstate(std::ios::badbit);
    });
  });
  EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
  EXPECT_EQ(entries_in(dir.path()), 0u);
}

TEST(Files, AtomicWriteIntoMissingFolderNamesTheFile) {
  TempDir dir;
  const std::string path = dir.file("no/such/folder/out.txt");
  const std::string msg = error_of([&] { write_file_atomically(path, [](std::ostream& os) { os << "x"; }); });
  EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "No such file or directory");
}

}  // namespace
}  // namespace gmg
