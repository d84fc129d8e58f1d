#include "engine/core/row_chunks.h"

#include <sys/mman.h>

#include <new>
#include <utility>

namespace gmg {

RowChunks::~RowChunks() { free_all(); }

RowChunks::RowChunks(RowChunks&& other) noexcept
    : width_(other.width_), rows_(other.rows_), chunks_(std::move(other.chunks_)) {
  other.chunks_.clear();
  other.rows_ = 0;
}

RowChunks& RowChunks::operator=(RowChunks&& other) noexcept {
  if (this != &other) {
    free_all();
    width_ = other.width_;
    rows_ = other.rows_;
    chunks_ = std::move(other.chunks_);
    other.chunks_.clear();
    other.rows_ = 0;
  }
  return *this;
}

void RowChunks::free_all() noexcept {
  for (float* c : chunks_) ::munmap(c, chunk_bytes());
  chunks_.clear();
}

void RowChunks::resize(std::size_t rows) {
  while (chunks_.size() << kShift < rows) {
    void* p = ::mmap(nullptr, chunk_bytes(), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    // Advice only (a kernel without transparent huge pages, or set to never, ignores it); what it
    // saves a long build: docs/decisions.md, "Implementation choices".
    ::madvise(p, chunk_bytes(), MADV_HUGEPAGE);
#endif
    chunks_.push_back(static_cast<float*>(p));
  }
  rows_ = rows;
}

}  // namespace gmg
