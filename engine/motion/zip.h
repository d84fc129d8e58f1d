// Zip archives held in memory, as .npz files are (libzip): reading members strictly and bounded
// (a member's declared size is checked against the archive's before anything is allocated), and
// writing an archive whose bytes depend only on its members.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gmg {

// A read-only view of a zip archive held in memory (libzip).
class ZipReader {
 public:
  // Opens the archive in `bytes` (which must outlive the reader). `name` labels errors.
  ZipReader(const std::string& bytes, const std::string& name);
  ZipReader(std::string&& bytes, const std::string& name) = delete;  // a temporary would not outlive it
  ~ZipReader();
  ZipReader(const ZipReader&) = delete;
  ZipReader& operator=(const ZipReader&) = delete;

  // Member names in archive order.
  const std::vector<std::string>& names() const { return names_; }
  bool has(const std::string& member) const;
  // The whole member, decompressed and CRC-checked. Its declared size is checked against the
  // archive's size (deflate cannot expand more than about 1032:1) and against 2 GiB first.
  std::string read(const std::string& member) const;

 private:
  struct Handle;
  std::unique_ptr<Handle> zip_;
  std::string name_;
  std::uint64_t archive_size_ = 0;
  std::vector<std::string> names_;
};

struct ZipMember {
  std::string name;
  std::string bytes;
  bool deflate = false;  // false: stored, as np.savez writes
};

// The bytes of a zip archive holding the members in order, every time stamp 1980-01-01 00:00
// (as numpy writes), so the same members always give the same bytes.
std::string zip_format(const std::vector<ZipMember>& members, const std::string& name);

}  // namespace gmg
