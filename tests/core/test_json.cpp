// engine/core/json: reading with the engine's error wording, writing that never throws.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/json.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::error_of;
using testing::TempDir;
using testing::write_text;

TEST(Json, ReadsAFile) {
  TempDir dir;
  write_text(dir.file("a.json"), "\xEF\xBB\xBF{\"a\": [1, 2.5, \"x\"], \"b\": null}");
  const nlohmann::json j = read_json_file(dir.file("a.json"));
  EXPECT_EQ(j.at("a").at(0).get<int>(), 1);
  EXPECT_EQ(j.at("a").at(1).get<double>(), 2.5);
  EXPECT_EQ(j.at("a").at(2).get<std::string>(), "x");
  EXPECT_TRUE(j.at("b").is_null());
}

TEST(Json, SyntaxErrorNamesFileAndByte) {
  TempDir dir;
  // {"a": } : the '}' is the 7th byte, where a value was expected.
  const std::string path = dir.file("bad.json");
  write_text(path, "{\"a\": }");
  const std::string msg = error_of([&] { read_json_file(path); });
  EXPECT_EQ(msg.rfind(path + ": byte 7: invalid JSON (", 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "unexpected '}'");

  write_text(path, "");
  EXPECT_EQ(error_of([&] { read_json_file(path); }).rfind(path + ": byte 1: invalid JSON (", 0), 0u);
}

TEST(Json, NumberOutOfRangeNamesFileAndByte) {
  TempDir dir;
  // 1e309 is beyond the largest double (1.8e308). The number takes bytes 7 to 11 of {"a": 1e309}.
  const std::string path = dir.file("huge.json");
  write_text(path, "{\"a\": 1e309}");
  EXPECT_EQ(error_of([&] { read_json_file(path); }),
            path + ": byte 11: invalid JSON (the number 1e309 is out of range for a double)");
  write_text(path, "[0, -2.5e400]");
  EXPECT_EQ(error_of([&] { read_json_file(path); }),
            path + ": byte 12: invalid JSON (the number -2.5e400 is out of range for a double)");
  EXPECT_EQ(error_of([&] { read_ordered_json_file(path); }),
            path + ": byte 12: invalid JSON (the number -2.5e400 is out of range for a double)");
  // Just below the limit is fine.
  write_text(path, "[1.7976931348623157e308]");
  EXPECT_EQ(read_json_file(path).at(0).get<double>(), 1.7976931348623157e308);
}

TEST(Json, MissingFileUsesTheReaderWording) {
  TempDir dir;
  const std::string path = dir.file("none.json");
  EXPECT_EQ(error_of([&] { read_json_file(path); }), path + ": cannot open (No such file or directory)");
}

TEST(Json, ParseTextUsesTheGivenName) {
  EXPECT_EQ(parse_json_text("[1, 2]", "inline").size(), 2u);
  // The end of input counts as one byte read.
  EXPECT_EQ(error_of([] { parse_json_text("[1,", "settings"); }).rfind("settings: byte 4: invalid JSON (", 0), 0u);
  EXPECT_EQ(error_of([] { parse_json_text("1e999", "settings"); }),
            "settings: byte 5: invalid JSON (the number 1e999 is out of range for a double)");
}

TEST(Json, OrderedKeepsKeyOrder) {
  TempDir dir;
  write_text(dir.file("o.json"), "{\"b\": 1, \"a\": 2}");
  EXPECT_EQ(json_dump(read_ordered_json_file(dir.file("o.json")), -1), "{\"b\":1,\"a\":2}");
  EXPECT_EQ(json_dump(read_json_file(dir.file("o.json")), -1), "{\"a\":2,\"b\":1}");  // sorted
}

TEST(Json, DumpReplacesInvalidUtf8AndIndents) {
  const nlohmann::json j = {{"name", std::string("caf\xE9")}};
  EXPECT_EQ(json_dump(j, -1), "{\"name\":\"caf\xEF\xBF\xBD\"}");
  nlohmann::ordered_json o;
  o["z"] = 1;
  o["a"] = "\xC3\xA9";
  EXPECT_EQ(json_dump(o), "{\n  \"z\": 1,\n  \"a\": \"\xC3\xA9\"\n}");
  EXPECT_EQ(json_dump(o, 0), "{\n\"z\": 1,\n\"a\": \"\xC3\xA9\"\n}");
}

}  // namespace
}  // namespace gmg
