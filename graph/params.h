// Graph construction parameters (paper 4.1, section 5; SPEC "Key nodes", "Edges").
//
// Owned by the graph stage: graph_params_validate checks them once, before a build.
#pragma once

#include <string>
#include <vector>

#include "engine/core/enum_names.h"
#include "engine/motion/up_axis.h"

namespace gmg {

// How the candidate transitions of each frame are found (graph/neighbours.h: one k-d tree search).
enum class NeighbourSearch {
  Auto,         // Exact up to GraphParams::exact_frames frames, Approximate above
  Exact,        // searched to the end: the exact candidates (time per frame grows with the reference)
  Approximate,  // at most ann_checks frames examined per frame (0: to the end, exact)
};
inline constexpr EnumName<NeighbourSearch> kNeighbourSearchNames[] = {
    {NeighbourSearch::Auto, "auto"}, {NeighbourSearch::Exact, "exact"}, {NeighbourSearch::Approximate, "approximate"}};

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
  std::string keywords;  // keyword lexicon file; "" = assets/keywords.txt
  // At most this many transitions out of a frame: the nearest of those that pass both prunings
  // among its candidates, the candidates_per_transition * max_transitions nearest frames under
  // its threshold. One rule at every reference length, so edges grow linearly with frames and
  // change smoothly with the reference's length. 0 = no bound (the paper's analysis, whose edges
  // grow as frames^2).
  // 4 and 32 (128 candidates): the ablation's sync, jerk and behaviour stay within their spread of
  // the unbounded analysis while the mean out-degree levels off with the reference's length (a
  // frame's candidates are mostly a few runs of consecutive frames, so a large candidate budget and
  // a small transition budget keep every frame's few distinct transitions). The figures:
  // docs/decisions.md (Parameters).
  int max_transitions = 4;
  int candidates_per_transition = 32;
  NeighbourSearch neighbours = NeighbourSearch::Auto;
  // Auto: the search runs to the end up to this many frames (8 min at 30 fps: every reference of
  // the paper's gets its exact candidates, the same in every build), and within the ann_checks
  // budget above, where the time of an exact search per frame keeps growing with the reference. The
  // budgeted search misses few candidates (its recall: docs/performance.md), so the edges do not
  // jump at this length.
  int exact_frames = 15000;
  // Approximate: frames examined per frame at most (whole leaves of 16 of the tree, nearest box
  // first); 0 = until exact. Under Auto this is the budget up to kAnnChecksFrames frames, and it
  // grows beyond them (kAnnChecksGrowth, below).
  int ann_checks = 2000;
  // The reference's up axis (engine/motion/up_axis.h): detected (auto) or given; clips are turned
  // into Y-up before anything is computed from them, and outputs back.
  UpChoice up = UpChoice::Auto;
  // The joints the lower body's path drives (engine/motion/body_layers.h); empty: found from the
  // skeleton's geometry (the root, the chain to where the legs part, the legs).
  std::vector<std::string> lower_joints;
};

// Auto's budget beyond an hour at 30 fps: ann_checks * (1 + kAnnChecksGrowth * log2(frames /
// kAnnChecksFrames)), a quarter more per doubling of the reference (graph/neighbours.h
// search_checks). A fixed budget loses recall as the tree grows; this keeps it about level for a
// cost per frame that grows with the log of the length, as the tree's depth does.
// docs/performance.md, "The k-d tree against FLANN", has the measurements.
inline constexpr int kAnnChecksFrames = 108000;
inline constexpr double kAnnChecksGrowth = 0.25;

// The build asks for the frames of each leaf of the k-d tree (16 neighbouring poses) together: one
// walk of the tree for the leaf, nearest box first, that examines at most kLeafWalkChecks times the
// per-frame budget above, and every frame of the leaf takes its members from every leaf the walk
// opens. A frame then sees more of the tree for less work than its own walk of the budget, and
// finds more of the exact candidates and edges (a missed candidate changes what pruning 2 keeps
// after it). Why 6: docs/performance.md, "Searching a leaf's frames together".
inline constexpr int kLeafWalkChecks = 6;

// The search reads each candidate's positions and velocity from a copy of the rows kept in the
// k-d tree's leaf order (a leaf's frames then lie side by side instead of across the whole
// reference), when that copy needs at most this many bytes. The copy is twice the positions (the
// velocities precomputed), so above the budget the frame-order rows are read instead: the graph is
// the same either way, bit for bit. 1 GiB holds 25 joints to 15 h and 55 joints to 7 h at 30 fps;
// what the copy saves: docs/performance.md.
inline constexpr long long kLeafOrderRowsBytes = 1LL << 30;

// Throws gmg::Error naming the first key out of range.
void graph_params_validate(const GraphParams& params);

}  // namespace gmg
