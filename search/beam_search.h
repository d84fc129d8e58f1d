// Beam search for one subsequence (paper 4.2.1, 4.2.2, A.1.2; SPEC "Beam search").
#pragma once

#include <string>
#include <vector>

#include "graph/motion_graph.h"
#include "search/params.h"
#include "search/reuse.h"
#include "search/segmentation.h"
#include "search/speech_match.h"

namespace gmg {

struct BeamRequest {
  std::vector<int> start_nodes;  // one-node paths the beam starts from (graph frames)
  int target_length = 1;         // l_sub (>= 1)
  Termination kind = Termination::Rhythm;
  std::string keyword;  // for Keyword termination
  int stop_frame = -1;  // for Frame termination
  // Frames whose stopping role is ignored (fallback 2); empty = none. Size 0 or frame_count.
  std::vector<char> ignore_stop;
  // Natural planner: a cost each start node's paths begin with (its junction cost); empty = 0.
  // Size 0 or start_nodes.size().
  std::vector<double> start_costs;
  // Natural planner: edge weights count as lambda_w * weight_scale * weight (1 / the graph's mean
  // transition weight, so one typical transition costs lambda_w whatever the length unit).
  double weight_scale = 1.0;
  // Natural planner: an unnatural edge may be taken only after this many frames of natural motion
  // since the path's start or its last unnatural edge (0: any time, the paper's beam).
  int min_run = 0;
  // Natural planner: the speech and reuse costs of a path, mean over its frames (frame i of a path
  // against test frame test_start + i; reuse at output frame `time`), times their weights. Null:
  // none.
  const SpeechMatch* speech = nullptr;
  double speech_weight = 0.0;
  double end_weight = 0.0;  // a terminated path also pays end_weight x speech->end_cost(its last frame)
  int test_start = 0;
  const ReuseTracker* reuse = nullptr;
  double reuse_weight = 0.0;
  int time = 0;
};

// One accepted path.
struct BeamCandidate {
  std::vector<int> path;  // graph frames
  double cost = 0.0;
};

struct BeamResult {
  bool accepted = false;  // a terminated path with 0.9 l_sub <= len <= 1.1 l_sub exists
  std::vector<int> path;  // the accepted path of lowest cost (graph frames), else empty
  double cost = 0.0;      // its cost
  int iterations = 0;     // beam extensions performed
  // Every accepted path of the final beam, by increasing cost (path/cost above is the first);
  // the natural planner draws among the near-equal ones.
  std::vector<BeamCandidate> candidates;
};

// True when frame `f` ends a path for this request (not considering the start node).
bool is_stop_node(const MotionGraph& g, int f, const BeamRequest& request);

// Runs the beam. Always ends: after max_length_factor * l_sub + 2 extensions at most.
BeamResult beam_search(const MotionGraph& g, const BeamRequest& request, const SearchParams& params);

// Path cost: lambda_w * sum of edge weights + lambda_len * |1 - len / l_sub| (plus the start cost
// of the path's start node, when the request gives one, and the speech and reuse costs).
double path_cost(double weight_sum, int length, int target_length, const SearchParams& params);

}  // namespace gmg
