#include "graph/key_nodes.h"

#include "engine/core/error.h"

namespace gmg {

void mark_key_nodes(std::vector<NodeInfo>& nodes, int offset, const ClipEvents& clip,
                    const std::vector<int>& capture_jumps) {
  const int frames = clip.motion.frame_count;
  auto node = [&](int f) -> NodeInfo& { return nodes.at(static_cast<std::size_t>(offset + f)); };
  for (int b : capture_jumps) node(b).kinds |= kBreakNode;
  node(frames - 1).kinds |= kBreakNode;
  for (int f : clip.onset_frames) {
    if (f < 0 || f >= frames) throw Error(clip.name + ": onset frame " + std::to_string(f) + " outside the clip");
    node(f).kinds |= kOnsetNode;
  }
  for (const auto& [f, word] : clip.keyword_frames) {
    if (f < 0 || f >= frames) throw Error(clip.name + ": keyword frame " + std::to_string(f) + " outside the clip");
    NodeInfo& n = node(f);
    if (n.kinds & kKeywordNode) continue;  // one label per node: the first keyword wins
    n.kinds |= kKeywordNode;
    n.keyword = word;
  }
}

}  // namespace gmg
