// graph/keyword_label: one interned text per label, the same handle for the same text.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "graph/keyword_label.h"
#include "graph/motion_graph.h"

namespace gmg {
namespace {

TEST(KeywordLabel, TheSameTextIsTheSameLabel) {
  const KeywordLabel none;
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.str(), "");
  EXPECT_TRUE(KeywordLabel("").empty());
  EXPECT_EQ(KeywordLabel(""), none);

  const KeywordLabel big("big");
  const std::string text = "big";
  EXPECT_FALSE(big.empty());
  EXPECT_EQ(big.str(), "big");
  EXPECT_EQ(big, KeywordLabel(text));
  EXPECT_EQ(big, "big");
  EXPECT_EQ(big, text);
  EXPECT_NE(big, "bigger");
  EXPECT_NE(big, KeywordLabel("Big"));  // byte for byte: case matters
  EXPECT_NE(big, none);
  const KeywordLabel phrase = std::string("on the other hand");
  EXPECT_EQ(phrase.str(), "on the other hand");
  std::ostringstream os;
  os << big << "|" << none << "|" << phrase;
  EXPECT_EQ(os.str(), "big||on the other hand");
  // A node's label is a 4-byte handle: a node is 8 bytes.
  EXPECT_EQ(sizeof(KeywordLabel), 4u);
  EXPECT_EQ(sizeof(NodeInfo), 8u);
}

// Threads interning the same texts at once get the same labels, each with its text.
TEST(KeywordLabel, InterningIsThreadSafe) {
  std::vector<std::vector<KeywordLabel>> seen(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 2000; ++i) seen[t].emplace_back("word " + std::to_string(i % 500));
    });
  for (std::thread& t : threads) t.join();
  for (std::size_t t = 0; t < seen.size(); ++t)
    for (int i = 0; i < 2000; ++i) {
      ASSERT_EQ(seen[t][static_cast<std::size_t>(i)], seen[0][static_cast<std::size_t>(i % 500)]);
      ASSERT_EQ(seen[t][static_cast<std::size_t>(i)].str(), "word " + std::to_string(i % 500));
    }
}

}  // namespace
}  // namespace gmg
