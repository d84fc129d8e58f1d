// Graph construction (paper 4.1): the steps of graph/ in order.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "graph/motion_graph.h"
#include "graph/params.h"

namespace gmg {

// Told how a build advances: a stage ("read": clips read, "analyse": frames whose transitions
// are known) and (done, total) in its units. Called from the building thread.
using BuildProgress = std::function<void(const std::string& stage, long done, long total)>;

// Builds a graph from clips handed over one at a time, in order, so that hours of reference are
// never all in memory at once: each clip's motion joins the graph's (in a temporary file in
// `spill_folder` once it outgrows memory; "" keeps it in memory), and what the analysis needs of
// it is taken at once (its key nodes, break nodes, thresholds, pose features: graph/features.h,
// graph/pose_space.h). Clips share one skeleton and fps and have >= 2 frames each (gmg::Error
// otherwise, naming the clip). finish() runs the continuity analysis with both prunings (SPEC "Key
// nodes" and "Edges") and gives the graph. The params are validated first.
class GraphBuild {
 public:
  // Past this many bytes an array (the motion's rotations or translations, the key nodes' junction
  // poses, the double positions of graph/features.h) goes to the spill folder.
  static constexpr std::size_t kMemoryLimit = std::size_t{256} << 20;
  explicit GraphBuild(const GraphParams& params, std::string spill_folder = "",
                      std::size_t memory_limit = kMemoryLimit);
  ~GraphBuild();
  GraphBuild(const GraphBuild&) = delete;
  GraphBuild& operator=(const GraphBuild&) = delete;

  void add(ClipEvents clip);
  MotionGraph finish(const BuildProgress& progress = {});

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// All at once: GraphBuild with every clip, in order.
MotionGraph graph_build(std::vector<ClipEvents> clips, const GraphParams& params, const BuildProgress& progress = {},
                        const std::string& spill_folder = "");

}  // namespace gmg
