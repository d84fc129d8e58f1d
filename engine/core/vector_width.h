// The width of the target's vector registers, for loops written with GCC/Clang vector extensions
// (audio/lanes.h, graph/tree_finder.cpp): 64 bytes with AVX-512, 32 with AVX, 16 otherwise
// (x86-64's baseline SSE2, or NEON). A vector wider than the registers is lowered through memory
// (GCC spills its parts to the stack at every operation), which made 64-byte vectors about five
// times slower on an AVX2 machine than 32-byte ones (docs/performance.md).
#pragma once

namespace gmg {

#if defined(__AVX512F__)
inline constexpr int kVectorBytes = 64;
#elif defined(__AVX__)
inline constexpr int kVectorBytes = 32;
#else
inline constexpr int kVectorBytes = 16;
#endif

}  // namespace gmg
