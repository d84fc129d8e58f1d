// Every tunable parameter of the engine, with its default: the one place defaults live.
//
// The paper's values (section 5) are the defaults where it gives them; the others are our
// choices, explained beside each field. Every field can be set from a JSON config file
// (`--config FILE`, an object of "key": value) or the command line (`--set key=value`), by the
// key named in config_keys(). `gmg config` prints them all.
//
// Every whole-number key has a range, shown in its help (`gmg config --keys`) and enforced when
// it is set: l_cn 1-300, l_pn 1-10000, l_npaths 1-1000, l_feat 1-1000, retries 0-100,
// ignore_rounds 1-100, l_blend 0-1000, beat_shift 0-30, smooth_window 3-255, smooth_order 0-15, seed any 64-bit
// unsigned value; and max_length_factor lies in 1.1-100. Values beyond these only cost time or
// memory (a beam of 10^9 paths) and never help.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/assemble/params.h"
#include "engine/face/params.h"
#include "engine/motion/cleanup.h"
#include "graph/params.h"
#include "search/params.h"

namespace gmg {

// The parameters of every stage, gathered; each stage owns and validates its own struct.
struct Config {
  GraphParams graph;
  SearchParams search;
  BlendParams blend;
  CleanupParams cleanup;
  FaceParams face;
  std::uint64_t seed = 20231009;  // default seed (the paper's conference date)
};

struct ConfigKey {
  std::string name;  // e.g. "l_pn"
  std::string help;  // one line
};

// All keys, in a stable order.
const std::vector<ConfigKey>& config_keys();

// Sets one key from text ("l_pn", "10"). Throws gmg::Error naming the key and value when the
// key is unknown or the value does not parse or is out of range.
void config_set(Config& config, const std::string& key, const std::string& value);

// "key=value" form of config_set.
void config_set_assignment(Config& config, const std::string& assignment);

// Value of a key as text.
std::string config_get(const Config& config, const std::string& key);

// Reads a JSON object of key: value pairs into config. Each value must have its key's JSON type,
// the one config_to_json writes: a number (a whole one for a whole-number key), true or false, a
// string (a file name or a mode), an array of numbers (w_full) or of strings (lock_joints); "3"
// for a number or [0.3] for one value is an error naming the key. Errors name the file, and quote
// a long key or value cut to its first 60 bytes.
void config_load_file(Config& config, const std::string& path);

// The same for JSON text already in memory; `name` labels errors.
void config_load_text(Config& config, const std::string& text, const std::string& name);

// The config as a JSON object text (every key).
std::string config_to_json(const Config& config);

// Checks ranges and combinations; throws gmg::Error describing the first problem.
void config_validate(const Config& config);

// The defaults, then the JSON file (when not empty), then each "key=value" in order; validated.
// What every subcommand's --config/--set options produce.
Config config_from(const std::string& file, const std::vector<std::string>& assignments);

}  // namespace gmg
