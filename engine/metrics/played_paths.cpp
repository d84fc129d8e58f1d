// What a reenactment played and how it was cut and reused; definitions in played_paths.h.
#include "engine/metrics/played_paths.h"

#include <algorithm>
#include <unordered_map>

#include "engine/core/error.h"
#include "engine/metrics/naturalness.h"

namespace gmg {
namespace {

// A report's ranges hold at most this many frames each: a bound on the memory a hostile report
// can ask for (10 million frames is 92 hours at 30 fps).
constexpr long kMaxRangeFrames = 10000000;

template <typename Json>
const Json& field(const Json& item, const char* key, const std::string& where) {
  if (!item.is_object() || !item.contains(key)) throw Error(where + " lacks " + key);
  return item[key];
}

template <typename Json>
int int_field(const Json& item, const char* key, const std::string& where) {
  const Json& v = field(item, key, where);
  if (!v.is_number_integer() || v.template get<long>() < 0 || v.template get<long>() > kMaxRangeFrames)
    throw Error(where + ": " + key + " is not a whole number in [0, " + std::to_string(kMaxRangeFrames) + "]");
  return v.template get<int>();
}

template <typename Json>
std::vector<int> ranges_field(const Json& item, const std::string& where) {
  const Json& ranges = field(item, "graph_ranges", where);
  if (!ranges.is_array()) throw Error(where + ": graph_ranges is not a list");
  std::vector<int> frames;
  for (const Json& r : ranges) {
    if (!r.is_array() || r.size() != 2 || !r[0].is_number_integer() || !r[1].is_number_integer() ||
        r[0].template get<long>() < 0 || r[1].template get<long>() < r[0].template get<long>() ||
        r[1].template get<long>() - r[0].template get<long>() >= kMaxRangeFrames ||
        r[1].template get<long>() > kMaxRangeFrames)
      throw Error(where + ": a graph range is not [first, last] with 0 <= first <= last");
    if (frames.size() + static_cast<std::size_t>(r[1].template get<long>() - r[0].template get<long>()) >=
        static_cast<std::size_t>(kMaxRangeFrames))
      throw Error(where + ": graph_ranges hold more than " + std::to_string(kMaxRangeFrames) + " frames");
    for (int g = r[0].template get<int>(); g <= r[1].template get<int>(); ++g) frames.push_back(g);
  }
  return frames;
}

// The fields a subsequence and a stretch share: where it starts, how long it lasts (its
// `length_key`), the graph frames it plays.
template <typename Json>
PlayedSegment segment_of(const Json& item, const char* length_key, const std::string& where) {
  PlayedSegment seg;
  seg.start_frame = int_field(item, "start_frame", where);
  seg.length = int_field(item, length_key, where);
  seg.path = ranges_field(item, where);
  return seg;
}

template <typename Json>
PlayedPaths parse(const Json& rep, const std::string& name) {
  if (!rep.is_object() || !rep.contains("subsequences") || !rep["subsequences"].is_array())
    throw Error(name + ": not a gmg reenactment report (no subsequences)");
  PlayedPaths out;
  int k = 0;
  for (const Json& s : rep["subsequences"]) {
    const std::string where = name + ": subsequence " + std::to_string(k++);
    PlayedSegment seg = segment_of(s, "target_length", where);
    const Json& continued = field(s, "continued", where);
    if (!continued.is_boolean()) throw Error(where + ": continued is not true or false");
    seg.continued = continued.template get<bool>();
    seg.transitions_inside = int_field(s, "transitions_inside", where);
    const Json& gap = field(s, "junction_gap_cm", where);
    if (!gap.is_number() || !(gap.template get<double>() >= 0.0))
      throw Error(where + ": junction_gap_cm is not a number >= 0");
    seg.junction_gap_cm = gap.template get<double>();
    out.upper.push_back(std::move(seg));
  }
  if (rep.contains("lower_body") && !rep["lower_body"].is_null()) {
    const Json& lower = rep["lower_body"];
    const std::string where = name + ": lower_body";
    const Json& stretches = field(lower, "stretches", where);
    if (!stretches.is_array()) throw Error(where + ": stretches is not a list");
    k = 0;
    for (const Json& s : stretches) {
      const std::string at = where + " stretch " + std::to_string(k++);
      PlayedSegment seg = segment_of(s, "length", at);
      const Json& change = field(s, "change", at);
      if (!change.is_string()) throw Error(at + ": change is not a name");
      out.stance_changes += change.template get<std::string>() != "start";
      out.lower.push_back(std::move(seg));
    }
  }
  return out;
}

}  // namespace

PlayedPaths played_paths_of(const nlohmann::json& report, const std::string& name) { return parse(report, name); }
PlayedPaths played_paths_of(const nlohmann::ordered_json& report, const std::string& name) {
  return parse(report, name);
}

std::vector<int> played_frames(const std::vector<PlayedSegment>& segments) {
  std::vector<int> out;
  for (const PlayedSegment& s : segments) out.insert(out.end(), s.path.begin(), s.path.end());
  return out;
}

int back_jumps(const std::vector<PlayedSegment>& segments, double fps, double window_s) {
  const double window = window_s * fps;         // output frames
  std::unordered_map<int, double> last_played;  // graph frame -> output frame it was last read at
  int jumps = 0, previous = -1;
  for (const PlayedSegment& s : segments) {
    const std::size_t n = s.path.size();
    for (std::size_t i = 0; i < n; ++i) {
      const int f = s.path[i];
      const double at =
          s.start_frame + (n > 1 ? static_cast<double>(i) * (s.length - 1) / static_cast<double>(n - 1) : 0.0);
      // A new piece that is not the natural continuation of the one before.
      if (previous >= 0 && f != previous + 1) {
        const auto it = last_played.find(f);
        if (it != last_played.end() && at - it->second < window) ++jumps;
      }
      last_played[f] = at;
      previous = f;
    }
  }
  return jumps;
}

Reuse reference_reuse(const std::vector<int>& source_frames, int reference_frames) {
  Reuse r;
  if (source_frames.empty()) return r;
  int size = reference_frames;
  if (size <= 0) size = *std::max_element(source_frames.begin(), source_frames.end()) + 1;
  std::vector<int> plays(static_cast<std::size_t>(std::max(size, 0)), 0);
  for (std::size_t i = 0; i < source_frames.size(); ++i) {
    const int f = source_frames[i];
    if (f < 0 || f >= size)
      throw Error("reference reuse: frame " + std::to_string(f) + " is outside the reference's " +
                  std::to_string(size) + " frames");
    if (i == 0 || source_frames[i - 1] != f) ++plays[static_cast<std::size_t>(f)];
  }
  r.max_plays = *std::max_element(plays.begin(), plays.end());
  if (reference_frames > 0)
    r.coverage = static_cast<double>(std::count_if(plays.begin(), plays.end(), [](int p) { return p > 0; })) /
                 static_cast<double>(reference_frames);
  return r;
}

LifelikePaths lifelike_paths(const PlayedPaths& paths, double fps, double duration_s, const LifelikeParams& params) {
  check_lifelike_params(params);
  LifelikePaths out;
  std::vector<double> gaps;
  for (std::size_t i = 0; i < paths.upper.size(); ++i) {
    const PlayedSegment& s = paths.upper[i];
    out.junctions += s.transitions_inside;
    if (i > 0 && !s.continued) {
      ++out.junctions;
      gaps.push_back(s.junction_gap_cm);
    }
  }
  const double minutes = duration_s / 60.0;
  out.junctions_per_min = minutes > 0.0 ? out.junctions / minutes : 0.0;
  if (!gaps.empty()) out.junction_gap_median_cm = percentile(gaps, 50.0);
  const bool layered = !paths.lower.empty();
  out.stance_changes_per_min = layered ? (minutes > 0.0 ? paths.stance_changes / minutes : 0.0) : out.junctions_per_min;
  const std::vector<PlayedSegment>& lower = layered ? paths.lower : paths.upper;
  out.max_plays_upper = reference_reuse(played_frames(paths.upper), 0).max_plays;
  out.max_plays_lower = reference_reuse(played_frames(lower), 0).max_plays;
  out.back_jumps_upper = back_jumps(paths.upper, fps, params.back_jump_window_s);
  out.back_jumps_lower = back_jumps(lower, fps, params.back_jump_window_s);
  return out;
}

}  // namespace gmg
