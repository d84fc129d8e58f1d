// The per-reference values of a graph (MotionGraph: keys, breaks, transition_weight, capture,
// beat_cost): what a reenactment would otherwise recompute from every frame or edge of the
// reference, computed once when the graph is built (and the index and the transition scale again
// when it is loaded, from the nodes and edges the load reads anyway), so that a reenactment reads
// only the key poses and the frames of its paths.
#pragma once

#include <vector>

#include "engine/motion/body_layers.h"
#include "engine/motion/capture_runs.h"
#include "graph/motion_graph.h"

namespace gmg {

// Fills every per-reference value of g from its nodes, edges, motion and activity (the end of
// graph_build).
void add_reference_facts(MotionGraph& g);

// The key and break frames and the transition weight (MotionGraph::keys, breaks,
// transition_weight; indexed) from the nodes and edges.
void index_graph(MotionGraph& g);

// The layers of g's body (engine/motion/body_layers.h): named by g.lower_joints, else found from
// its skeleton.
BodyLayers graph_body_layers(const MotionGraph& g);

// The mean weight of the unnatural edges, summed in edge order; 0 without any.
double mean_transition_weight(const MotionGraph& g);

// The key frames, ascending: the index when the graph has one, else a scan of the nodes.
std::vector<int> graph_keys(const MotionGraph& g);

// The capture runs of the motion (breaks at the break nodes): from the index when there is one.
CaptureRuns graph_runs(const MotionGraph& g);

}  // namespace gmg
