#include "engine/pipeline/report.h"

#include "engine/core/json.h"

namespace gmg {
namespace {

// Contiguous runs of a path: [[first, last], ...] in graph frames.
nlohmann::ordered_json frame_ranges(const std::vector<int>& path) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < path.size();) {
    std::size_t j = i;
    while (j + 1 < path.size() && path[j + 1] == path[j] + 1) ++j;
    out.push_back({path[i], path[j]});
    i = j + 1;
  }
  return out;
}

}  // namespace

nlohmann::ordered_json reenactment_report(const Plan& plan, const SpeechEvents& events, const Config& config,
                                          double fps, double length_to_cm, bool speech_driven) {
  nlohmann::ordered_json rep;
  rep["frames"] = events.total_frames;
  rep["fps"] = fps;
  rep["duration_s"] = events.duration_s;
  rep["seed"] = config.seed;
  rep["parameters"] = parse_ordered_json_text(config_to_json(config), "the config");
  rep["test_events"] = {
      {"onsets", events.onset_frames.size()}, {"keywords", events.keyword_frames.size()}, {"words", events.words}};
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  int accepted = 0;
  double speech_sum = 0.0;
  for (const PlannedSegment& s : plan.segments) {
    speech_sum += s.speech_cost * s.sub.length;
    nlohmann::ordered_json item;
    item["start_frame"] = s.sub.start;
    item["target_length"] = s.sub.length;
    item["termination"] =
        s.sub.kind == Termination::Keyword ? "keyword" : (s.sub.kind == Termination::Frame ? "frame" : "rhythm");
    if (s.sub.kind == Termination::Keyword) item["keyword"] = s.sub.keyword;
    if (s.sub.kind == Termination::Frame) item["stop_frame"] = s.sub.stop_frame;
    if (s.sub.fixed != Fixed::None) item["fixed"] = s.sub.fixed == Fixed::Rest ? "rest" : "pin";
    item["accepted"] = s.accepted;
    item["continued"] = s.continued;
    item["junction_gap_cm"] = s.junction_gap * length_to_cm;
    item["junction_cost"] = s.junction_cost;
    item["transitions_inside"] = s.transitions_inside;
    item["speech_cost"] = s.speech_cost;
    item["reuse_cost"] = s.reuse_cost;
    item["retries"] = s.retries;
    item["fallback"] = fallback_name(s.fallback);
    item["failure"] = s.failure;
    item["cost"] = s.cost;
    item["path_length"] = s.path.size();
    item["graph_ranges"] = frame_ranges(s.path);
    list.push_back(item);
    if (s.accepted) ++accepted;
  }
  rep["subsequences"] = list;
  rep["totals"] = {{"subsequences", plan.segments.size()},
                   {"accepted", accepted},
                   {"failures", plan.failure_count()},
                   {"fallbacks",
                    {{"keyword_to_rhythm", plan.fallback_count(Fallback::KeywordToRhythm)},
                     {"ignore_stops", plan.fallback_count(Fallback::IgnoreStops)},
                     {"hold_last_frame", plan.fallback_count(Fallback::HoldLastFrame)},
                     {"continue_motion", plan.fallback_count(Fallback::ContinueMotion)}}}};
  const bool natural = config.search.planner == PlannerMode::Natural;
  rep["totals"]["speech_driven"] = natural && speech_driven;
  rep["totals"]["mean_speech_cost"] = events.total_frames > 0 ? speech_sum / events.total_frames : 0.0;
  if (natural && !speech_driven)
    rep["notes"].push_back(
        "the graph holds no reference speech (made by an older gmg or from clips without it): planned without the "
        "speech-driven costs; rebuild it with 'gmg build' for motion that follows the speech");
  return rep;
}

}  // namespace gmg
