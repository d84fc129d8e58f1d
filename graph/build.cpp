#include "graph/build.h"

#include <cmath>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/motion/body_parts.h"
#include "graph/breaks.h"
#include "graph/continuity.h"
#include "graph/features.h"
#include "graph/graph_builder.h"
#include "graph/key_nodes.h"
#include "graph/key_poses.h"
#include "graph/reference_facts.h"

namespace gmg {

std::vector<int> MotionGraph::key_frames() const {
  std::vector<int> out;
  for (int f = 0; f < frame_count(); ++f)
    if (is_key(f)) out.push_back(f);
  return out;
}

namespace {

// Every clip against the first: one skeleton, one fps, at least 2 frames. Returns the total.
int check_clips(const std::vector<ClipEvents>& clips) {
  if (clips.empty()) throw Error("graph build: no reference clip given");
  const ClipEvents& first = clips.front();
  int total = 0;
  for (const ClipEvents& c : clips) {
    std::string why;
    if (!skeletons_match(first.motion.skeleton, c.motion.skeleton, &why))
      throw Error(c.name + ": skeleton differs from " + first.name + "'s: " + why);
    if (std::abs(c.motion.fps - first.motion.fps) > 1e-6)
      throw Error(c.name + ": " + std::to_string(c.motion.fps) + " fps differs from " + first.name + "'s " +
                  std::to_string(first.motion.fps) + " fps");
    if (c.motion.frame_count < 2) throw Error(c.name + ": a reference clip needs at least 2 frames");
    if (c.speech_dims != first.speech_dims)
      throw Error(c.name + ": has " + std::to_string(c.speech_dims) + " speech features per frame, " + first.name +
                  " has " + std::to_string(first.speech_dims));
    if (c.speech_dims < 0 || c.speech.size() != static_cast<std::size_t>(c.motion.frame_count) *
                                                    static_cast<std::size_t>(std::max(0, c.speech_dims)))
      throw Error(c.name + ": its speech features do not cover its frames");
    total += c.motion.frame_count;
  }
  return total;
}

// The pose features of clip m into columns [offset, offset + frames) of `out`, computed a piece
// at a time: pose_features of a whole hour holds several copies of it (forward kinematics, its
// transpose, the velocities). A piece starts one frame early so its first velocity is the
// clip's (v_t = p_t - p_{t-1}); the values are those of one pose_features call on the clip.
void clip_features(const Motion& m, int offset, PoseFeatures& out) {
  constexpr int kPiece = 4096;
  const std::size_t joints = static_cast<std::size_t>(m.joint_count());
  for (int first = 0; first < m.frame_count; first += kPiece) {
    const int from = std::max(0, first - 1), to = std::min(m.frame_count, first + kPiece);
    Motion piece = motion_rest(m.skeleton, m.fps, to - from);
    std::copy(m.rotations.begin() + static_cast<std::ptrdiff_t>(from * joints),
              m.rotations.begin() + static_cast<std::ptrdiff_t>(to * joints), piece.rotations.begin());
    std::copy(m.translations.begin() + static_cast<std::ptrdiff_t>(from * joints),
              m.translations.begin() + static_cast<std::ptrdiff_t>(to * joints), piece.translations.begin());
    const PoseFeatures f = pose_features(piece);
    out.positions.middleCols(offset + first, to - first) = f.positions.rightCols(to - first);
    out.velocities.middleCols(offset + first, to - first) = f.velocities.rightCols(to - first);
  }
}

// Per frame: the mean speed of `joints` (root-relative: the features' positions are, and their
// velocities are frame steps) over the median of it.
std::vector<float> upper_body_activity(const PoseFeatures& f, const std::vector<int>& joints) {
  const Eigen::Index n = f.velocities.cols();
  std::vector<float> out(static_cast<std::size_t>(n), 0.0f);
  if (joints.empty() || n == 0) return out;
  for (Eigen::Index t = 0; t < n; ++t) {
    double sum = 0.0;
    for (int j : joints) sum += f.velocities.block<3, 1>(3 * j, t).norm();
    out[static_cast<std::size_t>(t)] = static_cast<float>(sum / static_cast<double>(joints.size()));
  }
  std::vector<float> sorted = out;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const float median = sorted[sorted.size() / 2];
  for (float& a : out) a = median > 0.0f ? a / median : 0.0f;
  return out;
}

}  // namespace

MotionGraph graph_build(std::vector<ClipEvents> clips, const GraphParams& params, const BuildProgress& progress) {
  graph_params_validate(params);
  const int total = check_clips(clips);
  const Motion& first = clips.front().motion;
  MotionGraph g;
  g.params = params;
  g.motion = motion_rest(first.skeleton, first.fps, 0);
  g.motion.frame_count = total;
  g.speech_dims = clips.front().speech_dims;
  g.speech.reserve(static_cast<std::size_t>(total) * static_cast<std::size_t>(g.speech_dims));
  const std::size_t samples = static_cast<std::size_t>(total) * static_cast<std::size_t>(first.joint_count());
  if (clips.size() > 1) {
    g.motion.rotations.reserve(samples);
    g.motion.translations.reserve(samples);
  }
  PoseFeatures features;
  const Eigen::Index dims = 3 * static_cast<Eigen::Index>(first.joint_count());
  features.positions.resize(dims, total);
  features.velocities.resize(dims, total);
  GraphBuilder builder(total);

  int offset = 0;
  for (ClipEvents& c : clips) {
    const Motion& m = c.motion;
    g.clips.push_back({c.name, offset, m.frame_count});
    g.speech.insert(g.speech.end(), c.speech.begin(), c.speech.end());
    clip_features(m, offset, features);
    mark_key_nodes(builder.nodes(), offset, c,
                   capture_jump_frames(features.positions.middleCols(offset, m.frame_count), params));
    offset += m.frame_count;
    if (clips.size() == 1) {  // one clip: its samples are the graph's, no copy
      g.motion.rotations = std::move(c.motion.rotations);
      g.motion.translations = std::move(c.motion.translations);
    } else {
      g.motion.rotations.insert(g.motion.rotations.end(), m.rotations.begin(), m.rotations.end());
      g.motion.translations.insert(g.motion.translations.end(), m.translations.begin(), m.translations.end());
    }
    c.motion = Motion();  // release the clip's copy early
  }

  // Natural edges inside continuous runs; run_end (a run's last frame) for the analysis.
  std::vector<int> run_end(static_cast<std::size_t>(total));
  int end = total - 1;
  for (int f = total - 1; f >= 0; --f) {
    if (builder.node(f).kinds & kBreakNode) end = f;
    run_end[static_cast<std::size_t>(f)] = end;
  }
  for (int f = 0; f + 1 < total; ++f)
    if (!(builder.node(f).kinds & kBreakNode)) builder.add_edge(f, f + 1, EdgeInfo{0.0, true});

  if (g.has_speech()) g.activity = upper_body_activity(features, upper_body_joints(g.motion.skeleton));

  ContinuityProgress analysed;
  if (progress) analysed = [&](int done, int frames) { progress("analyse", done, frames); };
  for (const Transition& t : continuity_analysis(features, run_end, params, analysed))
    builder.add_edge(t.from, t.to, EdgeInfo{t.weight, false});
  g.graph = builder.finish();
  g.key_poses = key_junction_poses(g);
  add_reference_facts(g);
  return g;
}

}  // namespace gmg
