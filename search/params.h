// Search parameters (paper 4.2, A.1, section 5; SPEC "Beam search", "Feature-based
// initialisation", "Fallbacks").
//
// Owned by the search stage: search_params_validate checks them once, before planning.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/enum_names.h"

namespace gmg {

// How start nodes are chosen (paper 4.2.3; "random" is Table 2's weak initialisation).
enum class InitMode : std::uint8_t { Feature, Random };
inline constexpr EnumName<InitMode> kInitModeNames[] = {{InitMode::Feature, "feature"}, {InitMode::Random, "random"}};

// Natural (ours, the default): the paper's method made junction-aware (SPEC "Junction-aware
// search"): start nodes and beam paths pay for the pose distance from where the output would
// continue, a natural continuation is taken when its stop node falls within a wider window,
// very short subsequences merge into the next, and near-equal candidates are drawn at random.
// Paper: the paper's planner as published (all of that off); the pipeline then also joins pieces
// with the paper's cross-fade and a free root.
enum class PlannerMode : std::uint8_t { Natural, Paper };
inline constexpr EnumName<PlannerMode> kPlannerModeNames[] = {{PlannerMode::Natural, "natural"},
                                                              {PlannerMode::Paper, "paper"}};

struct SearchParams {
  PlannerMode planner = PlannerMode::Natural;
  int l_npaths = 20;        // beam width and number of start nodes
  double lambda_w = 1.0;    // weight of the summed edge weights in the path cost
  double lambda_len = 1.0;  // weight of the length mismatch |1 - len/l_sub|
  int l_feat = 10;          // key-node feature length
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
  bool fallbacks = true;              // false: report failures instead (paper's Table 2 ablation)
  InitMode init = InitMode::Feature;  // feature (paper 4.2.3) or random (weak initialisation)
  // Fallback 2 drops this growing share of stopping nodes per round: 0.25, 0.5, 0.75, 1.0.
  int ignore_rounds = 4;
  // The most key nodes a subsequence ranks as start nodes (0: all of them). Ranking costs a
  // subsequence time in proportion to the key nodes it weighs, so a graph with more ranks a sample of
  // this many for each subsequence (search/initialisation.h: blocks of 64 consecutive key nodes,
  // every stride-th block, the offset drawn per subsequence), and what ranking costs stops growing
  // with the reference; with fewer every key node is ranked, exactly as before, so references of up
  // to about 38 minutes plan as they did. Why 8192: docs/decisions.md (Parameters).
  int start_candidates = 8192;

  // ---- natural planner only ----
  // Junction cost J(s) = d_pose(c, s) / (mean unnatural edge weight of the graph), c the frame the
  // output would continue into. Added to d_feat with weight junction_rank when ranking start
  // nodes (d_feat differences between good key nodes are a few frames; J of a distant pose is
  // 3-10, so 5 lets pose continuity decide among rhythmically similar nodes) and to a beam path's
  // cost with weight junction_beam (one unnatural edge's worth per unit of J).
  double junction_rank = 5.0;
  double junction_beam = 1.0;
  // A natural continuation whose stop node lies within [continue_min, continue_max] x l_sub is
  // taken and time-warped onto the target. 0.5-2.0 visibly speeds playback up; 0.9-1.1 (the
  // beam's window) continues too rarely (the prototype measured 0.7-1.4 best).
  double continue_min = 0.7;
  double continue_max = 1.4;
  // Test subsequences shorter than this (frames) merge into the next: a 1/3 s piece cannot hold
  // a gesture and only adds a junction.
  int merge_below = 10;
  // Seeded variety (natural planner): the share of the reference's seconds each seed withholds
  // as places to jump to, so different seeds give clearly different motions (search/start_ranking.h).
  // 0: every seed plans the same. Why 0.3: docs/decisions.md (Parameters).
  double variety = 0.3;

  // ---- speech-driven (natural planner; search/speech_match.h, search/reuse.h) ----
  // The knob that trades sync for smoothness: the weight of the speech distance (mean squared
  // feature distance, ~0.1 for well matched speech, 1-3 for unrelated) in every candidate's cost,
  // against the junction cost (1 = a typical transition of the graph). 0 = the natural planner
  // without speech. Why 3: docs/decisions.md (Parameters; docs/results.md has the curve).
  double speech_weight = 3.0;
  // Part of the speech distance: in test pauses, rest_weight x the reference's motion activity
  // (1 = its typical motion) per frame: BEAT2's speaker moves most between phrases, and the output
  // should rest where the speech rests. Why 12: docs/decisions.md (Parameters).
  double rest_weight = 12.0;
  // Part of the speech cost: beat_weight x the end cost of a path (search/speech_match.h end_cost:
  // 0 when it ends on a kinematic beat of the reference, 1 far from one). Why 1: docs/decisions.md
  // (Parameters).
  double beat_weight = 1.0;
  // Weight of the reuse cost (a stretch just played costs 1 per play), and the half-life of a play
  // in output seconds. A replay is worth it only when the speech distance it saves, at most about
  // speech_weight x the speech distance (1 = unrelated speech), exceeds reuse_weight x its decayed
  // plays squared. With a half-life of 120 s, plays within one 60-90 s output barely decay, so a
  // frame's fourth play costs 3 x 9 and does not happen (the figures: docs/decisions.md, Parameters).
  double reuse_weight = 3.0;
  double reuse_halflife_s = 120.0;
  // And a cap: a frame played reuse_cap_plays times within reuse_cap_window_s output seconds
  // costs reuse_weight x 100 more (search/reuse.h): the decayed count alone let a stretch that
  // suits many pauses be played a fourth time within a minute (docs/decisions.md). 0 plays = no cap.
  int reuse_cap_plays = 3;
  double reuse_cap_window_s = 90.0;
  // And no jump into a frame played within the last no_return_s output seconds (a path that plays
  // 497-505, then 493-510 shows the same stroke twice in a row). 0: allowed.
  double no_return_s = 10.0;

  // ---- the layered body (search/lower_body.h; natural planner only) ----
  // The lower body (root, hips, legs) plays its own path of long contiguous stretches, changing
  // only where both feet are planted; the upper body follows the speech (engine/motion/body_layers.h).
  // false: one path for the whole body, its feet held by the foot lock (engine/assemble/foot_lock.h).
  bool layers = true;
  // New-speech pauses at least rest_min_s long rest (search/anchors.h); a rest starts rest_lead_s
  // before its pause: the upper body plays the reference's own way into a rest there (its
  // transition has decayed by the pause), and the lower body changes stance there when it must.
  double rest_min_s = 0.5;
  double rest_lead_s = 0.7;
};

// Throws gmg::Error naming the first key out of range.
void search_params_validate(const SearchParams& params);

}  // namespace gmg
