#include "engine/pipeline/assembly.h"

#include "engine/assemble/channels.h"
#include "engine/assemble/resample.h"
#include "engine/assemble/transitions.h"
#include "engine/motion/capture_facts.h"
#include "engine/motion/npz.h"
#include "graph/graph_check.h"
#include "graph/reference_facts.h"

namespace gmg {

BlendParams assembly_params(const Config& config) {
  BlendParams p = config.blend;
  // The paper's planner comes with the paper's blending (SPEC: "with the cost weight at 0 and the
  // paper blending, the planner is the paper's").
  if (config.search.planner == PlannerMode::Paper) {
    p.mode = BlendMode::Crossfade;
    p.root = RootMode::Free;
  }
  return p;
}

namespace {

std::vector<PathPiece> plan_pieces(const Plan& plan) {
  std::vector<PathPiece> pieces;
  pieces.reserve(plan.segments.size());
  for (const PlannedSegment& s : plan.segments) pieces.push_back({s.path, s.sub.length});
  return pieces;
}

// Checks the frames the assembly reads, for a graph whose motion is checked when used
// (graph/graph_check.h graph_check_frames; nothing for others): each stretch of consecutive frames
// of each piece, and kMargin frames either side of it (the assembly samples between a frame and
// its successor, and a transition continues the old source a step at its warp rate past its last
// frame). Blocks of 64 frames make the margin cost little.
void check_played_frames(const MotionGraph& g, const Plan& plan) {
  constexpr int kMargin = 8;
  for (const PlannedSegment& s : plan.segments) {
    const std::vector<int>& p = s.path;
    for (std::size_t i = 0; i < p.size();) {
      std::size_t j = i + 1;
      while (j < p.size() && p[j] == p[j - 1] + 1) ++j;
      graph_check_frames(g, p[i] - kMargin, p[j - 1] + kMargin);
      i = j;
    }
  }
}

}  // namespace

std::unique_ptr<BeatAlignment> beat_alignment(const MotionGraph& g, const std::vector<int>& onsets,
                                              const BlendParams& params) {
  if (params.beat_shift <= 0 || params.mode != BlendMode::Inertialize || g.beat_cost.empty()) return nullptr;
  auto out = std::make_unique<BeatAlignment>();
  out->onsets = onsets;
  for (std::size_t f = 0; f < g.beat_cost.size(); ++f)
    if (g.beat_cost[f] == 0.0f) out->beats.push_back(static_cast<int>(f));
  out->max_shift = params.beat_shift;
  out->max_rate = params.beat_rate;
  return out;
}

Motion assemble_motion(const MotionGraph& g, const Plan& plan, const BlendParams& params, const BeatAlignment* beats) {
  check_played_frames(g, plan);
  if (params.mode == BlendMode::Inertialize) {
    // The graph's capture facts, so that only the frames played are read; a graph made without
    // them (by hand) has them computed from every frame.
    const CaptureRuns runs = graph_runs(g);
    return assemble_inertialized(g.motion, runs, g.capture.known ? g.capture : capture_facts(g.motion, runs),
                                 plan_pieces(plan), params, {}, beats);
  }
  std::vector<Motion> pieces;
  pieces.reserve(plan.segments.size());
  for (const PlannedSegment& s : plan.segments) {
    pieces.push_back(resample_path(g.motion, s.path, s.sub.length));
    motion_release_pages(g.motion);  // each piece reads another stretch of a graph served from its file
  }
  return blend_concatenate(pieces, params);
}

SmplxBody assemble_body(const MotionGraph& g, const Plan& plan, const BlendParams& params) {
  SmplxBody out;
  out.betas = g.body.betas;
  out.gender = g.body.gender;
  out.model = g.body.model;
  if (!g.body.has_face()) return out;
  out.expression_dims = g.body.expression_dims;
  out.expressions =
      params.mode == BlendMode::Inertialize
          ? assemble_channels_inertialized(g.body.expressions, g.body.expression_dims, graph_runs(g), plan_pieces(plan),
                                           params.halflife_s * g.motion.fps)
          : assemble_channels_blended(g.body.expressions, g.body.expression_dims, plan_pieces(plan), params);
  return out;
}

nlohmann::ordered_json body_report(const Skeleton& skeleton, const SmplxBody& body, const std::string& betas_from) {
  const bool face = body.has_face(), betas = !body.betas.empty();
  if (!face && !betas && !has_smplx_names(skeleton)) return nullptr;
  nlohmann::ordered_json j;
  j["face"] = face ? "reference" : "none";
  j["betas"] = betas ? betas_from : "none";
  std::string note;
  if (!face)
    note = "the reference has no face (no SMPL-X .npz with expressions): an .npz output's expressions are zeros";
  if (!betas)
    note += std::string(note.empty() ? "" : "; ") +
            "the reference has no body shape: an .npz output's betas are zeros (--betas FILE gives them)";
  if (!note.empty()) j["note"] = note;
  return j;
}

}  // namespace gmg
