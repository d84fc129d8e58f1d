// Eight doubles (or floats) as one vector, for the resampler's and the spectrogram's loops.
//
// GCC and Clang vector extensions: lane-wise IEEE arithmetic, so each lane rounds exactly as the
// scalar code would (the build turns contraction off), and the vectorised loops give the scalar
// formulas' results bit for bit. Internal to audio/.
#pragma once

#include <cstring>

namespace gmg::audio::lanes {

constexpr int kWidth = 8;
using Lanes = double __attribute__((vector_size(64)));
using LanesF = float __attribute__((vector_size(32)));
using LaneBits = long long __attribute__((vector_size(64)));

// mask ? a : b, lane by lane (mask lanes all ones or all zeros, as comparisons give).
inline Lanes select(const LaneBits& mask, const Lanes& a, const Lanes& b) {
  LaneBits ab, bb;
  std::memcpy(&ab, &a, sizeof ab);
  std::memcpy(&bb, &b, sizeof bb);
  const LaneBits r = (ab & mask) | (bb & ~mask);
  Lanes out;
  std::memcpy(&out, &r, sizeof out);
  return out;
}

// m[j][l] becomes m[l][j]: an 8 x 8 block transposed in registers (three rounds of two-vector
// shuffles, pairing rows 1, 2 and then 4 apart).
template <typename V>
inline void transpose8(V (&m)[kWidth]) {
  V b[kWidth], c[kWidth];
  for (int i = 0; i < kWidth; i += 2) {
    b[i] = __builtin_shufflevector(m[i], m[i + 1], 0, 8, 2, 10, 4, 12, 6, 14);
    b[i + 1] = __builtin_shufflevector(m[i], m[i + 1], 1, 9, 3, 11, 5, 13, 7, 15);
  }
  for (int i : {0, 1, 4, 5}) {
    c[i] = __builtin_shufflevector(b[i], b[i + 2], 0, 1, 8, 9, 4, 5, 12, 13);
    c[i + 2] = __builtin_shufflevector(b[i], b[i + 2], 2, 3, 10, 11, 6, 7, 14, 15);
  }
  for (int i = 0; i < 4; ++i) {
    m[i] = __builtin_shufflevector(c[i], c[i + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    m[i + 4] = __builtin_shufflevector(c[i], c[i + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
}

}  // namespace gmg::audio::lanes
