// The graph file's archive (graph_io.h; the layout is in docs/graph_format.md): its constants, the
// writer that puts a payload's bytes out in whole blocks while counting and summing them, and the
// reader that takes them back front to back, summing every byte it checks. The sections of the
// file (graph/graph_sections.h, graph/graph_motion_sections.h) are written and read with these.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/core/checksum.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/mapped_file.h"
#include "engine/motion/motion.h"

namespace gmg {

constexpr char kGraphMagic[8] = {'G', 'M', 'G', 'R', 'A', 'P', 'H', '\0'};
constexpr std::size_t kGraphAlign = 4096;  // the sections read in place start at multiples of it
// Magic, version, payload size, and how many of the payload's bytes the checksum covers.
constexpr std::size_t kGraphHeaderBytes = sizeof kGraphMagic + sizeof(std::uint32_t) + 2 * sizeof(std::uint64_t);

// A graph file is written in whole blocks of this many bytes from its start (BlockWriter,
// engine/core/file_write.h): a file served from its mapping is read as fast as the page cache's
// folios are large, and written in smaller pieces it was served much slower
// (docs/decisions.md, "Implementation choices").
constexpr std::size_t kGraphWriteBlock = std::size_t{16} << 20;

// Writes the payload to a stream, or only counts and checksums it (out == nullptr), so the
// header's size is known before the first byte is written. What it writes goes out in whole
// kGraphWriteBlock blocks (the file's header first: raw), the rest at flush().
class ArchiveWriter {
 public:
  explicit ArchiveWriter(std::ostream* out) {
    if (out) out_.emplace(*out, kGraphWriteBlock);
  }
  void bytes(const void* data, std::size_t size) {
    if (out_) out_->write(data, size);
    if (summing_) sum_.add(data, size);
    size_ += size;
  }
  // Bytes of the file outside the payload (its header and checksum): written, neither counted nor
  // summed.
  void raw(const void* data, std::size_t size) {
    if (out_) out_->write(data, size);
  }
  // Writes what is left.
  void flush() {
    if (out_) out_->flush();
  }
  // The checksum covers the bytes written so far and none after (the motion, checked by blocks).
  void stop_summing() {
    summing_ = false;
    summed_ = size_;
  }
  std::uint64_t summed() const { return summed_; }
  // Whether the bytes are written (not only counted).
  bool writes() const { return out_.has_value(); }
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable<T>::value, "pod only");
    bytes(&v, sizeof(T));
  }
  void str(const std::string& s) {
    pod<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable<T>::value, "pod only");
    pod<std::uint64_t>(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  // A list written from a function of its index, in chunks (for arrays whose memory layout is not
  // the file's).
  template <typename T, typename F>
  void vec_of(std::size_t n, const F& at) {
    pod<std::uint64_t>(n);
    std::vector<T> chunk;
    for (std::size_t i = 0; i < n; i += kChunk) {
      chunk.clear();
      for (std::size_t j = i; j < std::min(n, i + kChunk); ++j) chunk.push_back(at(j));
      bytes(chunk.data(), chunk.size() * sizeof(T));
    }
  }
  // A list whose items start on a kGraphAlign boundary of the file (after its count and zero padding).
  template <typename T>
  void aligned(const T* data, std::size_t n) {
    static_assert(std::is_trivially_copyable<T>::value, "pod only");
    pod<std::uint64_t>(n);
    static const char zeros[kGraphAlign] = {};
    bytes(zeros, (kGraphAlign - (kGraphHeaderBytes + size_) % kGraphAlign) % kGraphAlign);
    bytes(data, n * sizeof(T));
  }
  // The same for samples, a few MB at a time, giving each piece's pages back after it when they
  // are read from a file's mapping (the spilled motion of a long build: engine/core/spill.h).
  template <typename T>
  void aligned(const Samples<T>& values) {
    pod<std::uint64_t>(values.size());
    static const char zeros[kGraphAlign] = {};
    bytes(zeros, (kGraphAlign - (kGraphHeaderBytes + size_) % kGraphAlign) % kGraphAlign);
    constexpr std::size_t kPiece = (std::size_t{4} << 20) / sizeof(T);
    for (std::size_t i = 0; i < values.size(); i += kPiece) {
      const std::size_t m = std::min(kPiece, values.size() - i);
      bytes(values.data() + i, m * sizeof(T));
      values.release_pages(i, m);
    }
  }
  std::uint64_t size() const { return size_; }
  std::uint64_t checksum() const { return sum_.value(); }

 private:
  static constexpr std::size_t kChunk = 1 << 16;
  std::optional<BlockWriter> out_;
  Checksum sum_;
  std::uint64_t size_ = 0;
  bool summing_ = true;
  std::uint64_t summed_ = 0;
};

// Where the payload's bytes are: a mapped file (whose pages a pass gives back as it goes) or a
// buffer; `owner` keeps them alive for the arrays read in place.
struct ArchiveSource {
  const char* data = nullptr;  // the whole file
  std::size_t size = 0;
  const MappedFile* file = nullptr;
  std::shared_ptr<const void> owner;
  void release(std::size_t offset, std::size_t n) const {
    if (file) file->release(offset, n);
  }
};

// Runs visit(chunk, count) over n items of T at p in chunks of a few MB, giving each chunk's pages
// back after it, so a pass over a large array does not leave it resident.
template <typename T, typename F>
void in_chunks(const ArchiveSource& src, const T* p, std::size_t n, const F& visit) {
  constexpr std::size_t kChunk = (std::size_t{4} << 20) / sizeof(T);
  for (std::size_t i = 0; i < n; i += kChunk) {
    const std::size_t m = std::min(kChunk, n - i);
    visit(p + i, i, m);
    src.release(static_cast<std::size_t>(reinterpret_cast<const char*>(p + i) - src.data), m * sizeof(T));
  }
}

// n value-initialised values for a large array the load fills: allocated, advised to take huge
// pages (engine/core/mapped_file.h advise_huge_pages), and only then touched: the nodes and edges a
// load copies are its private memory, whose first touch in 4 KiB pages costs a long reference's
// reenactment much of its time (docs/performance.md, "Length of the reference: reenactment").
template <typename T>
std::vector<T> huge_vector(std::size_t n) {
  std::vector<T> v;
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
  v.resize(n);
  return v;
}

// Reads the payload front to back, adding every byte it takes to the checksum as it goes, so one
// pass both checks and reads the file: the large arrays are validated chunk by chunk while they are
// summed, and each chunk's pages are given back after it.
class ArchiveReader {
 public:
  ArchiveReader(const char* data, std::size_t size, const std::string& path, const ArchiveSource& src,
                std::string note = "")
      : data_(data), size_(size), path_(path), src_(src), note_(std::move(note)) {}
  template <typename T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    consume(sizeof(T));
    return v;
  }
  std::string str() {
    const std::uint32_t n = pod<std::uint32_t>();
    need(n);
    std::string s(data_ + pos_, n);
    consume(n);
    return s;
  }
  // The count of a list of T, checked against the bytes left; the caller reads the items.
  template <typename T>
  std::size_t count() {
    const std::uint64_t n = pod<std::uint64_t>();
    if (n > (size_ - pos_) / sizeof(T)) fail("a list is longer than the file");
    return static_cast<std::size_t>(n);
  }
  template <typename T>
  std::vector<T> vec() {
    std::vector<T> v(count<T>());
    if (!v.empty()) std::memcpy(v.data(), data_ + pos_, v.size() * sizeof(T));
    consume(v.size() * sizeof(T));
    return v;
  }
  // n items of T converted one by one (for arrays whose memory layout is not the file's).
  template <typename T, typename F>
  void items(std::size_t n, const F& take) {
    need(n * sizeof(T));
    constexpr std::size_t kChunk = 8192;
    for (std::size_t i = 0; i < n; i += kChunk) {
      const std::size_t m = std::min(kChunk, n - i);
      for (std::size_t j = 0; j < m; ++j) {
        T v;
        std::memcpy(&v, data_ + pos_ + j * sizeof(T), sizeof(T));
        take(i + j, v);
      }
      consume(m * sizeof(T));
    }
  }
  // The start of a list written by ArchiveWriter::aligned: its count and zero padding. Its items are
  // next, at the pointer returned; read them with in_place.
  template <typename T>
  std::pair<const T*, std::size_t> aligned() {
    const std::uint64_t n = pod<std::uint64_t>();
    const std::size_t pad = (kGraphAlign - (kGraphHeaderBytes + pos_) % kGraphAlign) % kGraphAlign;
    need(pad);
    for (std::size_t i = 0; i < pad; ++i)
      if (data_[pos_ + i] != 0) fail("padding that is not zero");
    consume(pad);
    if (n > (size_ - pos_) / sizeof(T)) fail("a list is longer than the file");
    return {reinterpret_cast<const T*>(data_ + pos_), static_cast<std::size_t>(n)};
  }
  // The n items of T that follow (an aligned list's): visit(chunk, first, count) over chunks of a
  // few MB, each summed after its visit and (`release`) its pages given back, so a pass over a large
  // array does not leave it resident. The items stay readable in place (they live as long as the
  // bytes).
  template <typename T, typename F>
  void in_place(std::size_t n, const F& visit, bool release = true) {
    need(n * sizeof(T));
    const T* p = reinterpret_cast<const T*>(data_ + pos_);
    constexpr std::size_t kChunk = (std::size_t{4} << 20) / sizeof(T);
    for (std::size_t i = 0; i < n; i += kChunk) {
      const std::size_t m = std::min(kChunk, n - i);
      visit(p + i, i, m);
      const std::size_t offset = static_cast<std::size_t>(data_ + pos_ - src_.data);
      consume(m * sizeof(T));
      if (release) src_.release(offset, m * sizeof(T));
    }
  }
  bool done() const { return pos_ == size_; }
  // What keeps the bytes alive, for the arrays read in place.
  const std::shared_ptr<const void>& owner() const { return src_.owner; }
  // The checksum of every byte read so far (up to stop_summing).
  std::uint64_t checksum() const { return sum_.value(); }
  // The bytes from here on are not summed (the motion, checked by blocks); returns the bytes
  // summed.
  std::size_t stop_summing() {
    summing_ = false;
    return pos_;
  }
  // Passes over the n items of T that follow without reading them (the motion's values, checked
  // by blocks: read_motion).
  template <typename T>
  void skip(std::size_t n) {
    need(n * sizeof(T));
    consume(n * sizeof(T));
  }
  // Throws "PATH: byte N: damaged graph file: WHAT", then the note given to the reader (which
  // version the file was read as, when it is not the one this gmg writes).
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(
        error_at_byte(path_, static_cast<long long>(pos_ + kGraphHeaderBytes), "damaged graph file: " + what + note_));
  }

 private:
  void need(std::size_t n) {
    if (n > size_ - pos_) fail("unexpected end of data");
  }
  void consume(std::size_t n) {
    if (summing_) sum_.add(data_ + pos_, n);
    pos_ += n;
  }
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  const std::string& path_;
  const ArchiveSource& src_;
  std::string note_;  // appended to every failure (fail)
  Checksum sum_;
  bool summing_ = true;
};

// How many of p[0 .. n) are finite. x - x is 0 for a finite x and NaN for an infinite or NaN one,
// and a count without an early exit vectorises, where std::isfinite and a short-circuit ran at a
// value per cycle over a load's largest arrays (docs/decisions.md, "Implementation choices").
template <typename T>
std::size_t count_finite(const T* p, std::size_t n) {
  std::size_t good = 0;
  for (std::size_t i = 0; i < n; ++i) good += (p[i] - p[i] == T(0)) ? 1 : 0;
  return good;
}

}  // namespace gmg
