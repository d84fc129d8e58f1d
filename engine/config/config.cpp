#include "engine/config/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

double parse_double(const std::string& key, const std::string& v) {
  double out = 0.0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
  if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(out))
    throw Error("config key '" + key + "': '" + shorten_for_message(v) + "' is not a finite number");
  return out;
}

// A whole number within [lo, hi]: "config key 'l_npaths': 1000000000 is out of range (1 to 1000)".
template <typename T>
T parse_whole(const std::string& key, const std::string& v, T lo, T hi) {
  T out = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
  if (r.ptr != v.data() + v.size() || (r.ec != std::errc() && r.ec != std::errc::result_out_of_range)) {
    if (std::is_unsigned<T>::value && !v.empty() && v[0] == '-')
      throw Error("config key '" + key + "': must not be negative");
    throw Error("config key '" + key + "': '" + shorten_for_message(v) + "' is not a whole number");
  }
  if (r.ec == std::errc::result_out_of_range || out < lo || out > hi)
    throw Error("config key '" + key + "': " + v + " is out of range (" + std::to_string(lo) + " to " +
                std::to_string(hi) + ")");
  return out;
}

bool parse_bool(const std::string& key, const std::string& v) {
  if (v == "true" || v == "1" || v == "on" || v == "yes") return true;
  if (v == "false" || v == "0" || v == "off" || v == "no") return false;
  throw Error("config key '" + key + "': '" + shorten_for_message(v) + "' is not true or false");
}

// The shortest text that reads back as exactly v, so `gmg config --keys` shows 0.2, not
// 0.20000000000000001, and config_to_json (which parses it back) keeps every bit.
std::string format_double(double v) { return format_number(v); }

// What a key's value is, for the JSON types a config file may give it.
enum class KeyKind {
  Number,   // a JSON number
  Whole,    // a JSON number with a whole value (4.0 is read as 4)
  Bool,     // true or false
  Text,     // a string (a file name)
  Choice,   // a string naming one of the mode's values
  Numbers,  // an array of numbers (w_full)
  Texts,    // an array of strings (lock_joints)
};

struct Accessor {
  ConfigKey key;
  std::function<void(Config&, const std::string&)> set;
  std::function<std::string(const Config&)> get;
  KeyKind kind = KeyKind::Number;
};

// The text of a number key's range, added to its help ("[1 to 1000]").
// Whole numbers in full ("100000", not "1e+05").
template <typename T>
std::string range_text(T lo, T hi) {
  if constexpr (std::is_integral_v<T>) return " [" + std::to_string(lo) + " to " + std::to_string(hi) + "]";
  return " [" + format_number(static_cast<double>(lo)) + " to " + format_number(static_cast<double>(hi)) + "]";
}

template <typename T>
Accessor number_key(const char* name, const char* help, T Config::*group, double(T::*field)) {
  return {{name, help},
          [=](Config& c, const std::string& v) { (c.*group).*field = parse_double(name, v); },
          [=](const Config& c) { return format_double((c.*group).*field); }};
}
// A number key with a bound the stage's own validation does not set (a huge value would make
// the engine loop or overflow).
template <typename T>
Accessor bounded_number_key(const char* name, const char* help, T Config::*group, double(T::*field), double lo,
                            double hi) {
  return {{name, help + range_text(lo, hi)},
          [=](Config& c, const std::string& v) {
            const double x = parse_double(name, v);
            if (x < lo || x > hi)
              throw Error(std::string("config key '") + name + "': " + v + " is out of range (" + format_number(lo) +
                          " to " + format_number(hi) + ")");
            (c.*group).*field = x;
          },
          [=](const Config& c) { return format_double((c.*group).*field); }};
}
// Every whole-number key has a range, in its help: values beyond it would only cost time or
// memory (a beam of 10^9 paths), never help.
template <typename T>
Accessor int_key(const char* name, const char* help, T Config::*group, int(T::*field), int lo, int hi) {
  return {{name, help + range_text(lo, hi)},
          [=](Config& c, const std::string& v) { (c.*group).*field = parse_whole<int>(name, v, lo, hi); },
          [=](const Config& c) { return std::to_string((c.*group).*field); },
          KeyKind::Whole};
}
template <typename T>
Accessor bool_key(const char* name, const char* help, T Config::*group, bool(T::*field)) {
  return {{name, help},
          [=](Config& c, const std::string& v) { (c.*group).*field = parse_bool(name, v); },
          [=](const Config& c) { return std::string((c.*group).*field ? "true" : "false"); },
          KeyKind::Bool};
}
template <typename T>
Accessor string_key(const char* name, const char* help, T Config::*group, std::string(T::*field)) {
  return {{name, help},
          [=](Config& c, const std::string& v) { (c.*group).*field = v; },
          [=](const Config& c) { return (c.*group).*field; },
          KeyKind::Text};
}

// A mode chosen by name from the enum's table (engine/core/enum_names.h).
template <typename T, typename E, std::size_t N>
Accessor enum_key(const char* name, const char* help, T Config::*group, E(T::*field), const EnumName<E> (&table)[N]) {
  return {{name, help},
          [=, &table](Config& c, const std::string& v) {
            const std::optional<E> e = enum_from_name(table, v);
            if (!e) {
              std::vector<std::string> names;
              for (const EnumName<E>& n : table) names.emplace_back(n.name);
              throw Error(std::string("config key '") + name + "': '" + shorten_for_message(v) + "' is not " +
                          enum_choices(table) + did_you_mean(v, names));
            }
            (c.*group).*field = *e;
          },
          [=, &table](const Config& c) { return std::string(enum_name(table, (c.*group).*field)); },
          KeyKind::Choice};
}

// One table of every key, in the order `gmg config` prints them: its length is the number of
// keys, not complexity.
const std::vector<Accessor>& accessors() {  // NOLINT(readability-function-size)
  static const std::vector<Accessor> table = {
      number_key("lambda_pos", "weight of joint positions in the pose distance", &Config::graph,
                 &GraphParams::lambda_pos),
      number_key("lambda_vel", "weight of joint velocities in the pose distance", &Config::graph,
                 &GraphParams::lambda_vel),
      int_key("l_cn", "frames after l averaged for l's continuity threshold", &Config::graph, &GraphParams::l_cn, 1,
              300),
      int_key("l_pn", "pruning neighbourhood in frames (weak pruning: 1)", &Config::graph, &GraphParams::l_pn, 1,
              10000),
      bool_key("exclude_near", "never add a transition to a frame within l_pn (false: paper-literal)", &Config::graph,
               &GraphParams::exclude_near),
      number_key("min_onset_strength", "raw onset strength a peak needs (weak detection: 0)", &Config::graph,
                 &GraphParams::min_onset_strength),
      number_key("break_jump_factor", "capture jump = distance to next frame above this times the median",
                 &Config::graph, &GraphParams::break_jump_factor),
      string_key("keywords", "keyword lexicon file (empty: assets/keywords.txt)", &Config::graph,
                 &GraphParams::keywords),
      int_key("max_transitions",
              "at most this many transitions out of a frame, the nearest (0: no bound, the paper's analysis)",
              &Config::graph, &GraphParams::max_transitions, 0, 100000),
      int_key("candidates_per_transition", "candidates looked at per transition kept (times max_transitions)",
              &Config::graph, &GraphParams::candidates_per_transition, 1, 1000),
      enum_key("neighbours",
               "candidate search: auto (exact up to exact_frames frames, the tree above), exact or approximate",
               &Config::graph, &GraphParams::neighbours, kNeighbourSearchNames),
      int_key("exact_frames",
              "auto: the exact search up to this many frames, the k-d tree above (same candidates up to "
              "ann_checks)",
              &Config::graph, &GraphParams::exact_frames, 0, 100000000),
      int_key("ann_checks",
              "approximate search: frames examined per frame at most; under auto up to 1 h at 30 fps, a quarter "
              "more per doubling beyond (0: until exact)",
              &Config::graph, &GraphParams::ann_checks, 0, 100000000),
      int_key("l_npaths", "beam width and number of start nodes", &Config::search, &SearchParams::l_npaths, 1, 1000),
      number_key("lambda_w", "weight of edge weights in the path cost", &Config::search, &SearchParams::lambda_w),
      number_key("lambda_len", "weight of the length mismatch in the path cost", &Config::search,
                 &SearchParams::lambda_len),
      int_key("l_feat", "key-node feature length", &Config::search, &SearchParams::l_feat, 1, 1000),
      number_key("lambda_full", "weight of the whole feature distance", &Config::search, &SearchParams::lambda_full),
      number_key("lambda_first", "weight of the first-length ratio", &Config::search, &SearchParams::lambda_first),
      number_key("lambda_occ", "weight of how often a start node was used", &Config::search, &SearchParams::lambda_occ),
      {{"w_full", "feature element weights, comma separated"},
       [](Config& c, const std::string& v) {
         c.search.w_full.clear();
         for (const std::string& item : split_trimmed(v, ',')) c.search.w_full.push_back(parse_double("w_full", item));
       },
       [](const Config& c) {
         std::string s;
         for (double w : c.search.w_full) s += (s.empty() ? "" : ",") + format_double(w);
         return s;
       },
       KeyKind::Numbers},
      int_key("retries", "retries with new start nodes before a fallback", &Config::search, &SearchParams::retries, 0,
              100),
      bounded_number_key("max_length_factor", "beam search stops after this times l_sub extensions", &Config::search,
                         &SearchParams::max_length_factor, 1.1, 100),
      bool_key("fallbacks", "use the termination fallbacks (false: count failures)", &Config::search,
               &SearchParams::fallbacks),
      enum_key("planner",
               "natural (junction-aware, ours) or paper (the published planner, with its cross-fade and a free root)",
               &Config::search, &SearchParams::planner, kPlannerModeNames),
      number_key("junction_rank", "weight of the junction cost in the start-node ranking (natural planner)",
                 &Config::search, &SearchParams::junction_rank),
      number_key("junction_beam", "weight of the junction cost in the beam path cost (natural planner)",
                 &Config::search, &SearchParams::junction_beam),
      number_key("continue_min", "shortest natural continuation taken, times l_sub (natural planner)", &Config::search,
                 &SearchParams::continue_min),
      number_key("continue_max", "longest natural continuation taken, times l_sub (natural planner)", &Config::search,
                 &SearchParams::continue_max),
      int_key("merge_below", "subsequences shorter than this many frames merge into the next (natural planner)",
              &Config::search, &SearchParams::merge_below, 0, 1000),
      number_key(
          "variety",
          "share of the reference each seed withholds as places to jump to (natural planner; 0: seeds plan alike)",
          &Config::search, &SearchParams::variety),
      number_key("speech_weight",
                 "sync against smoothness: weight of the speech distance in every candidate's cost (0 = no speech)",
                 &Config::search, &SearchParams::speech_weight),
      number_key("beat_weight", "cost of a path that does not end on a kinematic beat (part of the speech cost)",
                 &Config::search, &SearchParams::beat_weight),
      number_key("rest_weight",
                 "in pauses of the new speech, weight of the reference's motion (part of the speech cost)",
                 &Config::search, &SearchParams::rest_weight),
      number_key("reuse_weight", "weight of the cost of replaying recently played reference frames", &Config::search,
                 &SearchParams::reuse_weight),
      number_key("reuse_halflife_s", "output seconds after which a play costs half as much", &Config::search,
                 &SearchParams::reuse_halflife_s),
      int_key("reuse_cap_plays",
              "plays of one reference frame within reuse_cap_window_s that cost far more (0: no cap)", &Config::search,
              &SearchParams::reuse_cap_plays, 0, 100),
      number_key("reuse_cap_window_s", "output seconds over which reuse_cap_plays are counted", &Config::search,
                 &SearchParams::reuse_cap_window_s),
      number_key("no_return_s", "a jump into a frame played within this many output seconds costs as a capped one",
                 &Config::search, &SearchParams::no_return_s),
      bool_key("layers",
               "layered body: the lower body plays its own calm path, changing stance only with both feet planted "
               "(false: one path for the whole body, feet held by the foot lock)",
               &Config::search, &SearchParams::layers),
      number_key("rest_min_s", "new-speech pauses at least this long rest (natural planner), seconds", &Config::search,
                 &SearchParams::rest_min_s),
      number_key("rest_lead_s",
                 "a rest starts this long before its pause: the way into it, and any change of stance, seconds",
                 &Config::search, &SearchParams::rest_lead_s),
      enum_key("init", "start nodes: feature or random (weak initialisation)", &Config::search, &SearchParams::init,
               kInitModeNames),
      int_key("ignore_rounds", "rounds of fallback 2, each ignoring a larger share of stopping nodes", &Config::search,
              &SearchParams::ignore_rounds, 1, 100),
      int_key("start_candidates",
              "most key nodes a subsequence ranks as start nodes; above it an even sample of them (0: all)",
              &Config::search, &SearchParams::start_candidates, 0, 100000000),
      int_key("l_blend", "frames blended on each side of a junction", &Config::blend, &BlendParams::l_blend, 0, 1000),
      enum_key("blend_curve", "blend weights: linear or sigmoid", &Config::blend, &BlendParams::curve,
               kBlendCurveNames),
      enum_key("blend_mode",
               "inertialize (carry each transition's offset over and let it decay), offset (spread the junction's "
               "excess jump) or crossfade (the paper's held-frame cross-fade)",
               &Config::blend, &BlendParams::mode, kBlendModeNames),
      number_key("transition_halflife", "inertialization half-life, seconds", &Config::blend, &BlendParams::halflife_s),
      enum_key("root", "root at transitions: anchor (continue where the output was) or free (as captured)",
               &Config::blend, &BlendParams::root, kRootModeNames),
      number_key("root_halflife", "seconds for the root anchor to relax halfway back to the capture's position",
                 &Config::blend, &BlendParams::root_halflife_s),
      bool_key("foot_lock", "keep feet the capture has on the ground planted (IK on the legs)", &Config::blend,
               &BlendParams::foot_lock),
      number_key("foot_step_s", "seconds a released foot takes to step to where the leg puts it", &Config::blend,
                 &BlendParams::foot_step_s),
      int_key("beat_shift",
              "frames the upper body's kinematic beat may move to land on an onset it plays through (0: off)",
              &Config::blend, &BlendParams::beat_shift, 0, 30),
      number_key("beat_rate", "the most a beat's move may speed playback up or slow it down (times)", &Config::blend,
                 &BlendParams::beat_rate),
      number_key("spine_follow",
                 "layered body: share of the pelvis difference the spine takes up so the chest keeps the gesture's "
                 "posture (1) or rides on the lower body's pelvis (0)",
                 &Config::blend, &BlendParams::spine_follow),
      enum_key("up", "the reference's up axis: auto (the axis along which the body is tallest), y or z (gmg build)",
               &Config::graph, &GraphParams::up, kUpChoiceNames),
      {{"lower_joints",
        "joints the lower body's own path drives, comma separated (gmg build; empty: the root, the chain to where the "
        "legs part and the legs, found from the skeleton)"},
       [](Config& c, const std::string& v) { c.graph.lower_joints = split_trimmed(v, ','); },
       [](const Config& c) {
         std::string s;
         for (const std::string& j : c.graph.lower_joints) s += (s.empty() ? "" : ",") + j;
         return s;
       },
       KeyKind::Texts},
      {{"lock_joints", "reference joints whose yaw/pitch are locked and roll smoothed, comma separated (empty: off)"},
       [](Config& c, const std::string& v) { c.cleanup.lock_joints = split_trimmed(v, ','); },
       [](const Config& c) {
         std::string s;
         for (const std::string& j : c.cleanup.lock_joints) s += (s.empty() ? "" : ",") + j;
         return s;
       },
       KeyKind::Texts},
      int_key("smooth_window", "Savitzky-Golay window for the locked joints' roll (odd)", &Config::cleanup,
              &CleanupParams::smooth_window, 3, 255),
      int_key("smooth_order", "Savitzky-Golay polynomial order", &Config::cleanup, &CleanupParams::smooth_order, 0, 15),
      // The face track (engine/face/params.h).
      enum_key("face_mode", "the jaw and expressions follow the new speech (speech) or the body's path (body)",
               &Config::face, &FaceParams::mode, kFaceModeNames),
      int_key("face_candidates", "face track: reference stretches kept per unit of the new speech", &Config::face,
              &FaceParams::candidates, 1, 500),
      int_key("face_unit_frames", "face track: frames per unit of speech without phones", &Config::face,
              &FaceParams::unit_frames, 1, 60),
      number_key("face_silence_unit_max_s",
                 "face track: longest pause between phones played as one unit, seconds [0.05, 10]", &Config::face,
                 &FaceParams::silence_unit_max_s),
      number_key("face_phone_weight", "face track: cost of a reference phone of another symbol [0, 100]", &Config::face,
                 &FaceParams::phone_weight),
      number_key("face_context_weight", "face track: cost of other neighbouring phones [0, 100]", &Config::face,
                 &FaceParams::context_weight),
      number_key("face_duration_weight", "face track: cost of |log| of the duration ratio [0, 100]", &Config::face,
                 &FaceParams::duration_weight),
      number_key("face_audio_weight", "face track: cost of sounding unlike the new speech [0, 100]", &Config::face,
                 &FaceParams::audio_weight),
      number_key("face_spectrum_weight", "face track: weight of voicing and spectrum against loudness [0, 100]",
                 &Config::face, &FaceParams::spectrum_weight),
      number_key("face_jaw_weight", "face track: cost of a jaw unlike the one the speech predicts [0, 100]",
                 &Config::face, &FaceParams::jaw_weight),
      number_key("face_join_weight", "face track: weight of a join's cost [0, 100]", &Config::face,
                 &FaceParams::join_weight),
      number_key("face_join_cost", "face track: cost of any join, beside the faces' difference [0, 100]", &Config::face,
                 &FaceParams::join_cost),
      number_key("face_crossfade_s", "face track: seconds a join cross-fades either side [0, 1]", &Config::face,
                 &FaceParams::crossfade_s),
      {{"seed", "seed of every random choice [0 to 18446744073709551615]"},
       [](Config& c, const std::string& v) {
         c.seed = parse_whole<std::uint64_t>("seed", v, 0, std::numeric_limits<std::uint64_t>::max());
       },
       [](const Config& c) { return std::to_string(c.seed); },
       KeyKind::Whole},
  };
  return table;
}

const Accessor& find_accessor(const std::string& key) {
  for (const Accessor& a : accessors())
    if (a.key.name == key) return a;
  std::vector<std::string> names;
  for (const Accessor& a : accessors()) names.push_back(a.key.name);
  const std::string near = did_you_mean(key, names);
  throw Error("unknown config key '" + shorten_for_message(key) + "'" +
              (near.empty() ? " (run 'gmg config --keys' for the list)" : near));
}

}  // namespace

const std::vector<ConfigKey>& config_keys() {
  static const std::vector<ConfigKey> keys = [] {
    std::vector<ConfigKey> out;
    for (const Accessor& a : accessors()) out.push_back(a.key);
    return out;
  }();
  return keys;
}

void config_set(Config& config, const std::string& key, const std::string& value) {
  find_accessor(key).set(config, value);
}

void config_set_assignment(Config& config, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error("--set expects key=value, got '" + shorten_for_message(assignment) + "'");
  config_set(config, assignment.substr(0, eq), assignment.substr(eq + 1));
}

std::string config_get(const Config& config, const std::string& key) { return find_accessor(key).get(config); }

namespace {

// "a string (\"3\")": a JSON value's type, and the value itself when short, for a message.
std::string json_type_text(const nlohmann::json& v) {
  const char* type = v.is_string()    ? "a string"
                     : v.is_array()   ? "an array"
                     : v.is_object()  ? "an object"
                     : v.is_boolean() ? "true or false"
                     : v.is_null()    ? "null"
                                      : "a number";
  return std::string(type) + " (" + shorten_for_message(json_dump(v, -1)) + ")";
}

// What a key of `kind` needs from JSON, or nullptr when v is of that type.
const char* json_type_problem(KeyKind kind, const nlohmann::json& v) {
  switch (kind) {
    case KeyKind::Number:
    case KeyKind::Whole:
      return v.is_number() ? nullptr : "a number";
    case KeyKind::Bool:
      return v.is_boolean() ? nullptr : "true or false";
    case KeyKind::Text:
    case KeyKind::Choice:
      return v.is_string() ? nullptr : "a string";
    case KeyKind::Numbers:
      return v.is_array() && std::all_of(v.begin(), v.end(), [](const nlohmann::json& x) { return x.is_number(); })
                 ? nullptr
                 : "an array of numbers";
    case KeyKind::Texts:
      return v.is_array() && std::all_of(v.begin(), v.end(), [](const nlohmann::json& x) { return x.is_string(); })
                 ? nullptr
                 : "an array of strings";
  }
  return nullptr;
}

// The text config_set expects for a JSON value of the type its key takes (gmg::Error naming the
// key and both types otherwise: "3" for a number would read as the number, [0.3] as 0.3, and a
// file that says something else than it means should not work by accident): a string as is, an
// array as a comma-separated list, a number of a whole-number key with an integral value as that
// integer (config_to_json writes every number as a JSON double, e.g. 4.0), anything else as JSON.
std::string json_value_text(const Accessor& a, const nlohmann::json& v) {
  if (const char* wanted = json_type_problem(a.kind, v))
    throw Error("config key '" + a.key.name + "': expected " + wanted + ", got " + json_type_text(v));
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string text;
    for (const auto& item : v)
      text += (text.empty() ? "" : ",") + (item.is_string() ? item.get<std::string>() : json_dump(item, -1));
    return text;
  }
  if (v.is_number_float() && a.kind == KeyKind::Whole) {
    const double d = v.get<double>();
    if (std::trunc(d) == d && std::abs(d) < 9007199254740992.0)  // 2^53: every integer exact
      return std::to_string(static_cast<long long>(d));
  }
  return json_dump(v, -1);
}

}  // namespace

void config_load_file(Config& config, const std::string& path) {
  config_load_text(config, read_file_bytes(path), path);
}

void config_load_text(Config& config, const std::string& text, const std::string& path) {
  const nlohmann::json j = parse_json_text(text, path);
  if (!j.is_object()) throw Error(path + ": a config file must be a JSON object of \"key\": value");
  for (auto it = j.begin(); it != j.end(); ++it) {
    try {
      const Accessor& a = find_accessor(it.key());
      a.set(config, json_value_text(a, it.value()));
    } catch (const Error& e) {
      throw Error(path + ": " + e.what());
    }
  }
}

std::string config_to_json(const Config& config) {
  nlohmann::ordered_json j;
  for (const Accessor& a : accessors()) {
    const std::string v = a.get(config);
    if (a.key.name == "w_full") {
      j[a.key.name] = config.search.w_full;
    } else if (a.key.name == "lock_joints") {
      j[a.key.name] = config.cleanup.lock_joints;
    } else if (a.key.name == "lower_joints") {
      j[a.key.name] = config.graph.lower_joints;
    } else if (a.key.name == "seed") {
      j[a.key.name] = config.seed;
    } else if (v == "true" || v == "false") {
      j[a.key.name] = v == "true";
    } else {
      double d = 0.0;
      const auto r = std::from_chars(v.data(), v.data() + v.size(), d);
      if (!v.empty() && r.ec == std::errc() && r.ptr == v.data() + v.size())
        j[a.key.name] = d;
      else
        j[a.key.name] = v;
    }
  }
  return json_dump(j, 2);
}

Config config_from(const std::string& file, const std::vector<std::string>& assignments) {
  Config c;
  if (!file.empty()) config_load_file(c, file);
  for (const std::string& a : assignments) config_set_assignment(c, a);
  config_validate(c);
  return c;
}

void config_validate(const Config& c) {
  graph_params_validate(c.graph);
  search_params_validate(c.search);
  cleanup_params_validate(c.cleanup);
  blend_params_validate(c.blend);
  face_params_validate(c.face);
}

}  // namespace gmg
