// Tests of text/phones: the phones tier of a TextGrid, phone symbols and visemes.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.h"
#include "tests/test_support.h"
#include "tests/text/text_test_util.h"
#include "text/phones.h"

namespace {

namespace tx = gmg::text;

TEST(Phones, SymbolsDropStressAndSilence) {
  EXPECT_EQ(tx::phone_symbol("AH0"), "AH");
  EXPECT_EQ(tx::phone_symbol(" ey1 "), "EY");
  EXPECT_EQ(tx::phone_symbol("M"), "M");
  EXPECT_EQ(tx::phone_symbol("sil"), "");
  EXPECT_EQ(tx::phone_symbol("sp"), "");
  EXPECT_EQ(tx::phone_symbol("spn"), "");
  EXPECT_EQ(tx::phone_symbol(""), "");
}

TEST(Phones, VisemesGroupLikeMouths) {
  EXPECT_EQ(tx::viseme_of("P"), tx::Viseme::Bilabial);
  EXPECT_EQ(tx::viseme_of("M"), tx::Viseme::Bilabial);
  EXPECT_EQ(tx::viseme_of("AA"), tx::Viseme::OpenVowel);
  EXPECT_EQ(tx::viseme_of("IY"), tx::Viseme::CloseVowel);
  EXPECT_EQ(tx::viseme_of(""), tx::Viseme::Silence);
  EXPECT_EQ(tx::viseme_of("QQ"), tx::Viseme::Other);
  EXPECT_EQ(tx::phone_difference("B", "B"), 0);
  EXPECT_EQ(tx::phone_difference("B", "M"), 1);
  EXPECT_EQ(tx::phone_difference("B", "AA"), 2);
}

TEST(Phones, ThePhonesTierOfATextGrid) {
  gmg::testing::TempDir dir;
  gmg::testing::write_text(dir.file("a.TextGrid"), gmg::testing::kLongTextGrid);
  const auto phones = tx::read_phones(dir.file("a.TextGrid"));
  ASSERT_EQ(phones.size(), 1u);  // the silence dropped
  EXPECT_EQ(phones[0].symbol, "AH");
  EXPECT_DOUBLE_EQ(phones[0].start, 1.0);
  EXPECT_DOUBLE_EQ(phones[0].end, 3.5);
  // MFA names it "<speaker> - phones"; without such a tier there are none, and no error.
  std::string renamed = gmg::testing::kLongTextGrid;
  renamed.replace(renamed.find("\"phones\""), 8, "\"scott - phones\"");
  EXPECT_EQ(tx::parse_textgrid_phones(renamed, "b.TextGrid").size(), 1u);
  renamed.replace(renamed.find("\"scott - phones\""), 16, "\"syllables\"");
  EXPECT_TRUE(tx::parse_textgrid_phones(renamed, "c.TextGrid").empty());
  gmg::testing::write_text(dir.file("a.tsv"), "1\t2\thello\n");
  EXPECT_TRUE(tx::read_phones(dir.file("a.tsv")).empty());
}

TEST(Phones, ABrokenPhonesTierNamesTheFile) {
  std::string bad = gmg::testing::kLongTextGrid;
  bad.replace(bad.find("xmax = 3.5 \n            text = \"AH0\""), 10, "xmax = 0.5 ");
  try {
    tx::parse_textgrid_phones(bad, "bad.TextGrid");
    ADD_FAILURE() << "accepted a phone that ends before it starts";
  } catch (const gmg::Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.TextGrid"), std::string::npos) << e.what();
  }
}

// A phones tier past the audio's end (a transcript of another recording) is refused as words are,
// naming the file, the phone and both times; within 50 ms of the end it is taken.
TEST(Phones, APhonesTierPastTheAudiosEndIsRefused) {
  const std::vector<tx::Phone> phones = {{1.0, 1.2, "M"}, {1.2, 3.5, "AH"}};
  tx::check_phones_fit(phones, 3.46, "a.TextGrid");
  try {
    tx::check_phones_fit(phones, 3.4, "a.TextGrid");
    ADD_FAILURE() << "accepted a phone ending 0.1 s past the audio";
  } catch (const gmg::Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "a.TextGrid: the phones tier runs past the end of the audio: phone \"AH\" ends at 3.5 s but the audio "
              "lasts 3.4 s (a transcript of another recording?)");
  }
  tx::check_phones_fit({}, 0.0, "a.TextGrid");
}

}  // namespace
