// Sixteen floats as register-wide vectors (engine/core/vector_width.h: one with AVX-512, two with
// AVX, four with SSE2), for the candidate search's distances and bounds. Every lane is computed
// on its own with lane-wise IEEE arithmetic (the build turns contraction off), and sums across the
// sixteen lanes are taken in one fixed pairwise order, so a value comes out bit for bit the same
// whatever the vector width: the native and portable builds find the same candidates, also where
// the budgeted search stops early. Internal to graph/.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstring>

#if defined(__SSE__)
#include <immintrin.h>
#endif

#include "engine/core/vector_width.h"

namespace gmg::neighbours {

constexpr int kLanes = kVectorBytes / static_cast<int>(sizeof(float));
using Floats = float __attribute__((vector_size(kVectorBytes)));

// Lane-wise square root (correctly rounded, as std::sqrt).
inline Floats square_root(Floats x) {
#if defined(__AVX512F__)
  return _mm512_sqrt_ps(x);
#elif defined(__AVX__)
  return _mm256_sqrt_ps(x);
#elif defined(__SSE__)
  return _mm_sqrt_ps(x);
#else
  for (int i = 0; i < kLanes; ++i) x[i] = std::sqrt(x[i]);
  return x;
#endif
}

// Bit i set where lane i of x is <= limit.
inline unsigned lanes_at_most(Floats x, float limit) {
#if defined(__AVX512F__)
  return _mm512_cmp_ps_mask(x, _mm512_set1_ps(limit), _CMP_LE_OQ);
#elif defined(__AVX__)
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(x, _mm256_set1_ps(limit), _CMP_LE_OQ)));
#elif defined(__SSE__)
  return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(x, _mm_set1_ps(limit))));
#else
  unsigned bits = 0;
  for (int i = 0; i < kLanes; ++i) bits |= (x[i] <= limit ? 1u : 0u) << i;
  return bits;
#endif
}

// Bit i set where lane i of x is <= lane i of limit.
inline unsigned lanes_at_most(Floats x, Floats limit) {
#if defined(__AVX512F__)
  return _mm512_cmp_ps_mask(x, limit, _CMP_LE_OQ);
#elif defined(__AVX__)
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(x, limit, _CMP_LE_OQ)));
#elif defined(__SSE__)
  return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(x, limit)));
#else
  unsigned bits = 0;
  for (int i = 0; i < kLanes; ++i) bits |= (x[i] <= limit[i] ? 1u : 0u) << i;
  return bits;
#endif
}

inline Floats load(const float* p) {
  Floats v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

struct Sixteen {
  static constexpr int kParts = 16 / kLanes;
  Floats part[kParts];

  static Sixteen zero() {
    Sixteen s;
    for (Floats& p : s.part) p = Floats{};
    return s;
  }
  static Sixteen at(const float* p) {
    Sixteen s;
    for (int i = 0; i < kParts; ++i) s.part[i] = load(p + static_cast<std::ptrdiff_t>(i) * kLanes);
    return s;
  }
  void store(float* p) const { std::memcpy(p, part, sizeof part); }
  // x - y, lane by lane.
  static Sixteen difference(const Sixteen& x, const Sixteen& y) {
    Sixteen s;
    for (int i = 0; i < kParts; ++i) s.part[i] = x.part[i] - y.part[i];
    return s;
  }
  // this += (x - y)^2, lane by lane.
  void add_square_of_difference(const Sixteen& x, const Sixteen& y) {
    for (int i = 0; i < kParts; ++i) {
      const Floats g = x.part[i] - y.part[i];
      part[i] += g * g;
    }
  }
};

// v[0] + ... + v[7], as ((v0 + v1) + (v2 + v3)) + ((v4 + v5) + (v6 + v7)).
inline float sum8(const float* v) { return ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7])); }

// The sixteen lanes in the same pairwise order: sum8 of each half, then their sum.
inline float sum16(const float* v) { return sum8(v) + sum8(v + 8); }

}  // namespace gmg::neighbours
