#include "engine/core/checksum.h"

// Inlined, so XXH3 is compiled for this build's target (its accumulate loop then uses the widest
// vectors the build allows) and nothing is linked.
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace gmg {

// XXH3's streaming state (576 bytes, 64-byte aligned), held by pointer so that the header does
// not carry xxhash.h.
struct Checksum::State {
  XXH3_state_t xxh;
};

Checksum::Checksum() : state_(new State) { XXH3_64bits_reset(&state_->xxh); }

Checksum::~Checksum() = default;

void Checksum::add(const void* data, std::size_t size) {
  // An empty vector's data() may be null; XXH3 accepts (nullptr, 0), but a call is not needed.
  if (size == 0) return;
  XXH3_64bits_update(&state_->xxh, data, size);
}

std::uint64_t Checksum::value() const { return XXH3_64bits_digest(&state_->xxh); }

std::uint64_t checksum_of(const void* data, std::size_t size) { return XXH3_64bits(data, size); }

}  // namespace gmg
