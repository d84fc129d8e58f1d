#include "search/beam_search.h"

#include <algorithm>
#include <cmath>

namespace gmg {

bool is_stop_node(const MotionGraph& g, int f, const BeamRequest& request) {
  if (!request.ignore_stop.empty() && request.ignore_stop[static_cast<std::size_t>(f)]) return false;
  const NodeInfo& n = g.node(f);
  if (request.kind == Termination::Frame) return f == request.stop_frame;
  if (request.kind == Termination::Keyword) return (n.kinds & kKeywordNode) && n.keyword == request.keyword;
  return (n.kinds & (kOnsetNode | kBreakNode)) != 0;
}

double path_cost(double weight_sum, int length, int target_length, const SearchParams& params) {
  return params.lambda_w * weight_sum +
         params.lambda_len * std::abs(1.0 - static_cast<double>(length) / static_cast<double>(target_length));
}

namespace {

// Paths share prefixes: each beam entry points at a node of this tree of extensions, so an
// extension costs O(1) instead of copying the path.
struct TreeNode {
  int frame;
  int parent;  // index in the tree, -1 for a start node
};

struct Entry {
  int tree;           // last node of the path, in the tree
  int length;         // nodes in the path
  double weight_sum;  // sum of edge weights along it
  double start_cost;  // what the start node cost (junction cost; 0 in the paper's planner)
  double extra_sum;   // sum over its frames of the weighted speech costs
  double reuse_max;   // the most recently replayed of its frames: its weighted reuse cost
  int run;            // frames since its start or its last unnatural edge
  double cost;
  bool terminated;
};

// The weighted speech cost of frame `index` of a path being `frame`.
double extra_cost(const BeamRequest& r, int index, int frame) {
  return r.speech && r.speech_weight > 0.0 ? r.speech_weight * r.speech->frame_cost(r.test_start + index, frame) : 0.0;
}

// The weighted reuse cost of that frame.
double reuse_cost(const BeamRequest& r, int index, int frame) {
  return r.reuse && r.reuse_weight > 0.0 ? r.reuse_weight * r.reuse->frame_cost(frame, r.time + index) : 0.0;
}

// The `width` lowest entries, sorted: a partial sort, since each step extends l_npaths paths by
// every out-edge (thousands of entries on a large graph) to keep l_npaths of them.
template <typename Less>
void keep_lowest(std::vector<Entry>& entries, std::size_t width, const Less& less) {
  if (entries.size() > width) {
    std::partial_sort(entries.begin(), entries.begin() + static_cast<std::ptrdiff_t>(width), entries.end(), less);
    entries.resize(width);
  } else {
    std::sort(entries.begin(), entries.end(), less);
  }
}

}  // namespace

BeamResult beam_search(const MotionGraph& g, const BeamRequest& request, const SearchParams& params) {
  BeamResult result;
  const int target = std::max(1, request.target_length);
  const int min_len = static_cast<int>(std::ceil(0.9 * target - 1e-9));
  const int max_len = static_cast<int>(std::floor(1.1 * target + 1e-9));
  const int max_iterations = static_cast<int>(params.max_length_factor * target) + 2;
  const std::size_t width = static_cast<std::size_t>(std::max(1, params.l_npaths));

  std::vector<TreeNode> tree;
  std::vector<Entry> beam;
  for (std::size_t k = 0; k < request.start_nodes.size(); ++k) {
    tree.push_back({request.start_nodes[k], -1});
    const double start = request.start_costs.empty() ? 0.0 : request.start_costs[k];
    const double extra = extra_cost(request, 0, request.start_nodes[k]);
    const double reuse = reuse_cost(request, 0, request.start_nodes[k]);
    beam.push_back({static_cast<int>(tree.size()) - 1, 1, 0.0, start, extra, reuse, 1,
                    start + extra + reuse + path_cost(0.0, 1, target, params), false});
  }
  auto accepted = [&](const Entry& e) { return e.terminated && e.length >= min_len && e.length <= max_len; };
  auto by_cost = [](const Entry& a, const Entry& b) {
    if (a.cost != b.cost) return a.cost < b.cost;
    return a.tree < b.tree;  // deterministic ties: older paths first
  };
  keep_lowest(beam, width, by_cost);

  // A one-frame target is met by the start node itself.
  if (target == 1 && !beam.empty()) {
    result.accepted = true;
    result.path = {tree[static_cast<std::size_t>(beam.front().tree)].frame};
    result.cost = beam.front().cost;
    result.candidates.push_back({result.path, result.cost});
    return result;
  }

  std::vector<Entry> next;
  for (int it = 0; it < max_iterations && !beam.empty(); ++it) {
    const bool all_accepted = std::all_of(beam.begin(), beam.end(), accepted);
    // An unterminated path can still become accepted only while it is shorter than max_len.
    const bool extensible =
        std::any_of(beam.begin(), beam.end(), [&](const Entry& e) { return !e.terminated && e.length < max_len; });
    if (all_accepted || !extensible) break;
    next.clear();
    for (const Entry& e : beam) {
      if (e.terminated || e.length >= max_len) {
        next.push_back(e);  // terminated paths go to the watch list as they are
        continue;
      }
      const int frame = tree[static_cast<std::size_t>(e.tree)].frame;
      for (const GraphEdge out : g.graph.out_edges(static_cast<GraphVertex>(frame))) {
        const int child = static_cast<int>(g.graph.target(out));
        const bool natural = is_natural_edge(static_cast<std::size_t>(frame), static_cast<std::size_t>(child));
        // No transition before the path has dwelt min_run frames, and none back into the stretch
        // it is playing (a loop that replays what was just shown).
        if (!natural && request.min_run > 0 &&
            (e.run < request.min_run || (child <= frame && child > frame - e.run - 1)))
          continue;
        tree.push_back({child, e.tree});
        Entry x;
        x.tree = static_cast<int>(tree.size()) - 1;
        x.length = e.length + 1;
        x.weight_sum = e.weight_sum + request.weight_scale * g.weight(out);
        x.start_cost = e.start_cost;
        x.extra_sum = e.extra_sum + extra_cost(request, e.length, child);
        x.reuse_max = std::max(e.reuse_max, reuse_cost(request, e.length, child));
        x.run = natural ? e.run + 1 : 1;
        x.terminated = is_stop_node(g, child, request);
        if (x.terminated && request.speech && request.end_weight > 0.0)
          x.start_cost += request.end_weight * request.speech->end_cost(child);
        x.cost =
            x.start_cost + x.extra_sum / x.length + x.reuse_max + path_cost(x.weight_sum, x.length, target, params);
        next.push_back(x);
      }
    }
    keep_lowest(next, width, by_cost);
    beam.swap(next);
    ++result.iterations;
  }

  std::vector<const Entry*> accepted_entries;
  for (const Entry& e : beam)
    if (accepted(e)) accepted_entries.push_back(&e);
  if (accepted_entries.empty()) return result;
  std::sort(accepted_entries.begin(), accepted_entries.end(),
            [&](const Entry* a, const Entry* b) { return by_cost(*a, *b); });
  for (const Entry* e : accepted_entries) {
    BeamCandidate c;
    c.cost = e->cost;
    for (int t = e->tree; t >= 0; t = tree[static_cast<std::size_t>(t)].parent)
      c.path.push_back(tree[static_cast<std::size_t>(t)].frame);
    std::reverse(c.path.begin(), c.path.end());
    result.candidates.push_back(std::move(c));
  }
  result.accepted = true;
  result.path = result.candidates.front().path;
  result.cost = result.candidates.front().cost;
  return result;
}

}  // namespace gmg
