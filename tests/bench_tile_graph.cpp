// Benchmark helper: a graph many times as long as a built one, to measure how a reenactment's cost
// grows with the reference where building one that long takes too long (a 19 h reference).
//
//   build/bench_tile_graph --graph speaker.gmg --copies 19 -o speaker_x19.gmg
//
// The graph is repeated: every copy's clips, nodes, edges (targets moved to the copy), speech
// features, activity, key poses and reference facts are the original's, so the tiled graph has
// copies times the frames, key nodes and transitions, and a reenactment from it ranks, reads and
// plays a reference of that length. Its motion repeats, so it says nothing about quality, only about
// cost. The result is an ordinary graph file (graph_save; gmg reenact and gmg inspect read it).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "graph/graph_builder.h"
#include "graph/graph_io.h"
#include "graph/reference_facts.h"

namespace {

template <typename T>
gmg::Samples<T> repeated(const gmg::Samples<T>& s, int copies) {
  std::vector<T> out;
  out.reserve(s.size() * static_cast<std::size_t>(copies));
  for (int c = 0; c < copies; ++c) out.insert(out.end(), s.begin(), s.end());
  return out;
}

gmg::MotionGraph tile(const gmg::MotionGraph& g, int copies) {
  using namespace gmg;
  const std::size_t n = static_cast<std::size_t>(g.frame_count());
  MotionGraph t;
  t.params = g.params;
  t.motion = motion_rest(g.motion.skeleton, g.motion.fps, 0);
  t.motion.frame_count = g.frame_count() * copies;
  t.motion.rotations = repeated(g.motion.rotations, copies);
  t.motion.translations = repeated(g.motion.translations, copies);
  for (int c = 0; c < copies; ++c)
    for (const ClipInfo& clip : g.clips)
      t.clips.push_back(
          {clip.name + "#" + std::to_string(c), clip.first_frame + c * g.frame_count(), clip.frame_count});
  t.speech_dims = g.speech_dims;
  t.speech = repeated(g.speech, copies);
  t.activity = repeated(g.activity, copies);
  t.key_poses = repeated(g.key_poses, copies);
  t.capture = g.capture;
  t.capture.foot_flags = repeated(g.capture.foot_flags, copies);
  t.beat_cost = repeated(g.beat_cost, copies);
  t.body = g.body;
  t.body.expressions.clear();
  for (int c = 0; c < copies; ++c)
    t.body.expressions.insert(t.body.expressions.end(), g.body.expressions.begin(), g.body.expressions.end());
  const Samples<std::uint32_t>& rows = g.graph.row_starts();
  const Samples<GraphVertex>& columns = g.graph.targets();
  std::vector<NodeInfo> nodes;
  std::vector<std::uint32_t> rowstart;
  std::vector<GraphVertex> targets;
  std::vector<double> weights;
  const std::size_t e = columns.size();
  for (int c = 0; c < copies; ++c) {
    for (std::size_t f = 0; f < n; ++f) {
      nodes.push_back(g.graph[f]);
      rowstart.push_back(static_cast<std::uint32_t>(rows[f] + c * e));
    }
    for (std::size_t i = 0; i < e; ++i) {
      targets.push_back(static_cast<GraphVertex>(columns[i] + static_cast<std::size_t>(c) * n));
      weights.push_back(g.edge_weights[i]);
    }
  }
  rowstart.push_back(static_cast<std::uint32_t>(copies * e));
  t.graph = gmg::GraphStorage(std::move(nodes), std::move(rowstart), std::move(targets));
  t.edge_weights = Samples<double>(std::move(weights));
  index_graph(t);
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  std::string in, out;
  int copies = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--graph") in = argv[i + 1];
    if (a == "--copies") copies = std::atoi(argv[i + 1]);
    if (a == "-o") out = argv[i + 1];
  }
  if (in.empty() || out.empty() || copies < 1) {
    std::fprintf(stderr, "usage: bench_tile_graph --graph IN.gmg --copies N -o OUT.gmg\n");
    return 2;
  }
  try {
    const gmg::MotionGraph g = gmg::graph_load(in);
    const gmg::MotionGraph t = tile(g, copies);
    gmg::graph_save(out, t);
    std::printf("wrote %s: %d frames, %zu key nodes, %zu edges\n", out.c_str(), t.frame_count(), t.keys.size(),
                t.graph.edge_count());
  } catch (const gmg::Error& e) {
    std::fprintf(stderr, "bench_tile_graph: %s\n", e.what());
    return 1;
  }
  return 0;
}
