#include "engine/pipeline/lower_body.h"

#include <cmath>

#include "audio/speech_features.h"
#include "engine/assemble/layers.h"
#include "engine/assemble/transitions.h"
#include "engine/pipeline/assembly.h"
#include "graph/graph_check.h"
#include "graph/reference_facts.h"
#include "search/rests.h"

namespace gmg {

std::vector<float> pause_track(const std::vector<float>& features, int frames) {
  std::vector<float> out;
  if (frames <= 0 || features.size() < static_cast<std::size_t>(frames) * audio::SpeechFeatures::kDims) return out;
  out.resize(static_cast<std::size_t>(frames));
  for (int t = 0; t < frames; ++t)
    out[static_cast<std::size_t>(t)] =
        audio::pause_weight(features[static_cast<std::size_t>(t) * audio::SpeechFeatures::kDims]);
  return out;
}

std::vector<Anchor> output_rests(const MotionGraph& g, const std::vector<float>& features, int total_frames,
                                 const Config& config) {
  if (config.search.planner != PlannerMode::Natural || !g.has_speech()) return {};
  const std::vector<float> pause = pause_track(features, total_frames);
  return rest_anchors(pause, g.motion.fps, config.search.rest_min_s, RestFinder(g).hold(),
                      static_cast<int>(std::lround(config.search.rest_lead_s * g.motion.fps)));
}

LowerBody plan_lower_body(const MotionGraph& g, const std::vector<Anchor>& rests, int total_frames,
                          const Config& config, std::mt19937_64& rng) {
  LowerBody out;
  if (!config.search.layers || config.search.planner != PlannerMode::Natural) return out;
  BodyLayers layers = graph_body_layers(g);
  if (!layers.layered()) return out;
  const CaptureRuns runs = graph_runs(g);
  // A graph of format 10 or older has no stance: it is computed from every frame here.
  const Stance computed = g.stance.known ? Stance{} : stance_facts(g.motion, runs, layers);
  const Stance& stance = g.stance.known ? g.stance : computed;
  if (!stance.known) return out;
  LowerBodyParams p;
  p.reuse_cap_plays = config.search.reuse_cap_plays;
  p.variety = config.search.variety;
  out.plan = plan_lower_body(stance, runs, rests, total_frames, g.motion.fps, p, rng);
  out.layers = std::move(layers);
  return out;
}

Motion assemble_layered(const MotionGraph& g, const Plan& plan, const LowerBody& lower, const BlendParams& params,
                        const BeatAlignment* beats) {
  BlendParams p = params;
  p.foot_lock = false;
  Motion upper = assemble_motion(g, plan, p, beats);
  if (!lower.layers.layered()) return upper;
  std::vector<PathPiece> pieces;
  for (const LowerSegment& s : lower.plan.segments) {
    // The lower body's stretches are read as the upper body's pieces are: checked on use, with the
    // same margin either side (engine/pipeline/assembly.cpp check_played_frames).
    graph_check_frames(g, s.source - 8, s.source + s.length - 1 + 8);
    PathPiece piece;
    piece.length = s.length;
    for (int i = 0; i < s.length; ++i) piece.path.push_back(s.source + i);
    pieces.push_back(std::move(piece));
  }
  const CaptureRuns runs = graph_runs(g);
  const Motion legs = assemble_inertialized(g.motion, runs, g.capture.known ? g.capture : capture_facts(g.motion, runs),
                                            pieces, p, lower.layers.feet);
  return join_layers(upper, legs, lower.layers, params.spine_follow);
}

nlohmann::ordered_json lower_body_report(const Skeleton& skeleton, const LowerBody& lower) {
  if (!lower.layers.layered()) return nullptr;
  nlohmann::ordered_json j;
  j["layers"] = describe_body_layers(skeleton, lower.layers);
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const LowerSegment& s : lower.plan.segments) {
    nlohmann::ordered_json item;
    item["start_frame"] = s.start;
    item["length"] = s.length;
    item["change"] = enum_name(kLowerChangeNames, s.change);
    item["stance_gap"] = s.gap;
    item["graph_ranges"] =
        nlohmann::ordered_json::array({nlohmann::ordered_json::array({s.source, s.source + s.length - 1})});
    list.push_back(std::move(item));
  }
  j["stretches"] = std::move(list);
  return j;
}

}  // namespace gmg
