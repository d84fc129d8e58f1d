// engine/config/config: a config file's values must have the JSON type of their key (a string
// for a number, an array for one value, are refused naming the key), and a key that names nothing
// is quoted in a short message, in time linear in its length.
#include <chrono>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/config/config.h"
#include "engine/core/error.h"

namespace gmg {
namespace {

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

std::string load_error(const std::string& text) {
  Config c;
  return error_of([&] { config_load_text(c, text, "c.json"); });
}

TEST(ConfigTypes, AValueOfAnotherJsonTypeThanItsKeysIsRefusedNamingBoth) {
  EXPECT_EQ(load_error(R"({"speech_weight": "3"})"),
            R"(c.json: config key 'speech_weight': expected a number, got a string ("3"))");
  EXPECT_EQ(load_error(R"({"variety": [0.3]})"),
            "c.json: config key 'variety': expected a number, got an array ([0.3])");
  EXPECT_EQ(load_error(R"({"l_pn": "5"})"), R"(c.json: config key 'l_pn': expected a number, got a string ("5"))");
  EXPECT_EQ(load_error(R"({"seed": "5"})"), R"(c.json: config key 'seed': expected a number, got a string ("5"))");
  EXPECT_EQ(load_error(R"({"l_pn": true})"), "c.json: config key 'l_pn': expected a number, got true or false (true)");
  EXPECT_EQ(load_error(R"({"fallbacks": "true"})"),
            R"(c.json: config key 'fallbacks': expected true or false, got a string ("true"))");
  EXPECT_EQ(load_error(R"({"fallbacks": 1})"),
            "c.json: config key 'fallbacks': expected true or false, got a number (1)");
  EXPECT_EQ(load_error(R"({"planner": 1})"), "c.json: config key 'planner': expected a string, got a number (1)");
  EXPECT_EQ(load_error(R"({"keywords": null})"), "c.json: config key 'keywords': expected a string, got null (null)");
  EXPECT_EQ(load_error(R"({"w_full": "1,2"})"),
            R"(c.json: config key 'w_full': expected an array of numbers, got a string ("1,2"))");
  EXPECT_EQ(load_error(R"({"w_full": [1, "2"]})"),
            R"(c.json: config key 'w_full': expected an array of numbers, got an array ([1,"2"]))");
  EXPECT_EQ(load_error(R"({"lock_joints": "Neck"})"),
            R"(c.json: config key 'lock_joints': expected an array of strings, got a string ("Neck"))");
  EXPECT_EQ(load_error(R"({"lambda_w": {"a": 1}})"),
            R"(c.json: config key 'lambda_w': expected a number, got an object ({"a":1}))");
}

TEST(ConfigTypes, EveryKeyTakesTheTypeGmgConfigPrintsAndRefusesItAsAString) {
  // What `gmg config` prints loads back, key by key ...
  const nlohmann::json all = nlohmann::json::parse(config_to_json(Config{}));
  std::set<std::string> checked;
  for (const ConfigKey& k : config_keys()) {
    const nlohmann::json& v = all.at(k.name);
    const nlohmann::json one = {{k.name, v}};
    EXPECT_EQ(load_error(one.dump()), "<no error>") << one.dump();
    // ... and the same value as a string is refused, except for the keys whose values are strings.
    if (v.is_string()) continue;
    const nlohmann::json as_text = {{k.name, v.dump()}};
    EXPECT_NE(load_error(as_text.dump()).find("config key '" + k.name + "': expected "), std::string::npos)
        << as_text.dump();
    checked.insert(k.name);
  }
  EXPECT_GE(checked.size(), 45u);  // every key but keywords and the six modes
}

TEST(ConfigTypes, AHugeUnknownKeyIsQuotedShortAndFoundUnknownInLinearTime) {
  const std::string key(10'000'000, 'x');
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = load_error("{\"" + key + "\": 1}");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(e,
            "c.json: unknown config key '" + std::string(60, 'x') + "\u2026' (run 'gmg config --keys' for the list)");
  EXPECT_LT(seconds, 5.0);  // was 14 s to 20 s: the edit distance to every key name, quadratic
  // A long value is cut the same way, at a character's start.
  const std::string value = std::string(59, 'a') + "\u00e9" + std::string(1000, 'b');
  EXPECT_EQ(load_error("{\"planner\": \"" + value + "\"}"),
            "c.json: config key 'planner': '" + std::string(59, 'a') + "\u2026' is not natural or paper");
  // A near name is still suggested.
  EXPECT_EQ(load_error(R"({"l_pm": 3})"), "c.json: unknown config key 'l_pm' (did you mean 'l_pn'?)");
}

}  // namespace
}  // namespace gmg
