// Every tunable parameter of the engine, with its default: the one place defaults live.
//
// The paper's values (section 5) are the defaults where it gives them; the others are our
// choices, explained beside each field. Every field can be set from a JSON config file
// (`--config FILE`, an object of "key": value) or the command line (`--set key=value`), by the
// key named in config_keys(). `gmg config` prints them all.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gmg {

struct GraphParams {
  double lambda_pos = 1.0;          // weight of the joint-position term of the pose distance
  double lambda_vel = 1.0;          // weight of the joint-velocity term
  int l_cn = 5;                     // frames after l whose mean distance is l's continuity threshold
  int l_pn = 10;                    // pruning neighbourhood (frames)
  bool exclude_near = true;         // never jump to |r - l| <= l_pn (a stutter); false = paper-literal
  double min_onset_strength = 5.0;  // raw onset envelope value a peak needs (mean per-band dB rise)
  // Capture jumps: a frame whose distance to the next is above break_jump_factor times the
  // clip's median frame-to-frame distance is a break node. 8x the median is far outside the
  // spread of natural motion (speed rarely exceeds 4x its median in conversational gesture)
  // yet catches the teleports of a broken capture.
  double break_jump_factor = 8.0;
  std::string keywords;             // keyword lexicon file; "" = assets/keywords.txt
};

struct SearchParams {
  int l_npaths = 20;                // beam width and number of start nodes
  double lambda_w = 1.0;            // weight of the summed edge weights in the path cost
  double lambda_len = 1.0;          // weight of the length mismatch |1 - len/l_sub|
  int l_feat = 10;                  // key-node feature length
  double lambda_full = 1.0;
  double lambda_first = 1.0;
  double lambda_occ = 0.5;
  std::vector<double> w_full = {1, .5, .5, .2, .2, .2, .1, .1, .1, .1};
  // Retries with fresh start nodes before a fallback. 3 gives the next 60 key nodes a chance
  // (with l_npaths 20) while keeping a hopeless subsequence cheap.
  int retries = 3;
  // The beam stops after max_length_factor * l_sub + 2 extensions: no path longer than
  // 1.1 * l_sub can be accepted, so 1.5 leaves room for paths that wander and come back.
  double max_length_factor = 1.5;
  bool fallbacks = true;            // false: report failures instead (paper's Table 2 ablation)
  std::string init = "feature";     // "feature" (paper 4.2.3) or "random" (weak initialisation)
  // Fallback 2 drops this growing share of stopping nodes per round: 0.25, 0.5, 0.75, 1.0.
  int ignore_rounds = 4;
};

struct BlendParams {
  // Frames on each side of a junction. Retries restart the search at other key nodes, so some
  // junctions join distant poses: on BEAT2 (2_scott_0_2_2 from 0_1_1) 8 frames (0.27 s at
  // 30 fps) halves the output's mean jerk against 4 (94.8k -> 50.1k cm/s^3), while 12 also
  // lowers Div, i.e. starts to smear strokes.
  int l_blend = 8;
  std::string curve = "sigmoid";    // "linear" or "sigmoid"
  // "offset": keep both pieces' own motion and spread the junction's excess jump (the right
  // piece's first frame minus where the left piece was heading) over the window, so a junction
  // that is already continuous is left as it is. "crossfade": SPEC's literal cross-fade of
  // "left, then its last frame held" into "right's first frame held, then right"; its holds
  // stall one side while the other moves, so even a continuous junction speeds up and slows
  // down (a step of v (1 - w) + dw * l_blend * v > v). Offset is the default for that reason.
  std::string mode = "offset";
};

struct CleanupParams {
  // Reference clips' joints whose yaw and pitch are locked and roll smoothed (engine/cleanup.h);
  // empty = off, the default. The paper's GENEA 2023 setup names the four wrist joints.
  std::vector<std::string> lock_joints;
  int smooth_window = 15;  // Savitzky-Golay window (odd), the paper's value
  int smooth_order = 3;    // Savitzky-Golay polynomial order, the paper's value
};

struct Config {
  GraphParams graph;
  SearchParams search;
  BlendParams blend;
  CleanupParams cleanup;
  std::uint64_t seed = 20231009;    // default seed (the paper's conference date)
};

struct ConfigKey {
  std::string name;   // e.g. "l_pn"
  std::string help;   // one line
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

// Reads a JSON object of key: value pairs into config. Errors name the file.
void config_load_file(Config& config, const std::string& path);

// The config as a JSON object text (every key).
std::string config_to_json(const Config& config);

// Checks ranges and combinations; throws gmg::Error describing the first problem.
void config_validate(const Config& config);

// The defaults, then the JSON file (when not empty), then each "key=value" in order; validated.
// What every subcommand's --config/--set options produce.
Config config_from(const std::string& file, const std::vector<std::string>& assignments);

}  // namespace gmg
