// The layered body of a reenactment: the lower body's own plan (search/lower_body.h) beside the
// upper body's (search/planner.h), each assembled by source time with inertialized transitions,
// joined at the spine (engine/assemble/layers.h).
#pragma once

#include <random>

#include <nlohmann/json.hpp>

#include "engine/assemble/timeline.h"
#include "engine/config/config.h"
#include "engine/motion/body_layers.h"
#include "engine/motion/stance.h"
#include "graph/motion_graph.h"
#include "search/lower_body.h"
#include "search/planner.h"

namespace gmg {

struct LowerBody {
  BodyLayers layers;  // empty: not layered (the whole body follows the upper plan)
  LowerPlan plan;
};

// The lower body's plan, when config asks for layers (the natural planner with `layers`) and the
// graph's skeleton has two legs; otherwise layers stay empty. `rests`: the output's rests (the
// upper body's). Draws from rng after the upper body's plan.
LowerBody plan_lower_body(const MotionGraph& g, const std::vector<Anchor>& rests, int total_frames,
                          const Config& config, std::mt19937_64& rng);

// The output's rests (search/anchors.h rest_anchors) for the new speech's features: its pauses of
// rest_min_s or longer, each held as long as the reference ever rests (search/rests.h); none for
// the paper's planner or a graph without speech or activity.
std::vector<Anchor> output_rests(const MotionGraph& g, const std::vector<float>& features, int total_frames,
                                 const Config& config);

// The motion of a plan with a layered body: the upper plan and the lower plan each assembled
// (without the foot lock: the lower body plays the capture's own feet), joined at the spine.
// `beats` as assemble_motion's, for the upper body.
Motion assemble_layered(const MotionGraph& g, const Plan& plan, const LowerBody& lower, const BlendParams& params,
                        const BeatAlignment* beats = nullptr);

// Per output frame, how much the new speech pauses (audio::pause_weight of its loudness); empty
// without speech features.
std::vector<float> pause_track(const std::vector<float>& features, int frames);

// The report's "lower_body": the layers' joints and one entry per stretch (start_frame,
// length, change, graph_ranges, stance_gap); null when not layered.
nlohmann::ordered_json lower_body_report(const Skeleton& skeleton, const LowerBody& lower);

}  // namespace gmg
