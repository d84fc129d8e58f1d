#include "engine/core/checksum.h"

#include <algorithm>
#include <cstring>

namespace gmg {
namespace {

constexpr std::uint64_t kP1 = 11400714785074694791ULL, kP2 = 14029467366897019727ULL, kP3 = 1609587929392839161ULL,
                        kP5 = 2870177450012600261ULL;

std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

}  // namespace

Checksum::Checksum() : lane_{kP1 + kP2, kP2, 0, 0 - kP1} {}

void Checksum::add(const void* data, std::size_t size) {
  // An empty vector's data() may be null, and memcpy from null is undefined even for 0 bytes.
  if (size == 0) return;
  const auto* p = static_cast<const unsigned char*>(data);
  total_ += size;
  if (fill_ > 0) {
    const std::size_t take = std::min(size, sizeof buffer_ - fill_);
    std::memcpy(buffer_ + fill_, p, take);
    fill_ += take;
    p += take;
    size -= take;
    if (fill_ < sizeof buffer_) return;
    block(buffer_);
    fill_ = 0;
  }
  for (; size >= sizeof buffer_; p += sizeof buffer_, size -= sizeof buffer_) block(p);
  if (size > 0) std::memcpy(buffer_, p, size);
  fill_ = size;
}

std::uint64_t Checksum::value() const {
  std::uint64_t h = rotl(lane_[0], 1) + rotl(lane_[1], 7) + rotl(lane_[2], 12) + rotl(lane_[3], 18);
  h ^= total_ * kP5;
  for (std::size_t i = 0; i < fill_; ++i) h = rotl(h ^ (buffer_[i] * kP5), 11) * kP1;
  h ^= h >> 33;
  h *= kP2;
  h ^= h >> 29;
  h *= kP3;
  h ^= h >> 32;
  return h;
}

void Checksum::block(const unsigned char* p) {
  for (int i = 0; i < 4; ++i) {
    std::uint64_t w = 0;
    std::memcpy(&w, p + static_cast<std::ptrdiff_t>(8) * i, 8);
    lane_[i] = rotl(lane_[i] + w * kP2, 31) * kP1;
  }
}

std::uint64_t checksum_of(const void* data, std::size_t size) {
  Checksum c;
  c.add(data, size);
  return c.value();
}

}  // namespace gmg
