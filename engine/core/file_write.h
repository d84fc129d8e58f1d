// Writing output files: each appears complete or not at all (a temporary file renamed into place),
// the files of one command all or none (OutputTransaction), and no temporary file outlives its
// process, even one killed (remove_stale_temporaries).
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace gmg {

// Renames a finished temporary file `temp` to `path` (on the same file system, so the file
// appears whole or not at all). When the rename fails, temp is removed and gmg::Error naming
// path is thrown. For writers whose temporary file is made by another program (the video of
// `gmg render`); the others use write_file_atomically.
void rename_into_place(const std::string& temp, const std::string& path);

// Calls write(stream) on a temporary file beside `path` ("<path>.tmp<pid>_<n>"), then renames it
// to `path`. When write throws or the stream fails, the temporary file is removed, `path` is
// left untouched and gmg::Error (naming `path`) is thrown. So an interrupted or failed job leaves
// no partial file. While an OutputTransaction is open on the calling thread, the rename waits
// for its commit().
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

// Writes to a stream in whole blocks of `block` bytes, each at a multiple of `block` from where
// writing began (flush() writes the shorter rest). Linux (6.18 with ext4 here) gives the page cache
// of a write folios as large as the write's length and alignment allow, and a file later read
// through a mapping is read as fast as its folios are large (a graph file: graph/graph_archive.h,
// measured in docs/decisions.md, "Implementation choices"). Buffers at most one block; whole
// blocks at a block boundary go out without a copy.
class BlockWriter {
 public:
  BlockWriter(std::ostream& out, std::size_t block) : out_(out), block_(block) {}
  void write(const void* data, std::size_t size);
  void flush();

 private:
  std::ostream& out_;
  std::size_t block_;
  std::vector<char> buffer_;
};

// Creates the folder `dir` and the missing ones above it (gmg::Error naming dir and the reason
// when it cannot); destroyed without keep(), it removes the folders it created, deepest first,
// as long as they are empty, so a command that fails (a full disk) leaves no empty folder behind.
// Put it outside the command's OutputTransaction, whose temporary files must go first.
class CreatedFolders {
 public:
  explicit CreatedFolders(const std::string& dir);
  ~CreatedFolders();
  CreatedFolders(const CreatedFolders&) = delete;
  CreatedFolders& operator=(const CreatedFolders&) = delete;
  void keep() { created_.clear(); }

 private:
  void remove_created() noexcept;
  std::vector<std::string> created_;  // deepest first
};

// The files one command writes, all or nothing. While it is open (on this thread),
// write_file_atomically leaves each finished temporary file in place; commit() renames them all
// into place; destroyed without a commit (an exception, an error in a later step) it removes
// them, so a failed report also takes away the BVH it belonged to. Transactions nest (the inner
// one is the current); a path written twice keeps the second version.
class OutputTransaction {
 public:
  OutputTransaction();
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // Renames every staged file into place, in the order written. Throws gmg::Error naming the file
  // whose rename failed (the ones after it are removed).
  void commit();
  // Drops the staged version of `path` (nothing is written there).
  void discard(const std::string& path);
  // Paths staged so far, in order.
  std::vector<std::string> staged() const;

  // Internal: write_file_atomically hands a finished temporary file over.
  void stage(const std::string& temp, const std::string& path, int slot);

 private:
  struct Staged {
    std::string temp, path;
    int slot = -1;  // in the interrupt registry (register_temporary_file)
  };
  std::vector<Staged> staged_;
  OutputTransaction* previous_ = nullptr;
};

// The owner of a temporary file named as write_file_atomically names them, "<name>.tmp<pid>_<n>":
// its process id, or 0 for any other name.
long temporary_file_owner(const std::string& file_name);

// Removes the temporary files in `dir` whose owner process is gone (a killed run's: SIGKILL
// cannot be caught) and whose <name> ends in one of `extensions` (ASCII case-insensitive; the
// files of other programs and of live processes are kept). Returns how many it removed.
int remove_stale_temporaries(const std::string& dir, const std::vector<std::string>& extensions);

// A temporary name for `path` (write_file_atomically's form, unique in this process) that
// remove_stale_temporaries recognises, for temporary files another program writes (the video
// of `gmg render`).
std::string temporary_name_for(const std::string& path);

}  // namespace gmg
