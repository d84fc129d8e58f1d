#include "engine/app/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <sstream>

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
    throw Error("config key '" + key + "': '" + v + "' is not a finite number");
  return out;
}

long long parse_int(const std::string& key, const std::string& v) {
  long long out = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
  if (r.ec != std::errc() || r.ptr != v.data() + v.size())
    throw Error("config key '" + key + "': '" + v + "' is not a whole number");
  return out;
}

bool parse_bool(const std::string& key, const std::string& v) {
  if (v == "true" || v == "1" || v == "on" || v == "yes") return true;
  if (v == "false" || v == "0" || v == "off" || v == "no") return false;
  throw Error("config key '" + key + "': '" + v + "' is not true or false");
}

// 17 significant digits (not format_number's shortest round-trip text) because `gmg config
// --keys` prints this and must stay byte-identical until the switch is made deliberately.
std::string format_double(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

struct Accessor {
  ConfigKey key;
  std::function<void(Config&, const std::string&)> set;
  std::function<std::string(const Config&)> get;
  bool whole = false;  // the value is a whole number (a JSON 4.0 is read as 4)
};

template <typename T>
Accessor number_key(const char* name, const char* help, T Config::*group, double(T::*field)) {
  return {{name, help},
          [=](Config& c, const std::string& v) { (c.*group).*field = parse_double(name, v); },
          [=](const Config& c) { return format_double((c.*group).*field); }};
}
template <typename T>
Accessor int_key(const char* name, const char* help, T Config::*group, int(T::*field)) {
  return {{name, help},
          [=](Config& c, const std::string& v) {
            const long long x = parse_int(name, v);
            if (x < -1000000000LL || x > 1000000000LL)
              throw Error(std::string("config key '") + name + "': out of range");
            (c.*group).*field = static_cast<int>(x);
          },
          [=](const Config& c) { return std::to_string((c.*group).*field); },
          true};
}
template <typename T>
Accessor bool_key(const char* name, const char* help, T Config::*group, bool(T::*field)) {
  return {{name, help},
          [=](Config& c, const std::string& v) { (c.*group).*field = parse_bool(name, v); },
          [=](const Config& c) { return std::string((c.*group).*field ? "true" : "false"); }};
}
template <typename T>
Accessor string_key(const char* name, const char* help, T Config::*group, std::string(T::*field)) {
  return {{name, help},
          [=](Config& c, const std::string& v) { (c.*group).*field = v; },
          [=](const Config& c) { return (c.*group).*field; }};
}

// A mode chosen by name from the enum's table (engine/core/enum_names.h).
template <typename T, typename E, std::size_t N>
Accessor enum_key(const char* name, const char* help, T Config::*group, E(T::*field), const EnumName<E> (&table)[N]) {
  return {{name, help},
          [=, &table](Config& c, const std::string& v) {
            const std::optional<E> e = enum_from_name(table, v);
            if (!e) throw Error(std::string("config key '") + name + "': '" + v + "' is not " + enum_choices(table));
            (c.*group).*field = *e;
          },
          [=, &table](const Config& c) { return std::string(enum_name(table, (c.*group).*field)); }};
}

const std::vector<Accessor>& accessors() {
  static const std::vector<Accessor> table = {
      number_key("lambda_pos", "weight of joint positions in the pose distance", &Config::graph,
                 &GraphParams::lambda_pos),
      number_key("lambda_vel", "weight of joint velocities in the pose distance", &Config::graph,
                 &GraphParams::lambda_vel),
      int_key("l_cn", "frames after l averaged for l's continuity threshold", &Config::graph, &GraphParams::l_cn),
      int_key("l_pn", "pruning neighbourhood in frames (weak pruning: 1)", &Config::graph, &GraphParams::l_pn),
      bool_key("exclude_near", "never add a transition to a frame within l_pn (false: paper-literal)", &Config::graph,
               &GraphParams::exclude_near),
      number_key("min_onset_strength", "raw onset strength a peak needs (weak detection: 0)", &Config::graph,
                 &GraphParams::min_onset_strength),
      number_key("break_jump_factor", "capture jump = distance to next frame above this times the median",
                 &Config::graph, &GraphParams::break_jump_factor),
      string_key("keywords", "keyword lexicon file (empty: assets/keywords.txt)", &Config::graph,
                 &GraphParams::keywords),
      int_key("max_transitions", "at most this many transitions out of a frame, the nearest (0: no bound)",
              &Config::graph, &GraphParams::max_transitions),
      int_key("candidates_per_transition", "candidates looked at per transition kept (times max_transitions)",
              &Config::graph, &GraphParams::candidates_per_transition),
      enum_key("neighbours", "candidate search: auto (exact up to exact_frames frames), exact or approximate",
               &Config::graph, &GraphParams::neighbours, kNeighbourSearchNames),
      int_key("exact_frames", "auto searches candidates exactly up to this many frames", &Config::graph,
              &GraphParams::exact_frames),
      int_key("ann_checks", "approximate search: distance evaluations per frame at most (0: until exact)",
              &Config::graph, &GraphParams::ann_checks),
      int_key("l_npaths", "beam width and number of start nodes", &Config::search, &SearchParams::l_npaths),
      number_key("lambda_w", "weight of edge weights in the path cost", &Config::search, &SearchParams::lambda_w),
      number_key("lambda_len", "weight of the length mismatch in the path cost", &Config::search,
                 &SearchParams::lambda_len),
      int_key("l_feat", "key-node feature length", &Config::search, &SearchParams::l_feat),
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
       }},
      int_key("retries", "retries with new start nodes before a fallback", &Config::search, &SearchParams::retries),
      number_key("max_length_factor", "beam search stops after this times l_sub extensions", &Config::search,
                 &SearchParams::max_length_factor),
      bool_key("fallbacks", "use the termination fallbacks (false: count failures)", &Config::search,
               &SearchParams::fallbacks),
      enum_key("init", "start nodes: feature or random (weak initialisation)", &Config::search, &SearchParams::init,
               kInitModeNames),
      int_key("ignore_rounds", "rounds of fallback 2, each ignoring a larger share of stopping nodes", &Config::search,
              &SearchParams::ignore_rounds),
      int_key("l_blend", "frames blended on each side of a junction", &Config::blend, &BlendParams::l_blend),
      enum_key("blend_curve", "blend weights: linear or sigmoid", &Config::blend, &BlendParams::curve,
               kBlendCurveNames),
      enum_key("blend_mode", "offset (spread the junction's excess jump) or crossfade (SPEC's held-frame cross-fade)",
               &Config::blend, &BlendParams::mode, kBlendModeNames),
      {{"lock_joints", "reference joints whose yaw/pitch are locked and roll smoothed, comma separated (empty: off)"},
       [](Config& c, const std::string& v) { c.cleanup.lock_joints = split_trimmed(v, ','); },
       [](const Config& c) {
         std::string s;
         for (const std::string& j : c.cleanup.lock_joints) s += (s.empty() ? "" : ",") + j;
         return s;
       }},
      int_key("smooth_window", "Savitzky-Golay window for the locked joints' roll (odd)", &Config::cleanup,
              &CleanupParams::smooth_window),
      int_key("smooth_order", "Savitzky-Golay polynomial order", &Config::cleanup, &CleanupParams::smooth_order),
      {{"seed", "seed of every random choice"},
       [](Config& c, const std::string& v) {
         const long long x = parse_int("seed", v);
         if (x < 0) throw Error("config key 'seed': must not be negative");
         c.seed = static_cast<std::uint64_t>(x);
       },
       [](const Config& c) { return std::to_string(c.seed); },
       true},
  };
  return table;
}

const Accessor& find_accessor(const std::string& key) {
  for (const Accessor& a : accessors())
    if (a.key.name == key) return a;
  throw Error("unknown config key '" + key + "' (run 'gmg config' for the list)");
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
  if (eq == std::string::npos || eq == 0) throw Error("--set expects key=value, got '" + assignment + "'");
  config_set(config, assignment.substr(0, eq), assignment.substr(eq + 1));
}

std::string config_get(const Config& config, const std::string& key) { return find_accessor(key).get(config); }

namespace {

// The text config_set expects for a JSON value: a string as is, an array as a comma-separated
// list, a number of a whole-number key with an integral value as that integer (config_to_json
// writes every number as a JSON double, e.g. 4.0), anything else as JSON.
std::string json_value_text(const std::string& key, const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string text;
    for (const auto& item : v)
      text += (text.empty() ? "" : ",") + (item.is_string() ? item.get<std::string>() : item.dump());
    return text;
  }
  if (v.is_number_float()) {
    const double d = v.get<double>();
    const bool whole_key = std::any_of(accessors().begin(), accessors().end(),
                                       [&](const Accessor& a) { return a.key.name == key && a.whole; });
    if (whole_key && std::trunc(d) == d && std::abs(d) < 9007199254740992.0)  // 2^53: every integer exact
      return std::to_string(static_cast<long long>(d));
  }
  return v.dump();
}

}  // namespace

void config_load_file(Config& config, const std::string& path) {
  const nlohmann::json j = read_json_file(path);
  if (!j.is_object()) throw Error(path + ": a config file must be a JSON object of \"key\": value");
  for (auto it = j.begin(); it != j.end(); ++it) {
    try {
      config_set(config, it.key(), json_value_text(it.key(), it.value()));
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
  return j.dump(2);
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
}

}  // namespace gmg
