// Doubles (or floats) as one vector as wide as the target's registers, for the resampler's and the
// spectrogram's loops.
//
// GCC and Clang vector extensions: lane-wise IEEE arithmetic, so each lane rounds exactly as the
// scalar code would (the build turns contraction off), and the vectorised loops give the scalar
// formulas' results bit for bit. Internal to audio/.
//
// The width is the target's (engine/core/vector_width.h): 8 doubles with AVX-512, 4 with AVX, 2
// otherwise. The loops are written in terms of kWidth, and each lane is an output of its own, so
// how many outputs share one vector changes no output's bits.
#pragma once

#include <cstddef>
#include <cstring>
#include <utility>

#include "engine/core/vector_width.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace gmg::audio::lanes {

constexpr int kBytes = kVectorBytes;
constexpr int kWidth = kBytes / static_cast<int>(sizeof(double));
using Lanes = double __attribute__((vector_size(kBytes)));
using LaneBits = long long __attribute__((vector_size(kBytes)));
// A Lanes converted to float (kWidth floats, half a register).
using LanesF = float __attribute__((vector_size(kBytes / 2)));

// A whole register of floats (2 kWidth), e.g. kWidth complex numbers stored as re, im pairs.
using Floats = float __attribute__((vector_size(kBytes)));

// The kWidth doubles at p (any alignment).
inline Lanes load(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// The kWidth floats at p (any alignment) in double (exact). With AVX and AVX-512 through the
// conversion's intrinsic: GCC 12 lowers __builtin_convertvector from float to double there in
// halves, through the stack.
inline Lanes load_widened(const float* p) {
#if defined(__AVX512F__)
  return _mm512_cvtps_pd(_mm256_loadu_ps(p));
#elif defined(__AVX__)
  return _mm256_cvtps_pd(_mm_loadu_ps(p));
#else
  LanesF v;
  std::memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, Lanes);
#endif
}

// v in double (exact), through the conversion's intrinsic with AVX and AVX-512 (see load_widened).
inline Lanes widen(const LanesF& v) {
#if defined(__AVX512F__)
  return _mm512_cvtps_pd(v);
#elif defined(__AVX__)
  return _mm256_cvtps_pd(v);
#else
  return __builtin_convertvector(v, Lanes);
#endif
}

// The kWidth doubles at p (any alignment) from v.
inline void store(double* p, const Lanes& v) { std::memcpy(p, &v, sizeof v); }

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

namespace detail {

// Rows a and b, S apart in the block, exchange their S-element sub-blocks: element k of a (k with
// bit S set) trades places with element k - S of b.
template <std::size_t S, typename V, std::size_t... K>
inline void exchange(V& a, V& b, std::index_sequence<K...>) {
  constexpr std::size_t n = sizeof...(K);
  const V lo = __builtin_shufflevector(a, b, ((K & S) != 0 ? n + K - S : K)...);
  const V hi = __builtin_shufflevector(a, b, ((K & S) != 0 ? n + K : K + S)...);
  a = lo;
  b = hi;
}

template <std::size_t S, std::size_t I, typename V, std::size_t N>
inline void exchange_rows(V (&m)[N]) {
  if constexpr ((I & S) == 0) exchange<S>(m[I], m[I + S], std::make_index_sequence<N>());
}

// Every statement spelled out (fold expressions rather than loops), so that the block is a set of
// registers from the start: a loop the compiler left rolled would keep it in memory, stored in
// pieces and loaded whole (a store-forwarding stall on every row).
template <typename V, std::size_t N, std::size_t... I>
inline void transpose_rows(V (&m)[N], std::index_sequence<I...>) {
  static_assert(N >= 2 && N <= 16, "blocks of 2 x 2 to 16 x 16");
  (exchange_rows<1, I>(m), ...);  // rows 1, 2, 4, 8 apart: log2 N rounds
  if constexpr (N >= 4) (exchange_rows<2, I>(m), ...);
  if constexpr (N >= 8) (exchange_rows<4, I>(m), ...);
  if constexpr (N >= 16) (exchange_rows<8, I>(m), ...);
}

template <typename V, typename Load, typename Store, std::size_t... I>
inline void transpose(Load& load, Store& store, std::index_sequence<I...> rows) {
  V m[sizeof...(I)] = {load(static_cast<int>(I))...};
  transpose_rows(m, rows);
  (store(static_cast<int>(I), m[I]), ...);
}

template <std::size_t... K>
inline void deinterleave(const Floats& v, LanesF& even, LanesF& odd, std::index_sequence<K...>) {
  even = __builtin_shufflevector(v, v, (2 * K)...);
  odd = __builtin_shufflevector(v, v, (2 * K + 1)...);
}

template <std::size_t... K>
inline void deinterleave_reversed(const Floats& v, LanesF& even, LanesF& odd, std::index_sequence<K...>) {
  constexpr std::size_t n = sizeof...(K);
  even = __builtin_shufflevector(v, v, (2 * (n - 1 - K))...);
  odd = __builtin_shufflevector(v, v, (2 * (n - 1 - K) + 1)...);
}

template <std::size_t... K>
inline Lanes reversed(const Lanes& v, std::index_sequence<K...>) {
  return __builtin_shufflevector(v, v, (sizeof...(K) - 1 - K)...);
}

}  // namespace detail

// The kWidth pairs of v (re, im, re, im, ...) as their real parts (even) and imaginary parts (odd).
inline void deinterleave(const Floats& v, LanesF& even, LanesF& odd) {
  detail::deinterleave(v, even, odd, std::make_index_sequence<kWidth>());
}

// The same in reverse order: lane l of even and odd from pair kWidth - 1 - l of v.
inline void deinterleave_reversed(const Floats& v, LanesF& even, LanesF& odd) {
  detail::deinterleave_reversed(v, even, odd, std::make_index_sequence<kWidth>());
}

// v's lanes in reverse order.
inline Lanes reversed(const Lanes& v) { return detail::reversed(v, std::make_index_sequence<kWidth>()); }

// An N x N block, N the elements of V (2, 4, 8 or 16), transposed in registers (log2 N rounds of
// two-vector shuffles, pairing rows 1, 2, 4, ... apart): load(j) gives row j of the block, and
// store(l, v) is given row l of the transpose (v[j] = load(j)[l]), j, l = 0 .. N - 1.
template <typename V, typename Load, typename Store>
inline void transpose(Load&& load, Store&& store) {
  constexpr std::size_t n = sizeof(V) / sizeof(load(0)[0]);
  static_assert(n * sizeof(load(0)[0]) == sizeof(V) && (n & (n - 1)) == 0, "a square block of a power of two");
  detail::transpose<V>(load, store, std::make_index_sequence<n>());
}

// The same from memory to memory: row j of the block at src + j * src_stride, row l of the
// transpose to dst + l * dst_stride.
template <typename V, typename T>
inline void transpose_block(const T* src, std::ptrdiff_t src_stride, T* dst, std::ptrdiff_t dst_stride) {
  transpose<V>(
      [&](int j) {
        V v;
        std::memcpy(&v, src + j * src_stride, sizeof v);
        return v;
      },
      [&](int l, const V& v) { std::memcpy(dst + l * dst_stride, &v, sizeof v); });
}

}  // namespace gmg::audio::lanes
