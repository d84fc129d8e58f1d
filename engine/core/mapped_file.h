// A read-only mapping of a whole file that survives the file shrinking under it (a SIGBUS handler
// puts zero pages in place and the mapping reports the change), and the advice given to the kernel
// about the pages of mappings and large arrays.
#pragma once

#include <cstddef>
#include <string>

namespace gmg {

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
// arrays are validated copies, see graph/graph_sections.cpp) and call check_unchanged() before its
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

}  // namespace gmg
