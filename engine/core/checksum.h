// The graph file's 64-bit checksum: XXH3-64 with its default secret and seed 0, from the xxHash
// library (libxxhash-dev, used header-only so the build's vector width applies). XXH3's value
// does not depend on the vector code that computes it or on how the bytes are split into add()
// calls, and it runs at several times the speed of a byte-serial hash, so a load's checksum pass is
// bound by memory (docs/decisions.md, "Implementation choices").
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

namespace gmg {

class Checksum {
 public:
  Checksum();
  ~Checksum();
  Checksum(const Checksum&) = delete;
  Checksum& operator=(const Checksum&) = delete;
  // Appends `size` bytes to the stream (data may be null when size is 0).
  void add(const void* data, std::size_t size);
  // The checksum of every byte added so far (more may be added after).
  std::uint64_t value() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The checksum of one buffer.
std::uint64_t checksum_of(const void* data, std::size_t size);

}  // namespace gmg
