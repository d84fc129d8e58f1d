// engine/config/config: setting keys from text, the JSON config file, and the round trip of
// `gmg config > c.json; gmg --config c.json`.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/config/config.h"
#include "engine/core/error.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using testing::TempDir;
using testing::write_text;

// The message of the gmg::Error f throws ("<no error>" when it does not).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(ConfigSet, SetsEachKindOfKeyAndReadsItBack) {
  Config c;
  config_set(c, "l_pn", "3");
  EXPECT_EQ(c.graph.l_pn, 3);
  EXPECT_EQ(config_get(c, "l_pn"), "3");
  config_set(c, "lambda_w", "0.25");
  EXPECT_EQ(c.search.lambda_w, 0.25);
  EXPECT_EQ(config_get(c, "lambda_w"), "0.25");
  config_set(c, "exclude_near", "off");
  EXPECT_FALSE(c.graph.exclude_near);
  EXPECT_EQ(config_get(c, "exclude_near"), "false");
  config_set(c, "keywords", "my words.txt");
  EXPECT_EQ(c.graph.keywords, "my words.txt");
  config_set(c, "init", "random");
  EXPECT_EQ(c.search.init, InitMode::Random);
  EXPECT_EQ(config_get(c, "init"), "random");
  config_set(c, "blend_mode", "crossfade");
  EXPECT_EQ(c.blend.mode, BlendMode::Crossfade);
  config_set(c, "seed", "42");
  EXPECT_EQ(c.seed, 42u);
}

TEST(ConfigSet, NumbersPrintAsTheShortestTextThatReadsBack) {
  // `gmg config --keys` prints 0.1, not its 17 digits 0.10000000000000001; a value that needs them
  // (0.1 + 0.2) keeps them, so the text always reads back as the same double.
  Config c;
  config_set(c, "lambda_occ", "0.1");
  EXPECT_EQ(config_get(c, "lambda_occ"), "0.1");
  config_set(c, "lambda_occ", "0.30000000000000004");
  EXPECT_EQ(config_get(c, "lambda_occ"), "0.30000000000000004");
  EXPECT_EQ(c.search.lambda_occ, 0.1 + 0.2);
}

TEST(ConfigSet, ListsAreCommaSeparatedTrimmedAndSkipEmptyItems) {
  Config c;
  config_set(c, "w_full", " 1, 2.5 ,,\t3 ");
  EXPECT_EQ(c.search.w_full, (std::vector<double>{1.0, 2.5, 3.0}));
  EXPECT_EQ(config_get(c, "w_full"), "1,2.5,3");
  config_set(c, "lock_joints", "Neck, Head ,");
  EXPECT_EQ(c.cleanup.lock_joints, (std::vector<std::string>{"Neck", "Head"}));
  EXPECT_EQ(config_get(c, "lock_joints"), "Neck,Head");
  config_set(c, "lock_joints", "");
  EXPECT_TRUE(c.cleanup.lock_joints.empty());
}

TEST(ConfigSet, BadValuesNameTheKeyAndTheValue) {
  Config c;
  EXPECT_EQ(error_of([&] { config_set(c, "nope", "1"); }),
            "unknown config key 'nope' (run 'gmg config --keys' for the list)");
  EXPECT_EQ(error_of([&] { config_set(c, "l_pn", "2.5"); }), "config key 'l_pn': '2.5' is not a whole number");
  EXPECT_EQ(error_of([&] { config_set(c, "lambda_w", "abc"); }), "config key 'lambda_w': 'abc' is not a finite number");
  EXPECT_EQ(error_of([&] { config_set(c, "lambda_w", "inf"); }), "config key 'lambda_w': 'inf' is not a finite number");
  EXPECT_EQ(error_of([&] { config_set(c, "fallbacks", "maybe"); }),
            "config key 'fallbacks': 'maybe' is not true or false");
  EXPECT_EQ(error_of([&] { config_set(c, "seed", "-1"); }), "config key 'seed': must not be negative");
  EXPECT_EQ(error_of([&] { config_set(c, "l_blend", "3000000000"); }),
            "config key 'l_blend': 3000000000 is out of range (0 to 1000)");
  EXPECT_EQ(error_of([&] { config_set(c, "seed", "18446744073709551616"); }),
            "config key 'seed': 18446744073709551616 is out of range (0 to 18446744073709551615)");
  EXPECT_EQ(c.graph.l_pn, Config{}.graph.l_pn);  // a rejected value changes nothing
}

TEST(ConfigSet, EnumKeysRejectAnUnknownNameListingTheChoices) {
  Config c;
  EXPECT_EQ(error_of([&] { config_set(c, "init", "best"); }), "config key 'init': 'best' is not feature or random");
  EXPECT_EQ(error_of([&] { config_set(c, "blend_curve", "cubic"); }),
            "config key 'blend_curve': 'cubic' is not linear or sigmoid");
  EXPECT_EQ(error_of([&] { config_set(c, "blend_mode", "Offset"); }),  // names are exact, a near one is named
            "config key 'blend_mode': 'Offset' is not inertialize, offset or crossfade (did you mean 'offset'?)");
  EXPECT_EQ(c.search.init, Config{}.search.init);
}

TEST(ConfigSetAssignment, SplitsAtTheFirstEqualsSign) {
  Config c;
  config_set_assignment(c, "lock_joints=a=b,c");
  EXPECT_EQ(c.cleanup.lock_joints, (std::vector<std::string>{"a=b", "c"}));
  EXPECT_EQ(error_of([&] { config_set_assignment(c, "l_pn"); }), "--set expects key=value, got 'l_pn'");
  EXPECT_EQ(error_of([&] { config_set_assignment(c, "=3"); }), "--set expects key=value, got '=3'");
}

TEST(ConfigFrom, DefaultsThenFileThenAssignmentsInOrderThenValidation) {
  TempDir dir;
  const std::string file = dir.file("c.json");
  write_text(file, R"({"l_pn": 2, "l_cn": 7, "init": "random"})");
  const Config c = config_from(file, {"l_pn=5", "l_pn=6", "retries=0"});
  EXPECT_EQ(c.graph.l_pn, 6);  // the last --set wins over the file
  EXPECT_EQ(c.graph.l_cn, 7);  // the file over the default
  EXPECT_EQ(c.search.init, InitMode::Random);
  EXPECT_EQ(c.search.retries, 0);
  EXPECT_EQ(c.search.l_npaths, Config{}.search.l_npaths);  // untouched keys keep their default
  const Config d = config_from("", {});
  EXPECT_EQ(config_to_json(d), config_to_json(Config{}));
  // Validation runs on the result: w_full must have l_feat weights.
  const std::string e = error_of([&] { config_from(file, {"l_feat=3"}); });
  EXPECT_EQ(e.rfind("invalid config: ", 0), 0u) << e;
  EXPECT_NE(e.find("w_full"), std::string::npos) << e;
}

TEST(ConfigLoadFile, ErrorsNameTheFile) {
  TempDir dir;
  Config c;
  const std::string bad_json = dir.file("bad.json");
  write_text(bad_json, "{\"l_pn\": }");
  const std::string e1 = error_of([&] { config_load_file(c, bad_json); });
  EXPECT_EQ(e1.rfind(bad_json + ": byte ", 0), 0u) << e1;
  EXPECT_NE(e1.find("invalid JSON"), std::string::npos) << e1;
  const std::string array = dir.file("array.json");
  write_text(array, "[1, 2]");
  EXPECT_EQ(error_of([&] { config_load_file(c, array); }),
            array + ": a config file must be a JSON object of \"key\": value");
  const std::string bad_key = dir.file("key.json");
  write_text(bad_key, R"({"init": "best"})");
  EXPECT_EQ(error_of([&] { config_load_file(c, bad_key); }),
            bad_key + ": config key 'init': 'best' is not feature or random");
}

TEST(ConfigLoadFile, WholeNumberKeysAcceptIntegralJsonNumbersOnly) {
  TempDir dir;
  const std::string file = dir.file("c.json");
  Config c;
  write_text(file, R"({"ignore_rounds": 4.0, "l_blend": 6, "seed": 9.0, "lambda_w": 2.0, "w_full": [1, 0.5]})");
  config_load_file(c, file);
  EXPECT_EQ(c.search.ignore_rounds, 4);
  EXPECT_EQ(c.blend.l_blend, 6);
  EXPECT_EQ(c.seed, 9u);
  EXPECT_EQ(c.search.lambda_w, 2.0);
  EXPECT_EQ(c.search.w_full, (std::vector<double>{1.0, 0.5}));
  write_text(file, R"({"ignore_rounds": 4.5})");
  EXPECT_EQ(error_of([&] { config_load_file(c, file); }),
            file + ": config key 'ignore_rounds': '4.5' is not a whole number");
  write_text(file, R"({"l_pn": 1e30})");
  EXPECT_NE(error_of([&] { config_load_file(c, file); }), "<no error>");
}

// What `gmg config > c.json; gmg --config c.json ...` does: every number in config_to_json is a
// JSON double (l_pn: 3.0), and reading it back must give the same config.
TEST(ConfigToJson, RoundTripsThroughConfigLoadFile) {
  TempDir dir;
  const std::string file = dir.file("c.json");
  const std::string defaults = config_to_json(Config{});
  EXPECT_NE(defaults.find("\"ignore_rounds\": 4.0"), std::string::npos) << defaults;
  write_text(file, defaults);
  Config c;
  config_set(c, "l_pn", "9");  // so the file has something to restore
  config_set(c, "init", "random");
  config_load_file(c, file);
  EXPECT_EQ(config_to_json(c), defaults);

  Config changed;
  for (const char* a :
       {"l_pn=2", "lambda_occ=0.1", "exclude_near=false", "keywords=k.txt", "init=random", "blend_curve=linear",
        "lock_joints=Neck,Head", "seed=123456789", "w_full=1,2,3,4,5,6,7,8,9,0.3"})
    config_set_assignment(changed, a);
  const std::string text = config_to_json(changed);
  write_text(file, text);
  const Config back = config_from(file, {});
  EXPECT_EQ(config_to_json(back), text);
  EXPECT_EQ(back.search.lambda_occ, 0.1);
  EXPECT_EQ(back.cleanup.lock_joints, (std::vector<std::string>{"Neck", "Head"}));
  EXPECT_EQ(back.seed, 123456789u);
}

TEST(ConfigKeys, EveryKeyReadsBackWhatItPrints) {
  const Config d;
  for (const ConfigKey& k : config_keys()) {
    Config c;
    config_set(c, k.name, config_get(d, k.name));
    EXPECT_EQ(config_get(c, k.name), config_get(d, k.name)) << k.name;
    EXPECT_FALSE(k.help.empty()) << k.name;
  }
  const nlohmann::json j = nlohmann::json::parse(config_to_json(d));
  EXPECT_EQ(j.size(), config_keys().size());
}

// The message of whatever f throws ("" when nothing).
template <typename F>
std::string error_of_any(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// Every whole-number key documents its range in its help ("[1 to 1000]") and enforces it: both
// ends are accepted, one beyond either is refused naming the key and the range.
TEST(ConfigKeys, EveryWholeNumberKeyHasADocumentedRange) {
  int checked = 0;
  for (const ConfigKey& k : config_keys()) {
    Config probe;
    const std::string why = error_of_any([&] { config_set(probe, k.name, "0.5"); });
    if (why.find("is not a whole number") == std::string::npos || k.name == "seed") continue;
    const std::size_t open = k.help.rfind(" ["), to = k.help.find(" to ", open == std::string::npos ? 0 : open);
    ASSERT_NE(open, std::string::npos) << k.name << " has no range in its help: " << k.help;
    ASSERT_NE(to, std::string::npos) << k.help;
    const long long lo = std::stoll(k.help.substr(open + 2, to - open - 2));
    const long long hi = std::stoll(k.help.substr(to + 4));
    Config c;
    config_set(c, k.name, std::to_string(lo));
    config_set(c, k.name, std::to_string(hi));
    for (const long long beyond : {lo - 1, hi + 1})
      EXPECT_EQ(error_of([&] { config_set(c, k.name, std::to_string(beyond)); }),
                "config key '" + k.name + "': " + std::to_string(beyond) + " is out of range (" + std::to_string(lo) +
                    " to " + std::to_string(hi) + ")");
    ++checked;
  }
  // l_cn, l_pn, max_transitions, candidates_per_transition, exact_frames, ann_checks, l_npaths, l_feat,
  // retries, merge_below, reuse_cap_plays, ignore_rounds, start_candidates, l_blend, beat_shift, smooth_window,
  // smooth_order, face_candidates, face_unit_frames
  EXPECT_EQ(checked, 19);
  Config c;
  EXPECT_EQ(error_of([&] { config_set(c, "l_npaths", "1000000000"); }),
            "config key 'l_npaths': 1000000000 is out of range (1 to 1000)");
  EXPECT_EQ(error_of([&] { config_set(c, "max_length_factor", "1e300"); }),
            "config key 'max_length_factor': 1e300 is out of range (1.1 to 100)");
}

TEST(ConfigToJson, RoundTripsTheLargestSeed) {
  TempDir dir;
  Config c;
  config_set(c, "seed", "18446744073709551615");
  write_text(dir.file("c.json"), config_to_json(c));
  EXPECT_EQ(config_from(dir.file("c.json"), {}).seed, 18446744073709551615ull);
}

}  // namespace
}  // namespace gmg
