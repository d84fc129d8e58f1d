// File helpers shared by every reader and writer: inputs are regular files read whole, outputs
// appear complete or not at all, never on top of an input, and no temporary file outlives an
// interrupted process.
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace gmg {

// ---- Reading ------------------------------------------------------------------------------------

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

// A read-only mapping of a whole regular file (opened and refused as read_file_bytes does),
// unmapped when it goes: a reader takes its bytes from the page cache, without a copy of the
// file in memory (a graph of an hour of reference is hundreds of MB), and processes that map the
// same file share its pages. An empty file maps to data() == nullptr, size() == 0. Throws
// gmg::Error "path: what" like read_file_bytes.
//
// A file that shrinks under a mapping would kill the process with SIGBUS at the first read past
// its new end. While a MappedFile exists, a SIGBUS handler catches a fault inside it, puts zero
// pages over the lost part (so the read that faulted and every later one sees zeros, never a
// signal) and marks the mapping; changed() and check_unchanged() report it, as they do a file
// whose size or modification time is no longer the one it was mapped with (written in place).
// Code that reads a mapping must stay memory-safe whatever bytes it reads (indices into other
// arrays are validated copies, see graph/graph_io.cpp) and call check_unchanged() before its
// results are used, so a graph that changes while in use ends in an error, not in a signal
// death or in output made from a mix of two files.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const char* data() const { return data_; }
  std::size_t size() const { return size_; }
  const std::string& path() const { return path_; }
  // True when a read faulted past the file's end or the file's size or modification time changed.
  bool changed() const;
  // Throws gmg::Error "path: changed while in use (...)" when changed().
  void check_unchanged() const;
  // Drops the pages of [offset, offset + size) from this process's memory (the page cache keeps
  // them; a later read maps them again): for a pass over the whole file that should not leave it
  // all resident.
  void release(std::size_t offset, std::size_t size) const;

 private:
  std::string path_;
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  int fd_ = -1;  // kept open to compare its size and time at check_unchanged
  int slot_ = -1;
  long long mtime_ns_ = 0;
};

// Drops this process's pages of [p, p + size) where they lie in a file a live MappedFile maps (the
// page cache keeps them; a later read maps them again); other memory is left alone. For arrays read
// in place from a mapping at scattered places: a kernel that maps a whole large folio of the page
// cache on a read (up to 2 MB) makes each scattered read resident with its neighbours, so a reader
// that is done with a stretch gives it back. The caller keeps the mapping alive (it reads it).
void release_mapped_pages(const void* p, std::size_t size);

// Asks the kernel to back the whole 2 MiB pages inside [p, p + size), memory not yet touched, with
// transparent huge pages (madvise MADV_HUGEPAGE; nothing where the kernel does not offer them, or
// for less than 2 MiB). For large arrays filled once and read at random: their first touch then
// faults and clears 2 MiB at a time instead of 4 KiB, which on a virtual machine is most of the
// cost of a large array's first touch, and a random read misses the TLB less.
void advise_huge_pages(const void* p, std::size_t size);

// ---- Writing ------------------------------------------------------------------------------------

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
// through a mapping is read as fast as its folios are large: a graph file written in 4 MB pieces
// at unaligned offsets was served at about half the speed of the same bytes written in aligned
// blocks (graph/graph_io.cpp). Buffers at most one block; whole blocks at a block boundary go out
// without a copy.
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

// ---- Outputs apart from inputs ------------------------------------------------------------------

// A file named on the command line, with the option that named it ("-o", "--audio").
struct NamedFile {
  std::string option;
  std::string path;
};

// Throws gmg::Error before any work when `output` cannot be written as the file it names, so a
// job never does its work for an output it cannot write (the option is left out of the message
// when empty; each check names the file first, then the cause):
//   "out.txt: -o must be a .bvh or .npz file (its extension chooses the format)"  (extensions:
//       ASCII case-insensitive, with the dot; empty = any)
//   "out: -o is a folder, not a file"   (also a FIFO, a device, a socket: "is a FIFO (named pipe)")
//   "a/b/out.bvh: -o: the folder a/b does not exist"
//   "ro/out.bvh: -o: cannot write into the folder ro (Read-only file system)"
void check_output_file(const NamedFile& output, const std::vector<std::string>& extensions);

// The same for an output folder (created when missing): "out: -o is a file, not a folder", and
// the folder, or the nearest one above it that exists, must be writable.
void check_output_folder(const NamedFile& output);

// " or ": ".bvh or .npz", ".mp4, .mkv or .mov".
std::string extension_list(const std::vector<std::string>& extensions);

// Throws gmg::Error before any work when an output is an input (the same file, also through a
// symbolic or hard link: compared with std::filesystem::equivalent) or two outputs are the same
// file: "in.bvh: -o would overwrite the input given as --motion; choose another output". Empty
// paths are ignored.
void check_outputs_apart(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs);

// ---- Interruption -------------------------------------------------------------------------------

// A process-wide table of temporary files that a SIGINT, SIGTERM or SIGHUP removes (see
// InterruptCleanup). register_temporary_file returns its slot, or -1 when the table (256 paths
// of up to 4095 bytes) is full and the file will not be removed on a signal.
int register_temporary_file(const std::string& path) noexcept;
void unregister_temporary_file(int slot) noexcept;
// Unlinks every registered file. Async-signal-safe (unlink(2) on a fixed array): for handlers.
void remove_registered_temporary_files() noexcept;
// Removes them and ends the process as `sig` would, its handler reset to the default.
// Async-signal-safe: for handlers.
void remove_temporaries_and_die(int sig) noexcept;

// While alive, SIGINT, SIGTERM and SIGHUP remove the registered temporary files and then end the
// process as the signal would (the previous handlers are restored on destruction; the exit
// contract is in engine/core/interrupt.h). With a program name, the handler first writes
// "<program>: interrupted by SIGINT; no output written" on standard error. cli_main holds one
// for every subcommand; `gmg batch` and `gmg render` install a graceful handler on top
// (InterruptFlag), which removes the temporary files before dying on a second signal.
class InterruptCleanup {
 public:
  explicit InterruptCleanup(const char* program = nullptr);
  ~InterruptCleanup();
  InterruptCleanup(const InterruptCleanup&) = delete;
  InterruptCleanup& operator=(const InterruptCleanup&) = delete;

 private:
  struct Saved;
  Saved* saved_;
};

}  // namespace gmg
