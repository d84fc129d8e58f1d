// A plan's paths joined into the output: the motion and the SMPL-X body (face, shape) played along
// it, and what a report says of that body.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/assemble/blend.h"
#include "engine/assemble/timeline.h"
#include "engine/config/config.h"
#include "engine/motion/motion.h"
#include "graph/motion_graph.h"
#include "search/planner.h"

namespace gmg {

// The assembly parameters a configuration implies: config.blend, except that the paper's planner
// joins pieces with the paper's cross-fade and a free root.
BlendParams assembly_params(const Config& config);

// Paths of a plan joined into one motion: by source time with inertialized transitions
// (BlendMode::Inertialize), or resampled to their target lengths and blended (Offset, Crossfade).
// `beats` (optional): beats onto onsets inside continuous stretches (engine/assemble/timeline.h).
Motion assemble_motion(const MotionGraph& g, const Plan& plan, const BlendParams& params,
                       const BeatAlignment* beats = nullptr);

// The beats the upper body's assembly puts on the new speech's onsets: the onsets, the graph's
// kinematic beats (graph/beats.h: its frames of end cost 0); null when params turn it off or the
// graph has no beats.
std::unique_ptr<BeatAlignment> beat_alignment(const MotionGraph& g, const std::vector<int>& onsets,
                                              const BlendParams& params);

// The graph's body along a plan: its shape and labels, and its face assembled as assemble_motion
// assembles the motion (the same clock and transitions); no face when the graph has none.
SmplxBody assemble_body(const MotionGraph& g, const Plan& plan, const BlendParams& params);

// What a report says of an output's body, for an SMPL-X skeleton or a body (else null): {"face":
// "reference" | "none", "betas": betas_from (when the body has betas) | "none", "note": what an
// .npz output holds in place of what is missing}.
nlohmann::ordered_json body_report(const Skeleton& skeleton, const SmplxBody& body,
                                   const std::string& betas_from = "reference");

}  // namespace gmg
