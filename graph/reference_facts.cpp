#include "graph/reference_facts.h"

#include "engine/motion/body_parts.h"
#include "engine/motion/spikes.h"
#include "graph/beats.h"

namespace gmg {

double mean_transition_weight(const MotionGraph& g) {
  double sum = 0.0;
  long count = 0;
  for (std::size_t f = 0; f < g.graph.vertex_count(); ++f)
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f)))
      if (!is_natural_edge(f, g.graph.target(e))) {
        sum += g.weight(e);
        ++count;
      }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

std::vector<int> graph_keys(const MotionGraph& g) { return g.indexed ? g.keys : g.key_frames(); }

CaptureRuns graph_runs(const MotionGraph& g) {
  if (g.indexed) return CaptureRuns(g.frame_count(), g.breaks);
  std::vector<int> breaks;
  for (int f = 0; f < g.frame_count(); ++f)
    if (g.node(f).kinds & kBreakNode) breaks.push_back(f);
  return CaptureRuns(g.frame_count(), std::move(breaks));
}

void index_graph(MotionGraph& g) {
  g.keys.clear();
  g.breaks.clear();
  for (int f = 0; f < g.frame_count(); ++f) {
    if (g.is_key(f)) g.keys.push_back(f);
    if (g.node(f).kinds & kBreakNode) g.breaks.push_back(f);
  }
  g.transition_weight = mean_transition_weight(g);
  g.indexed = true;
}

void add_reference_facts(MotionGraph& g) {
  index_graph(g);
  const CaptureRuns runs = graph_runs(g);
  g.capture = capture_facts(g.motion, runs);
  g.beat_cost = g.activity.size() == static_cast<std::size_t>(g.frame_count())
                    ? Samples<float>(beat_end_costs(g.activity, runs, g.motion.fps))
                    : Samples<float>();
  g.lower_joints = g.params.lower_joints;
  g.stance = stance_facts(g.motion, runs, graph_body_layers(g));
  g.spikes = jerk_spikes(g.motion, runs, upper_body_joints(g.motion.skeleton));
}

BodyLayers graph_body_layers(const MotionGraph& g) {
  return g.lower_joints.empty() ? find_body_layers(g.motion) : body_layers_from_names(g.motion, g.lower_joints);
}

}  // namespace gmg
