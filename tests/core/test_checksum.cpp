// engine/core/checksum: the graph file's checksum (XXH3-64, seed 0), exact values.
//
// The expected values were printed by the xxHash command-line tool (`xxhsum -H3`, xxHash 0.8.1)
// for the same bytes; the empty input's is the one the xxHash documentation gives.
#include <gtest/gtest.h>

#include <algorithm>
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

std::vector<unsigned char> bytes_mod_251(int n) {
  std::vector<unsigned char> b(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) b[static_cast<std::size_t>(i)] = static_cast<unsigned char>(i % 251);
  return b;
}

TEST(Checksum, KnownValues) {
  EXPECT_EQ(checksum_of(nullptr, 0), 0x2D06800538D394C2ULL);
  EXPECT_EQ(Checksum().value(), 0x2D06800538D394C2ULL);
  EXPECT_EQ(checksum_of("abc", 3), 0x78AF5F94892F3950ULL);
  EXPECT_EQ(checksum_of("0123456789:;<=>?@ABCDEFGHIJKLMN", 31), 0x7FF327A2F5F9BDD9ULL);
  const std::string fox = "The quick brown fox jumps over the lazy dog";
  EXPECT_EQ(checksum_of(fox.data(), fox.size()), 0xCE7D19A5418FB365ULL);
  const std::vector<unsigned char> b = bytes_0_to(100);  // XXH3's mid-size path
  EXPECT_EQ(checksum_of(b.data(), b.size()), 0x004E4F921A64BD1CULL);
  const std::vector<unsigned char> big = bytes_mod_251(100000);  // its long path: many blocks and a tail
  EXPECT_EQ(checksum_of(big.data(), big.size()), 0x42C23AEEAD96750DULL);
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
      EXPECT_EQ(c.value(), 0x004E4F921A64BD1CULL) << first << " + " << second;
    }
  }
  // Across XXH3's internal buffer (256 bytes) and its blocks (1,024): pieces of every size.
  const std::vector<unsigned char> big = bytes_mod_251(100000);
  for (std::size_t piece : {1, 63, 255, 256, 257, 1023, 1024, 4096, 65537}) {
    Checksum c;
    for (std::size_t at = 0; at < big.size(); at += piece) c.add(big.data() + at, std::min(piece, big.size() - at));
    EXPECT_EQ(c.value(), 0x42C23AEEAD96750DULL) << piece;
  }
}

TEST(Checksum, NoBytesFromANullPointerMidStreamChangeNothing) {
  // An empty vector's data() is null; the graph writer adds such vectors between others.
  // Under UndefinedBehaviorSanitizer this also checks that nothing is copied from null.
  Checksum c;
  c.add("ab", 2);
  c.add(nullptr, 0);
  c.add("c", 1);
  EXPECT_EQ(c.value(), 0x78AF5F94892F3950ULL);
}

TEST(Checksum, ValueCanBeTakenMidStream) {
  Checksum c;
  c.add("ab", 2);
  (void)c.value();
  c.add("c", 1);
  EXPECT_EQ(c.value(), 0x78AF5F94892F3950ULL);
}

}  // namespace
}  // namespace gmg
