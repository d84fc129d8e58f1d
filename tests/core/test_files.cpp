// engine/core/files: the one reader and the atomic writer.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/interrupt.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::error_of;
using testing::present_pages;
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

// A stream buffer that keeps every write it is given, as the file's write() calls would be.
class RecordingBuffer : public std::streambuf {
 public:
  std::vector<std::string> writes;

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    writes.emplace_back(s, static_cast<std::size_t>(n));
    return n;
  }
  int_type overflow(int_type c) override {
    if (c != traits_type::eof()) writes.emplace_back(1, traits_type::to_char_type(c));
    return c;
  }
};

// Pieces of any size, a few bytes to several blocks, reach the stream as whole blocks at multiples
// of the block from the start, and the rest at flush(), the same bytes in the same order.
TEST(Files, BlockWriterWritesWholeAlignedBlocks) {
  RecordingBuffer recorded;
  std::ostream out(&recorded);
  BlockWriter w(out, 16);
  std::string expected;
  for (std::size_t size : {3, 5, 40, 1, 16, 7, 0, 33}) {
    std::string piece;
    for (std::size_t i = 0; i < size; ++i) piece += static_cast<char>('a' + (expected.size() + i) % 26);
    w.write(piece.data(), piece.size());
    expected += piece;
  }
  EXPECT_EQ(recorded.writes.size(), expected.size() / 16);  // only whole blocks before flush()
  w.flush();
  w.flush();  // nothing more
  ASSERT_EQ(recorded.writes.size(), expected.size() / 16 + 1);
  std::string joined;
  for (std::size_t i = 0; i < recorded.writes.size(); ++i) {
    EXPECT_EQ(recorded.writes[i].size(), i + 1 < recorded.writes.size() ? 16u : expected.size() % 16) << i;
    joined += recorded.writes[i];
  }
  EXPECT_EQ(joined, expected);
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

TEST(Files, ReadRefusesAFifoWithoutWaitingForAWriter) {
  TempDir dir;
  const std::string fifo = dir.file("pipe.wav");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  // Opening a FIFO for reading blocks until a writer comes; the reader must refuse it first.
  EXPECT_EQ(error_of([&] { read_file_bytes(fifo); }), fifo + ": is a FIFO (named pipe), not a regular file");
  EXPECT_EQ(error_of([&] { check_input_file(fifo); }), fifo + ": is a FIFO (named pipe), not a regular file");
}

TEST(Files, ReadRefusesADevice) {
  // /dev/zero would never end; /dev/null is the one every system has.
  EXPECT_EQ(error_of([] { read_file_bytes("/dev/null"); }), "/dev/null: is a character device, not a regular file");
  check_input_file("/no/such/file");  // a missing file is left to the reader's "cannot open"
}

TEST(Files, MappedFileHoldsEveryByte) {
  TempDir dir;
  std::string bytes(70000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 13 % 256);
  write_text(dir.file("g.gmg"), bytes);
  const MappedFile file(dir.file("g.gmg"));
  ASSERT_EQ(file.size(), bytes.size());
  EXPECT_EQ(std::string(file.data(), file.size()), bytes);
  write_text(dir.file("empty"), "");
  const MappedFile empty(dir.file("empty"));
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_EQ(empty.data(), nullptr);
}

TEST(Files, MappedFileRefusesWhatTheReaderRefuses) {
  TempDir dir;
  const std::string missing = dir.file("x.gmg");
  EXPECT_EQ(error_of([&] { MappedFile f(missing); }), missing + ": cannot open (No such file or directory)");
  EXPECT_EQ(error_of([&] { MappedFile f(dir.path().string()); }), dir.path().string() + ": is a folder, not a file");
  EXPECT_EQ(error_of([] { MappedFile f("/dev/null"); }), "/dev/null: is a character device, not a regular file");
  const std::string fifo = dir.file("pipe.gmg");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_EQ(error_of([&] { MappedFile f(fifo); }), fifo + ": is a FIFO (named pipe), not a regular file");
}

TEST(Files, MappedFileCutShortReadsZerosAndSaysSo) {
  TempDir dir;
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  write_text(dir.file("g.gmg"), std::string(3 * page, 'x'));
  const MappedFile file(dir.file("g.gmg"));
  EXPECT_FALSE(file.changed());
  EXPECT_EQ(file.data()[page + 1], 'x');
  ASSERT_EQ(::truncate(dir.file("g.gmg").c_str(), static_cast<off_t>(page)), 0);
  // Without the SIGBUS handler this read past the file's new end kills the process.
  EXPECT_EQ(file.data()[2 * page + 5], '\0');
  EXPECT_EQ(file.data()[page + 1], '\0');
  EXPECT_TRUE(file.changed());
  EXPECT_EQ(
      error_of([&] { file.check_unchanged(); }),
      dir.file("g.gmg") + ": changed while in use (it was truncated or written to; read it again when it is complete)");
}

TEST(Files, MappedFileNoticesAWriteInPlace) {
  TempDir dir;
  write_text(dir.file("g.gmg"), std::string(10000, 'x'));
  // An old modification time, so the write below changes it whatever the clock's resolution.
  const timespec old_times[2] = {{1000000, 0}, {1000000, 0}};
  ASSERT_EQ(::utimensat(AT_FDCWD, dir.file("g.gmg").c_str(), old_times, 0), 0);
  const MappedFile file(dir.file("g.gmg"));
  file.check_unchanged();
  {
    std::fstream f(dir.file("g.gmg"), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(5000);
    f.put('y');
  }
  EXPECT_TRUE(file.changed());
  EXPECT_NE(error_of([&] { file.check_unchanged(); }).find(": changed while in use"), std::string::npos);
}

TEST(Files, MappedFileReleaseKeepsTheBytes) {
  TempDir dir;
  std::string bytes(200000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7 % 251);
  write_text(dir.file("g.gmg"), bytes);
  const MappedFile file(dir.file("g.gmg"));
  EXPECT_EQ(std::string(file.data(), file.size()), bytes);
  file.release(0, file.size());  // the pages go back to the page cache, the bytes stay readable
  EXPECT_EQ(std::string(file.data(), file.size()), bytes);
  EXPECT_FALSE(file.changed());
}

// release_mapped_pages gives back the pages of a live mapping that a range covers, and leaves
// other memory (an ordinary vector) alone.
TEST(Files, ReleaseMappedPagesDropsOnlyMappedPages) {
  TempDir dir;
  std::string bytes(1 << 20, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 13 % 241);
  write_text(dir.file("g.gmg"), bytes);
  const MappedFile file(dir.file("g.gmg"));
  long sum = 0;
  for (std::size_t i = 0; i < file.size(); i += 4096) sum += file.data()[i];
  EXPECT_NE(sum, 0);
  ASSERT_GT(present_pages(file.data(), file.size()), 0u) << "reading maps pages";
  release_mapped_pages(file.data() + 1000, file.size() - 1000);  // from inside the first page on
  EXPECT_LE(present_pages(file.data(), file.size()), 1u) << "only the first page, partly outside the range, stays";
  EXPECT_EQ(std::string(file.data(), file.size()), bytes);
  std::vector<char> own(1 << 16, 'x');
  release_mapped_pages(own.data(), own.size());
  EXPECT_EQ(std::string(own.begin(), own.end()), std::string(own.size(), 'x'));
  release_mapped_pages(nullptr, 100);
}

TEST(Files, RenameIntoPlaceReplacesTheFile) {
  TempDir dir;
  write_text(dir.file("out.mp4"), "old");
  write_text(dir.file("out.tmp1.mp4"), "new");
  rename_into_place(dir.file("out.tmp1.mp4"), dir.file("out.mp4"));
  EXPECT_EQ(read_file_bytes(dir.file("out.mp4")), "new");
  EXPECT_EQ(entries_in(dir.path()), 1u);
}

TEST(Files, RenameIntoPlaceFailureRemovesTheTemporaryFile) {
  TempDir dir;
  write_text(dir.file("out.tmp1.mp4"), "new");
  const std::string target = dir.file("no/such/folder/out.mp4");
  const std::string msg = error_of([&] { rename_into_place(dir.file("out.tmp1.mp4"), target); });
  EXPECT_EQ(msg.rfind(target + ": cannot rename the finished file into place (", 0), 0u) << msg;
  EXPECT_EQ(entries_in(dir.path()), 0u);
}

TEST(Files, OutputsApartFromInputs) {
  TempDir dir;
  const std::string in = dir.file("in.bvh"), other = dir.file("other.bvh");
  write_text(in, "x");
  std::filesystem::create_symlink(in, dir.file("link.bvh"));
  std::filesystem::create_hard_link(in, dir.file("hard.bvh"));
  const std::vector<NamedFile> inputs = {{"--motion", in}, {"--audio", ""}};
  EXPECT_EQ(error_of([&] {
              check_outputs_apart({{"-o", in}}, inputs);
            }),
            in + ": -o would overwrite the input given as --motion; choose another output");
  EXPECT_EQ(
      error_of([&] {
        check_outputs_apart({{"-o", dir.file("link.bvh")}}, inputs);
      }),
      dir.file("link.bvh") + ": -o would overwrite the input given as --motion (" + in + "); choose another output");
  EXPECT_NE(error_of([&] { check_outputs_apart({{"-o", dir.file("hard.bvh")}}, inputs); }), "");
  // The same file by another spelling, not yet existing: two outputs.
  EXPECT_EQ(error_of([&] {
              check_outputs_apart({{"-o", other}, {"--report", dir.file("./other.bvh")}}, inputs);
            }),
            dir.file("./other.bvh") + ": given as both -o and --report; each output needs its own file");
  check_outputs_apart({{"-o", other}, {"--report", ""}}, inputs);  // distinct or empty: fine
}

TEST(Files, TransactionCommitsEveryFileOrNone) {
  TempDir dir;
  const std::string a = dir.file("a.bvh"), b = dir.file("b.json");
  write_text(b, "old");
  {
    OutputTransaction t;
    write_file_atomically(a, [](std::ostream& os) { os << "motion"; });
    write_file_atomically(b, [](std::ostream& os) { os << "report"; });
    EXPECT_FALSE(std::filesystem::exists(a));  // staged, not yet in place
    EXPECT_EQ(read_file_bytes(b), "old");
    EXPECT_EQ(t.staged(), (std::vector<std::string>{a, b}));
  }  // no commit: nothing written, no temporary left
  EXPECT_FALSE(std::filesystem::exists(a));
  EXPECT_EQ(read_file_bytes(b), "old");
  EXPECT_EQ(entries_in(dir.path()), 1u);
  {
    OutputTransaction t;
    write_file_atomically(a, [](std::ostream& os) { os << "first"; });
    write_file_atomically(a, [](std::ostream& os) { os << "second"; });  // the later version wins
    write_file_atomically(b, [](std::ostream& os) { os << "report"; });
    t.discard(b);
    t.commit();
  }
  EXPECT_EQ(read_file_bytes(a), "second");
  EXPECT_EQ(read_file_bytes(b), "old");
  EXPECT_EQ(entries_in(dir.path()), 2u);
  write_file_atomically(a, [](std::ostream& os) { os << "direct"; });  // no transaction: at once
  EXPECT_EQ(read_file_bytes(a), "direct");
}

// A child process writes through write_file_atomically and is interrupted in the middle of the
// write: the temporary file must be gone and the target never created.
TEST(Files, InterruptDuringAWriteRemovesTheTemporaryFile) {
  TempDir dir;
  const std::string path = dir.file("big.bvh");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const InterruptCleanup cleanup;
    write_file_atomically(path, [](std::ostream& os) {
      os << std::string(1 << 20, 'x');
      os.flush();
      ::raise(SIGINT);  // as a Ctrl-C would arrive, mid-write
      os << "never";
    });
    ::_exit(0);  // not reached: the signal ends the process
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_EQ(entries_in(dir.path()), 0u);
}

TEST(Files, RegistryTracksTemporaryFiles) {
  TempDir dir;
  const std::string t = dir.file("x.tmp1");
  write_text(t, "partial");
  const int slot = register_temporary_file(t);
  ASSERT_GE(slot, 0);
  remove_registered_temporary_files();
  EXPECT_FALSE(std::filesystem::exists(t));
  write_text(t, "again");
  unregister_temporary_file(slot);
  remove_registered_temporary_files();  // no longer registered: left alone
  EXPECT_TRUE(std::filesystem::exists(t));
  EXPECT_EQ(register_temporary_file(std::string(5000, 'a')), -1);  // too long for the table
}

TEST(Files, OutputFileIsCheckedBeforeAnyWork) {
  TempDir dir;
  const std::vector<std::string> motion = {".bvh", ".npz"};
  EXPECT_NO_THROW(check_output_file({"-o", dir.file("out.BVH")}, motion));
  EXPECT_NO_THROW(check_output_file({"-o", ""}, motion));  // not given
  EXPECT_EQ(error_of([&] {
              check_output_file({"-o", dir.file("out.txt")}, motion);
            }),
            dir.file("out.txt") + ": -o must be a .bvh or .npz file (its extension chooses the format)");
  EXPECT_EQ(error_of([&] {
              check_output_file({"", dir.file("x.fbx")}, {".mp4", ".mkv", ".mov"});
            }),
            dir.file("x.fbx") + ": must be a .mp4, .mkv or .mov file (its extension chooses the format)");
  std::filesystem::create_directories(dir.file("taken.bvh"));
  EXPECT_EQ(error_of([&] {
              check_output_file({"-o", dir.file("taken.bvh")}, motion);
            }),
            dir.file("taken.bvh") + ": -o is a folder, not a file");
  ASSERT_EQ(::mkfifo(dir.file("pipe.bvh").c_str(), 0644), 0);
  EXPECT_EQ(error_of([&] {
              check_output_file({"-o", dir.file("pipe.bvh")}, motion);
            }),
            dir.file("pipe.bvh") + ": -o is a FIFO (named pipe), not a regular file");
  EXPECT_EQ(error_of([&] {
              check_output_file({"--report", dir.file("no/r.json")}, {".json"});
            }),
            dir.file("no/r.json") + ": --report: the folder " + dir.file("no") + " does not exist");
  EXPECT_NO_THROW(check_output_file({"-o", "relative.bvh"}, motion));  // the working folder
}

TEST(Files, OutputIntoAReadOnlyFolderNamesTheFolderAndWhy) {
  testing::SmallDisk disk(64, /*read_only=*/true);
  if (!disk.ok()) GTEST_SKIP() << disk.why();
  EXPECT_EQ(
      error_of([&] {
        check_output_file({"-o", disk.file("out.bvh")}, {".bvh"});
      }),
      disk.file("out.bvh") + ": -o: cannot write into the folder " + disk.path().string() + " (Read-only file system)");
  EXPECT_EQ(
      error_of([&] {
        check_output_folder({"-o", disk.file("a/b")});
      }),
      disk.file("a/b") + ": -o: cannot write into the folder " + disk.path().string() + " (Read-only file system)");
}

TEST(Files, OutputFolderMustNotBeAFile) {
  TempDir dir;
  write_text(dir.file("f"), "x");
  EXPECT_EQ(error_of([&] {
              check_output_folder({"-o", dir.file("f")});
            }),
            dir.file("f") + ": -o is a file, not a folder");
  EXPECT_EQ(error_of([&] {
              check_output_folder({"-o", dir.file("f/sub")});
            }),
            dir.file("f/sub") + ": -o: " + dir.file("f") + " is a file, not a folder");
  EXPECT_NO_THROW(check_output_folder({"-o", dir.file("new/deeper")}));
  EXPECT_FALSE(std::filesystem::exists(dir.file("new")));  // checked, not made
}

TEST(Files, AtomicWriteOnAFullDiskSaysSo) {
  testing::SmallDisk disk(16);
  if (!disk.ok()) GTEST_SKIP() << disk.why();
  const std::string path = disk.file("big.bvh");
  const std::string msg =
      error_of([&] { write_file_atomically(path, [](std::ostream& os) { os << std::string(1 << 20, 'x'); }); });
  EXPECT_EQ(msg, path + ": cannot write (No space left on device)");
  EXPECT_EQ(entries_in(disk.path()), 0u);
}

TEST(Files, StaleTemporariesOfDeadProcessesAreRemoved) {
  TempDir dir;
  const pid_t dead = ::fork();  // a process id that is surely gone once reaped
  if (dead == 0) ::_exit(0);
  ASSERT_GT(dead, 0);
  ::waitpid(dead, nullptr, 0);
  const std::string gone = std::to_string(dead), alive = std::to_string(::getppid());
  EXPECT_EQ(temporary_file_owner("out.mp4.tmp" + gone + "_3"), dead);
  EXPECT_EQ(temporary_file_owner("out.mp4"), 0);
  EXPECT_EQ(temporary_file_owner("out.tmp12.mp4"), 0);
  for (const std::string& name :
       std::vector<std::string>{"a.mp4.tmp" + gone + "_0", "b.MKV.tmp" + gone + "_7", "c.bvh.tmp" + gone + "_1",
                                "d.mp4.tmp" + alive + "_0", "e.mp4", "f.mp4.tmpx_1"})
    write_text(dir.file(name), "x");
  EXPECT_EQ(remove_stale_temporaries(dir.path().string(), {".mp4", ".mkv"}), 2);
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.mp4.tmp" + gone + "_0")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("b.MKV.tmp" + gone + "_7")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("c.bvh.tmp" + gone + "_1")));   // another kind of output
  EXPECT_TRUE(std::filesystem::exists(dir.file("d.mp4.tmp" + alive + "_0")));  // its owner runs
  EXPECT_TRUE(std::filesystem::exists(dir.file("e.mp4")));
  const std::string t = temporary_name_for(dir.file("v.mp4"));
  EXPECT_EQ(temporary_file_owner(std::filesystem::path(t).filename().string()), ::getpid());
}

TEST(Files, CreatedFoldersGoWhenTheCommandFails) {
  TempDir dir;
  {
    const CreatedFolders folders(dir.file("a/b/c"));
    EXPECT_TRUE(std::filesystem::is_directory(dir.file("a/b/c")));
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("a")));  // every folder it made, deepest first
  {
    CreatedFolders folders(dir.file("k/l"));
    folders.keep();
  }
  EXPECT_TRUE(std::filesystem::is_directory(dir.file("k/l")));
  {
    const CreatedFolders folders(dir.file("k/m"));  // k was there: only m is its own
    write_text(dir.file("k/m/file"), "x");          // not empty: kept
  }
  EXPECT_TRUE(std::filesystem::exists(dir.file("k/m/file")));
  write_text(dir.file("plain"), "x");
  EXPECT_EQ(error_of([&] {
              CreatedFolders f(dir.file("plain/sub"));
            }).rfind(dir.file("plain/sub") + ": cannot create the folder (", 0),
            0u);
}

// advise_huge_pages: on a kernel that gives transparent huge pages to memory that asks (enabled
// "madvise" or "always"), the whole 2 MiB pages of an advised region are huge once touched
// (/proc/self/smaps, AnonHugePages of its mapping); the bytes read back as written, and the parts
// outside whole 2 MiB pages, and regions too small to hold one, are left as they are.
TEST(Files, AdvisedMemoryIsBackedByHugePagesWhereTheKernelOffersThem) {
  std::ifstream setting("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(setting, modes);
  if (modes.find("[madvise]") == std::string::npos && modes.find("[always]") == std::string::npos)
    GTEST_SKIP() << "this kernel gives no transparent huge pages on request: '" << modes << "'";
  advise_huge_pages(nullptr, 0);  // nothing to advise
  constexpr std::size_t kMiB = std::size_t{1} << 20;
  const std::size_t size = 9 * kMiB;  // holds at least three whole 2 MiB pages wherever it starts
  void* region = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(region, MAP_FAILED);
  auto* bytes = static_cast<unsigned char*>(region) + 4096;  // not on a 2 MiB boundary
  const std::size_t n = size - 4096;
  advise_huge_pages(bytes, n);
  advise_huge_pages(bytes, kMiB);  // under 2 MiB: nothing
  for (std::size_t i = 0; i < n; ++i) bytes[i] = static_cast<unsigned char>(i % 251);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < n; ++i) wrong += bytes[i] != static_cast<unsigned char>(i % 251) ? 1 : 0;
  EXPECT_EQ(wrong, 0u);
  // The AnonHugePages lines in smaps of the mappings within the region (the advice splits it).
  std::ifstream smaps("/proc/self/smaps");
  const auto start = reinterpret_cast<std::uintptr_t>(region);
  std::string line;
  bool inside = false;
  int mappings = 0;
  long huge_kb = 0;
  while (std::getline(smaps, line)) {
    const std::size_t dash = line.find('-');
    if (!line.empty() && std::isxdigit(static_cast<unsigned char>(line[0])) && dash != std::string::npos &&
        dash < line.find(' ')) {
      const std::uintptr_t from = std::stoull(line.substr(0, dash), nullptr, 16);
      inside = from >= start && from < start + size;
      mappings += inside ? 1 : 0;
    } else if (inside && line.rfind("AnonHugePages:", 0) == 0) {
      huge_kb += std::stol(line.substr(14));
    }
  }
  ::munmap(region, size);
  ASSERT_GE(mappings, 1) << "the region's mapping is not in /proc/self/smaps";
  EXPECT_GE(huge_kb, 3 * 2048) << "no huge pages: the kernel may have had no free 2 MiB page";
  EXPECT_LE(huge_kb, 4 * 2048);
}

}  // namespace
}  // namespace gmg
