#include "graph/build.h"

#include <cmath>

#include <algorithm>
#include <optional>

#include "engine/core/error.h"
#include "engine/core/limits.h"
#include "engine/core/spill.h"
#include "engine/motion/body_parts.h"
#include "graph/breaks.h"
#include "graph/continuity.h"
#include "graph/features.h"
#include "graph/graph_builder.h"
#include "graph/key_nodes.h"
#include "graph/key_poses.h"
#include "graph/pose_space.h"
#include "graph/reference_facts.h"

namespace gmg {

std::vector<int> MotionGraph::key_frames() const {
  std::vector<int> out;
  for (int f = 0; f < frame_count(); ++f)
    if (is_key(f)) out.push_back(f);
  return out;
}

namespace {

// Per frame: the mean speed of `joints` (root-relative: the features' positions are, and their
// velocities are frame steps), appended to `out`; graph-wide it is then divided by its median.
void append_upper_body_speed(const PoseFeatures& f, const std::vector<int>& joints, std::vector<float>& out) {
  for (Eigen::Index t = 0; t < f.velocities.cols(); ++t) {
    double sum = 0.0;
    for (int j : joints) sum += f.velocities.block<3, 1>(3 * static_cast<Eigen::Index>(j), t).norm();
    out.push_back(joints.empty() ? 0.0f : static_cast<float>(sum / static_cast<double>(joints.size())));
  }
}

void divide_by_median(std::vector<float>& values) {
  if (values.empty()) return;
  std::vector<float> sorted = values;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const float median = sorted[sorted.size() / 2];
  for (float& a : values) a = median > 0.0f ? a / median : 0.0f;
}

// One array of motion samples, in memory or spilled.
template <typename T>
Samples<T> finish_samples(SpillFile& spill) {
  const SpillFile::Bytes b = spill.finish();
  return Samples<T>::view(reinterpret_cast<const T*>(b.data), b.size / sizeof(T), b.owner);
}

}  // namespace

struct GraphBuild::State {
  GraphParams params;
  std::string spill_folder;
  std::size_t memory_limit = 0;
  std::string first_name;
  MotionGraph g;
  std::optional<Motion> only;  // the first clip's samples, moved in, while it is the only one
  std::unique_ptr<SpillFile> rotations, translations;
  std::unique_ptr<FeatureStore> store;
  std::unique_ptr<neighbours::PoseSpace> space;
  std::vector<double> theta;
  std::vector<NodeInfo> nodes;
  std::vector<float> speed;
  std::vector<int> upper_body;
  std::vector<double> clip_key_poses;
  std::unique_ptr<SpillFile> key_poses;  // 6 values a joint a key node: 0.7 GB at 19 h of 55 joints
  int frames = 0;

  void check(const ClipEvents& c) const {
    const Motion& first = g.motion;
    std::string why;
    if (!skeletons_match(first.skeleton, c.motion.skeleton, &why))
      throw Error(c.name + ": skeleton differs from " + first_name + "'s: " + why);
    if (std::abs(c.motion.fps - first.fps) > 1e-6)
      throw Error(c.name + ": " + std::to_string(c.motion.fps) + " fps differs from " + first_name + "'s " +
                  std::to_string(first.fps) + " fps");
  }

  // The samples so far into the spill files (from the second clip on, the motion is appended).
  void start_appending() {
    rotations = std::make_unique<SpillFile>(spill_folder, memory_limit);
    translations = std::make_unique<SpillFile>(spill_folder, memory_limit);
    if (only) {
      append_samples(*only);
      only.reset();
    }
  }

  void append_samples(const Motion& m) {
    rotations->append(m.rotations.data(), m.rotations.size() * sizeof(glm::dquat));
    translations->append(m.translations.data(), m.translations.size() * sizeof(glm::dvec3));
  }
};

GraphBuild::GraphBuild(const GraphParams& params, std::string spill_folder, std::size_t memory_limit)
    : s_(std::make_unique<State>()) {
  graph_params_validate(params);
  s_->params = params;
  s_->spill_folder = std::move(spill_folder);
  s_->memory_limit = memory_limit;
  s_->g.params = params;
}

GraphBuild::~GraphBuild() = default;

void GraphBuild::add(ClipEvents c) {
  State& s = *s_;
  if (c.motion.frame_count < 2) throw Error(c.name + ": a reference clip needs at least 2 frames");
  if (s.g.clips.empty()) {
    s.first_name = c.name;
    s.g.up = c.up;
    s.g.motion = motion_rest(c.motion.skeleton, c.motion.fps, 0);
    s.g.speech_dims = c.speech_dims;
    const int dims = 3 * c.motion.joint_count();
    s.store = std::make_unique<FeatureStore>(dims, s.spill_folder, s.memory_limit);
    s.space = std::make_unique<neighbours::PoseSpace>(*s.store, s.params);
    s.upper_body = upper_body_joints(c.motion.skeleton);
    s.key_poses = std::make_unique<SpillFile>(s.spill_folder, s.memory_limit);
  } else {
    s.check(c);
    if (c.up != s.g.up)
      throw Error(c.name + ": is " + enum_name(kUpAxisNames, c.up) + "-up but " + s.first_name + " is " +
                  enum_name(kUpAxisNames, s.g.up) + "-up (one graph needs one up axis: give --set up=y or up=z)");
  }
  if (c.speech_dims != s.g.speech_dims)
    throw Error(c.name + ": has " + std::to_string(c.speech_dims) + " speech features per frame, " + s.first_name +
                " has " + std::to_string(s.g.speech_dims));
  const Motion& m = c.motion;
  if (c.speech_dims < 0 ||
      c.speech.size() != static_cast<std::size_t>(m.frame_count) * static_cast<std::size_t>(std::max(0, c.speech_dims)))
    throw Error(c.name + ": its speech features do not cover its frames");
  if (static_cast<long long>(s.frames) + m.frame_count > limits::kMaxFrames)
    throw Error(c.name + ": the reference would have more than " + std::to_string(limits::kMaxFrames) + " frames");

  const int offset = s.frames;
  s.g.clips.push_back({c.name, offset, m.frame_count});
  s.g.speech.vec().insert(s.g.speech.vec().end(), c.speech.begin(), c.speech.end());
  const PoseFeatures f = clip_features(m);
  s.nodes.resize(static_cast<std::size_t>(offset + m.frame_count));
  mark_key_nodes(s.nodes, offset, c, capture_jump_frames(f.positions, s.params));
  // Runs end at break nodes (and the clip's end): each frame's threshold from its own run.
  std::vector<int> run_end(static_cast<std::size_t>(m.frame_count));
  int end = m.frame_count - 1;
  for (int i = m.frame_count - 1; i >= 0; --i) {
    if (s.nodes[static_cast<std::size_t>(offset + i)].kinds & kBreakNode) end = i;
    run_end[static_cast<std::size_t>(i)] = end;
  }
  const std::vector<double> theta = continuity_thresholds(f, run_end, s.params);
  s.theta.insert(s.theta.end(), theta.begin(), theta.end());
  s.store->add_clip(f);
  s.space->add_clip(f);
  if (c.speech_dims > 0) append_upper_body_speed(f, s.upper_body, s.speed);
  s.clip_key_poses.clear();
  append_key_junction_poses(m, s.nodes, offset, s.clip_key_poses);
  s.key_poses->append(s.clip_key_poses.data(), s.clip_key_poses.size() * sizeof(double));
  s.frames += m.frame_count;

  if (s.g.clips.size() == 1) {
    s.only = std::move(c.motion);  // one clip: its samples are the graph's, no copy
  } else {
    if (!s.rotations) s.start_appending();
    s.append_samples(m);
  }
}

MotionGraph GraphBuild::finish(const BuildProgress& progress) {
  State& s = *s_;
  if (s.g.clips.empty()) throw Error("graph build: no reference clip given");
  MotionGraph g = std::move(s.g);
  g.motion.frame_count = s.frames;
  if (s.only) {
    g.motion.rotations = std::move(s.only->rotations);
    g.motion.translations = std::move(s.only->translations);
    s.only.reset();
  } else {
    g.motion.rotations = finish_samples<glm::dquat>(*s.rotations);
    g.motion.translations = finish_samples<glm::dvec3>(*s.translations);
  }
  if (g.has_speech()) {
    divide_by_median(s.speed);
    g.activity = std::move(s.speed);
  }
  g.key_poses = finish_samples<double>(*s.key_poses);
  g.key_sketch = key_pose_sketch(g.key_poses, junction_pose_dims(g.motion.skeleton));

  // Natural edges inside continuous runs, then the analysis's.
  GraphBuilder builder(std::move(s.nodes));
  for (int f = 0; f + 1 < s.frames; ++f)
    if (!(builder.node(f).kinds & kBreakNode)) builder.add_edge(f, f + 1, EdgeInfo{0.0});
  s.store->finish();
  s.space->finish();
  ContinuityProgress analysed;
  if (progress) analysed = [&](int done, int frames) { progress("analyse", done, frames); };
  const std::vector<Transition> transitions = continuity_analysis(std::move(*s.space), s.theta, s.params, analysed);
  for (const Transition& t : transitions) builder.add_edge(t.from, t.to, EdgeInfo{t.weight});
  builder.finish(g);
  add_reference_facts(g);
  return g;
}

MotionGraph graph_build(std::vector<ClipEvents> clips, const GraphParams& params, const BuildProgress& progress,
                        const std::string& spill_folder) {
  GraphBuild build(params, spill_folder);
  for (ClipEvents& c : clips) {
    build.add(std::move(c));
    c = ClipEvents();  // release the clip's copy early
  }
  return build.finish(progress);
}

}  // namespace gmg
