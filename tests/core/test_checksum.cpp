// engine/core/checksum: the graph file's checksum, exact values.
//
// The expected values were computed by an independent implementation of the algorithm described
// in checksum.h (Python, arbitrary-precision integers reduced modulo 2^64), which also reproduces
// the checksum stored in graph files that gmg writes.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/checksum.h"

namespace gmg {
namespace {

std::vector<unsigned char> bytes_0_to(int n) {
  std::vector<unsigned char> b(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) b[static_cast<std::size_t>(i)] = static_cast<unsigned char>(i);
  return b;
}

TEST(Checksum, KnownValues) {
  EXPECT_EQ(checksum_of(nullptr, 0), 0x9090306C6E91ED59ULL);
  EXPECT_EQ(checksum_of("abc", 3), 0xB80C09AD8D9C38D5ULL);
  // Under one block: only the tail loop.
  EXPECT_EQ(checksum_of("0123456789:;<=>?@ABCDEFGHIJKLMN", 31), 0x3104DBE8E65783B2ULL);
  const std::string fox = "The quick brown fox jumps over the lazy dog";  // one block and a tail
  EXPECT_EQ(checksum_of(fox.data(), fox.size()), 0xCA894672563679AEULL);
  const std::vector<unsigned char> b = bytes_0_to(100);  // three blocks and a tail of 4
  EXPECT_EQ(checksum_of(b.data(), b.size()), 0xED7D8CF828FBA210ULL);
}

TEST(Checksum, DoesNotDependOnHowTheBytesAreSplit) {
  const std::vector<unsigned char> b = bytes_0_to(100);
  for (std::size_t first : {0, 1, 5, 31, 32, 33, 64, 99, 100}) {
    for (std::size_t second : {0, 1, 7, 32}) {
      if (first + second > b.size()) continue;
      Checksum c;
      c.add(b.data(), first);
      c.add(b.data() + first, second);
      c.add(b.data() + first + second, b.size() - first - second);
      EXPECT_EQ(c.value(), 0xED7D8CF828FBA210ULL) << first << " + " << second;
    }
  }
}

TEST(Checksum, NoBytesFromANullPointerMidStreamChangeNothing) {
  // An empty vector's data() is null; the graph writer adds such vectors between others.
  // Under UndefinedBehaviorSanitizer this also checks that nothing is copied from null.
  Checksum c;
  c.add("ab", 2);
  c.add(nullptr, 0);
  c.add("c", 1);
  EXPECT_EQ(c.value(), 0xB80C09AD8D9C38D5ULL);
}

TEST(Checksum, ValueCanBeTakenMidStream) {
  Checksum c;
  c.add("ab", 2);
  (void)c.value();
  c.add("c", 1);
  EXPECT_EQ(c.value(), 0xB80C09AD8D9C38D5ULL);
}

}  // namespace
}  // namespace gmg
