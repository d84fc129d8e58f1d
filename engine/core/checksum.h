// A 64-bit checksum of a byte stream, built like XXH64 (four independent multiply-rotate lanes
// over 32-byte blocks, so it runs at memory speed) but not equal to it: it is the graph file's
// own (graph/graph_io.cpp), and a change of even one step would make every saved graph unreadable.
//
//   lanes    v = {P1 + P2, P2, 0, -P1}; each 32-byte block's four little-endian 64-bit words w_i
//            update v_i = rotl(v_i + w_i * P2, 31) * P1
//   finish   h = rotl(v_0, 1) + rotl(v_1, 7) + rotl(v_2, 12) + rotl(v_3, 18); h ^= total_bytes * P5;
//            each byte b left over (fewer than 32): h = rotl(h ^ (b * P5), 11) * P1;
//            then h ^= h >> 33, h *= P2, h ^= h >> 29, h *= P3, h ^= h >> 32
//
// with XXH64's primes P1, P2, P3, P5, arithmetic modulo 2^64. Streaming: the value does not
// depend on how the bytes are split into add() calls.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gmg {

class Checksum {
 public:
  Checksum();
  // Appends `size` bytes to the stream.
  void add(const void* data, std::size_t size);
  // The checksum of every byte added so far (more may be added after).
  std::uint64_t value() const;

 private:
  void block(const unsigned char* p);

  std::uint64_t lane_[4];
  unsigned char buffer_[32] = {};  // the bytes of a block not yet complete
  std::size_t fill_ = 0;
  std::uint64_t total_ = 0;
};

// The checksum of one buffer.
std::uint64_t checksum_of(const void* data, std::size_t size);

}  // namespace gmg
