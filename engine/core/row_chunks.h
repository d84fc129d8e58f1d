// Rows of a fixed width, one per frame, appended in bulk and read at random across gigabytes (the
// candidate search's float positions of hours of reference). Kept in chunks of 2^16 rows, each an
// anonymous mapping advised to use huge pages: growing never moves the rows already there (a
// vector's doubling would copy gigabytes and hold both copies), and a random read costs one TLB
// entry per 2 MB instead of per 4 KB page.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace gmg {

class RowChunks {
 public:
  static constexpr int kShift = 16;  // 2^16 rows a chunk

  // `width` floats a row.
  explicit RowChunks(std::size_t width = 0) : width_(width) {}
  ~RowChunks();
  RowChunks(RowChunks&& other) noexcept;
  RowChunks& operator=(RowChunks&& other) noexcept;
  RowChunks(const RowChunks&) = delete;
  RowChunks& operator=(const RowChunks&) = delete;

  std::size_t rows() const { return rows_; }
  std::size_t width() const { return width_; }
  // Makes room for `rows` rows in all (new rows are zero). Throws std::bad_alloc when the memory
  // cannot be mapped.
  void resize(std::size_t rows);
  float* row(std::size_t i) { return chunks_[i >> kShift] + (i & kMask) * width_; }
  const float* row(std::size_t i) const { return chunks_[i >> kShift] + (i & kMask) * width_; }

 private:
  static constexpr std::size_t kMask = (std::size_t{1} << kShift) - 1;
  std::size_t chunk_bytes() const { return (std::size_t{1} << kShift) * width_ * sizeof(float); }
  void free_all() noexcept;

  std::size_t width_ = 0;
  std::size_t rows_ = 0;
  std::vector<float*> chunks_;
};

}  // namespace gmg
