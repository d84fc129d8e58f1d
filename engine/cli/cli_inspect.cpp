// `gmg inspect`: the counts of a built graph; DOT/GraphML exports.
#include <algorithm>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/limits.h"
#include "engine/face/face_track.h"
#include "graph/graph_io.h"
#include "graph/reference_facts.h"
#include "graph/stats.h"

namespace gmg {
namespace {

struct InspectArgs {
  std::string graph, dot, graphml, frames;
  bool json = false;
};

// --frames FROM:TO, frames FROM to TO - 1; either end may be left out (0, and -1 for the
// graph's end). Checked before the graph is read: a range that cannot mean anything is a usage
// error.
std::pair<int, int> parse_frame_range(const std::string& text) {
  if (text.empty()) return {0, -1};
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos)
    throw UsageError("--frames: '" + text + "' is not FROM:TO (e.g. 0:300)");
  auto end = [&](const std::string& part, int missing) {
    if (part.empty()) return missing;
    const bool digits = std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits)
      throw UsageError("--frames: '" + part + "' in '" + text + "' is not a frame number (a whole number, 0 or above)");
    const std::size_t first = std::min(part.find_first_not_of('0'), part.size() - 1);  // "007" is 7
    if (part.size() - first > 9 || std::stoi(part.substr(first)) > limits::kMaxFrames)
      throw UsageError("--frames: " + part + " in '" + text + "' is beyond the " + std::to_string(limits::kMaxFrames) +
                       " frames a graph can have");
    return std::stoi(part.substr(first));
  };
  const int from = end(text.substr(0, colon), 0), to = end(text.substr(colon + 1), -1);
  if (to >= 0 && from >= to)
    throw UsageError("--frames: " + text + " is empty: FROM (" + std::to_string(from) + ") must be below TO (" +
                     std::to_string(to) + ")");
  return {from, to};
}

// One count: its snake_case JSON key and its text label (SPEC "Command line": `onset nodes: 115`).
struct Count {
  const char* key;
  const char* label;
  nlohmann::ordered_json value;
};

// Frames where the lower body may change stance (both feet planted, hips slow); 0 without a stance.
long stance_frames(const MotionGraph& g) {
  long n = 0;
  for (std::size_t f = 0; f < g.stance.planted.size(); ++f) n += g.stance.planted[f];
  return n;
}

std::vector<Count> counts(const MotionGraph& g) {
  const GraphStats s = graph_stats(g);
  return {{"frames", "frames", s.frames},
          {"clips", "clips", s.clips},
          {"fps", "fps", g.motion.fps},
          {"joints", "joints", g.motion.joint_count()},
          {"onset_nodes", "onset nodes", s.onset_nodes},
          {"keyword_nodes", "keyword nodes", s.keyword_nodes},
          {"break_nodes", "break nodes", s.break_nodes},
          {"key_nodes", "key nodes", s.key_nodes},
          {"natural_edges", "natural edges", s.natural_edges},
          {"unnatural_edges", "unnatural edges", s.unnatural_edges},
          {"mean_out_degree", "mean out-degree", s.mean_out_degree},
          {"share_with_transition", "frames with a transition", s.share_with_transition},
          {"shortest_subsequence", "shortest subsequence", s.shortest_subsequence},
          {"longest_subsequence", "longest subsequence", s.longest_subsequence},
          {"up_axis", "up axis", enum_name(kUpAxisNames, g.up)},
          {"stance_frames", "stance frames", stance_frames(g)},
          {"layers", "layers", describe_body_layers(g.motion.skeleton, graph_body_layers(g))},
          {"face", "face", face_track_summary(g)}};
}

void run_inspect(const InspectArgs& a) {
  auto [from, to] = parse_frame_range(a.frames);
  check_output_extensions({{"--dot", a.dot, {".dot", ".gv"}}, {"--graphml", a.graphml, {".graphml", ".xml"}}});
  check_outputs_apart({{"--dot", a.dot}, {"--graphml", a.graphml}}, {{"graph", a.graph}});
  check_outputs({{"--dot", a.dot, {".dot", ".gv"}}, {"--graphml", a.graphml, {".graphml", ".xml"}}});
  OutputTransaction outputs;
  const MotionGraph g = graph_load(a.graph);
  if (to < 0) to = g.frame_count();
  if ((!a.dot.empty() || !a.graphml.empty()) && (from >= g.frame_count() || to > g.frame_count()))
    throw Error(a.graph + ": --frames " + a.frames + " reaches past its " + std::to_string(g.frame_count()) +
                " frames (0:" + std::to_string(g.frame_count()) + ")");
  const std::vector<Count> c = counts(g);
  if (a.json) {
    nlohmann::ordered_json j;
    for (const Count& k : c) j[k.key] = k.value;
    std::cout << json_dump(j, -1) << "\n";
  } else {
    for (const Count& k : c) std::cout << k.label << ": " << json_dump(k.value, -1) << "\n";
    for (const ClipInfo& clip : g.clips)
      std::cout << "clip: " << clip.name << " (frames " << clip.first_frame << ".."
                << clip.first_frame + clip.frame_count - 1 << ")\n";
  }
  if (!a.dot.empty()) graph_write_dot(a.dot, g, from, to);
  if (!a.graphml.empty()) graph_write_graphml(a.graphml, g, from, to);
  g.check_unchanged();
  outputs.commit();
}

}  // namespace

void add_inspect_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("inspect", "print the counts of a built graph; export DOT/GraphML");
  auto a = std::make_shared<InspectArgs>();
  cmd->add_option("graph", a->graph, "graph file")->required();
  cmd->add_flag("--json", a->json, "print one JSON object");
  cmd->add_option("--dot", a->dot, "write GraphViz DOT of the frame range");
  cmd->add_option("--graphml", a->graphml, "write GraphML of the frame range");
  cmd->add_option("--frames", a->frames, "frame range FROM:TO for the exports (default: all)");
  cmd->callback([a] { run_inspect(*a); });
}

}  // namespace gmg
