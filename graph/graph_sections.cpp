#include "graph/graph_sections.h"

#include <cmath>
#include <string>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "engine/motion/body_parts.h"
#include "graph/graph_builder.h"

namespace gmg {

void write_params(ArchiveWriter& w, const GraphParams& p) {
  w.pod(p.lambda_pos);
  w.pod(p.lambda_vel);
  w.pod<std::int32_t>(p.l_cn);
  w.pod<std::int32_t>(p.l_pn);
  w.pod<std::uint8_t>(p.exclude_near ? 1 : 0);
  w.pod(p.min_onset_strength);
  w.pod(p.break_jump_factor);
  w.str(p.keywords);
  w.pod<std::int32_t>(p.max_transitions);
  w.pod<std::int32_t>(p.candidates_per_transition);
  w.pod<std::uint8_t>(static_cast<std::uint8_t>(p.neighbours));
  w.pod<std::int32_t>(p.exact_frames);
  w.pod<std::int32_t>(p.ann_checks);
}

GraphParams read_params(ArchiveReader& r) {
  GraphParams p;
  p.lambda_pos = r.pod<double>();
  p.lambda_vel = r.pod<double>();
  p.l_cn = r.pod<std::int32_t>();
  p.l_pn = r.pod<std::int32_t>();
  p.exclude_near = r.pod<std::uint8_t>() != 0;
  p.min_onset_strength = r.pod<double>();
  p.break_jump_factor = r.pod<double>();
  p.keywords = r.str();
  p.max_transitions = r.pod<std::int32_t>();
  p.candidates_per_transition = r.pod<std::int32_t>();
  const std::uint8_t mode = r.pod<std::uint8_t>();
  if (mode > static_cast<std::uint8_t>(NeighbourSearch::Approximate)) r.fail("unknown neighbour search");
  p.neighbours = static_cast<NeighbourSearch>(mode);
  p.exact_frames = r.pod<std::int32_t>();
  p.ann_checks = r.pod<std::int32_t>();
  try {
    graph_params_validate(p);
  } catch (const Error& e) {
    r.fail(std::string("its build parameters are out of range (") + e.what() + ")");
  }
  return p;
}

void write_skeleton(ArchiveWriter& w, const Skeleton& sk) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(sk.joint_count()));
  for (const Joint& j : sk.joints) {
    w.str(j.name);
    w.pod<std::int32_t>(j.parent);
    w.pod(j.offset);
    std::vector<std::uint8_t> channels;
    for (Channel c : j.channels) channels.push_back(static_cast<std::uint8_t>(c));
    w.vec(channels);
    w.pod<std::uint8_t>(j.has_end_site ? 1 : 0);
    w.pod(j.end_site);
  }
}

namespace {

Joint read_joint(ArchiveReader& r, std::uint32_t i, std::vector<int>& depth) {
  Joint j;
  j.name = r.str();
  j.parent = r.pod<std::int32_t>();
  if (j.parent >= static_cast<int>(i) || (i > 0 && j.parent < 0) || (i == 0 && j.parent != -1))
    r.fail("joint hierarchy out of order");
  depth.push_back(j.parent < 0 ? 1 : depth[static_cast<std::size_t>(j.parent)] + 1);
  if (depth.back() > limits::kMaxHierarchyDepth) r.fail("joints nested too deep");
  j.offset = r.pod<glm::dvec3>();
  bool seen[6] = {false, false, false, false, false, false};
  for (std::uint8_t c : r.vec<std::uint8_t>()) {
    if (c > 5 || seen[c]) r.fail("unknown or repeated channel");
    seen[c] = true;
    j.channels.push_back(static_cast<Channel>(c));
  }
  j.rotation_order = rotation_order_from_channels(j.channels);
  j.has_end_site = r.pod<std::uint8_t>() != 0;
  j.end_site = r.pod<glm::dvec3>();
  if (!std::isfinite(j.offset.x + j.offset.y + j.offset.z + j.end_site.x + j.end_site.y + j.end_site.z))
    r.fail("a joint offset is not finite");
  return j;
}

}  // namespace

Skeleton read_skeleton(ArchiveReader& r) {
  Skeleton sk;
  const std::uint32_t joints = r.pod<std::uint32_t>();
  if (joints == 0 || joints > static_cast<std::uint32_t>(limits::kMaxJoints)) r.fail("implausible joint count");
  std::vector<int> depth;
  for (std::uint32_t i = 0; i < joints; ++i) sk.joints.push_back(read_joint(r, i, depth));
  return sk;
}

void write_clips(ArchiveWriter& w, const std::vector<ClipInfo>& clips) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(clips.size()));
  for (const ClipInfo& c : clips) {
    w.str(c.name);
    w.pod<std::int32_t>(c.first_frame);
    w.pod<std::int32_t>(c.frame_count);
  }
}

std::vector<ClipInfo> read_clips(ArchiveReader& r, long long& covered) {
  std::vector<ClipInfo> clips;
  const std::uint32_t count = r.pod<std::uint32_t>();
  covered = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    ClipInfo c;
    c.name = r.str();
    c.first_frame = r.pod<std::int32_t>();
    c.frame_count = r.pod<std::int32_t>();
    if (c.first_frame != covered || c.frame_count < 1 || covered + c.frame_count > limits::kMaxFrames)
      r.fail("clip table inconsistent");
    covered += c.frame_count;
    clips.push_back(c);
  }
  return clips;
}

void write_motion_header(ArchiveWriter& w, const Motion& m) {
  w.pod(m.fps);
  w.pod<std::int32_t>(m.frame_count);
}

void read_motion_header(ArchiveReader& r, Motion& m) {
  m.fps = r.pod<double>();
  m.frame_count = r.pod<std::int32_t>();
  if (!(m.fps >= limits::kMinFps && m.fps <= limits::kMaxFps))
    r.fail("frame rate " + format_number(m.fps) + " is outside " + format_number(limits::kMinFps) + " to " +
           format_number(limits::kMaxFps) + " fps");
  if (m.frame_count < 1 || m.frame_count > limits::kMaxFrames) r.fail("invalid frame count");
}

void write_nodes(ArchiveWriter& w, const MotionGraph& g) {
  const std::size_t n = static_cast<std::size_t>(g.frame_count());
  w.vec_of<std::uint8_t>(n, [&](std::size_t f) { return g.graph[f].kinds; });
  std::uint32_t labels = 0;
  for (std::size_t f = 0; f < n; ++f) labels += g.graph[f].keyword.empty() ? 0 : 1;
  w.pod(labels);
  for (std::size_t f = 0; f < n; ++f)
    if (!g.graph[f].keyword.empty()) {
      w.pod<std::uint32_t>(static_cast<std::uint32_t>(f));
      w.str(g.graph[f].keyword.str());
    }
}

std::vector<NodeInfo> read_nodes(ArchiveReader& r, std::size_t frames, MotionGraph& g) {
  std::vector<NodeInfo> nodes = huge_vector<NodeInfo>(frames);
  if (r.count<std::uint8_t>() != frames) r.fail("node count disagrees with the motion");
  bool unknown = false;
  r.items<std::uint8_t>(frames, [&](std::size_t f, std::uint8_t kinds) {
    nodes[f].kinds = kinds;
    unknown = unknown || (kinds & ~(kOnsetNode | kKeywordNode | kBreakNode)) != 0;
    if (kinds != 0) g.keys.push_back(static_cast<int>(f));
    if (kinds & kBreakNode) g.breaks.push_back(static_cast<int>(f));
  });
  g.indexed = true;
  if (unknown) r.fail("a node has unknown kinds");
  const std::uint32_t labels = r.pod<std::uint32_t>();
  std::int64_t previous = -1;
  for (std::uint32_t i = 0; i < labels; ++i) {
    const std::uint32_t f = r.pod<std::uint32_t>();
    if (f >= frames || static_cast<std::int64_t>(f) <= previous || !(nodes[f].kinds & kKeywordNode))
      r.fail("keyword label on a frame that is not a keyword node");
    previous = f;
    nodes[f].keyword = r.str();
    if (nodes[f].keyword.empty()) r.fail("empty keyword label");
  }
  for (const NodeInfo& n : nodes)
    if ((n.kinds & kKeywordNode) && n.keyword.empty()) r.fail("a keyword node has no label");
  return nodes;
}

void write_edges(ArchiveWriter& w, const MotionGraph& g, std::uint32_t version) {
  const Samples<std::uint32_t>& rows = g.graph.row_starts();
  const Samples<GraphVertex>& targets = g.graph.targets();
  const std::size_t e = targets.size();
  if (version >= 10) {
    w.aligned(rows);
    w.aligned(targets);
  } else {
    w.vec_of<std::uint32_t>(rows.size(), [&](std::size_t i) { return rows[i]; });
    w.vec_of<std::uint32_t>(e, [&](std::size_t i) { return targets[i]; });
  }
  if (version >= 9)
    w.aligned(g.edge_weights);
  else
    w.vec_of<double>(e, [&](std::size_t i) { return g.edge_weights[i]; });
  // Each edge's natural flag (is_natural_edge: derived, kept in the file so that a reader need not
  // know the rule).
  std::vector<std::uint8_t> natural(e);
  for (std::size_t f = 0; f + 1 < rows.size(); ++f)
    for (std::size_t i = rows[f]; i < rows[f + 1]; ++i) natural[i] = is_natural_edge(f, targets[i]) ? 1 : 0;
  w.vec(natural);
}

void read_edges(ArchiveReader& r, const ArchiveSource& src, std::uint32_t version, std::vector<NodeInfo> nodes,
                MotionGraph& out) {
  Samples<std::uint32_t> rowstart;
  Samples<GraphVertex> targets;
  if (version >= 10) {
    // Read in place (summed here, their pages kept mapped for the storage's checks and the flags'
    // pass that follow).
    auto in_place = [&](auto& into) {
      using T = typename std::decay_t<decltype(into)>::value_type;
      const auto [p, n] = r.aligned<T>();
      r.template in_place<T>(
          n, [](const T*, std::size_t, std::size_t) {}, false);
      into = Samples<T>::view(p, n, src.owner);
    };
    in_place(rowstart);
    in_place(targets);
  } else {
    std::vector<std::uint32_t> rows = huge_vector<std::uint32_t>(r.count<std::uint32_t>());
    r.items<std::uint32_t>(rows.size(), [&](std::size_t i, std::uint32_t s) { rows[i] = s; });
    std::vector<GraphVertex> columns = huge_vector<GraphVertex>(r.count<std::uint32_t>());
    r.items<std::uint32_t>(columns.size(), [&](std::size_t i, std::uint32_t t) { columns[i] = t; });
    rowstart = Samples<std::uint32_t>(std::move(rows));
    targets = Samples<GraphVertex>(std::move(columns));
  }
  const std::size_t e = targets.size();
  // A weight is valid when finite and not negative: w - w is 0 and w >= 0 (NaN fails both).
  auto valid = [](double w) { return w - w == 0.0 && w >= 0.0; };
  bool invalid = false;
  if (version >= 9) {
    const auto [weights, n] = r.aligned<double>();
    if (n != e) r.fail("edge weights disagree with the edge count");
    r.in_place<double>(
        n,
        [&](const double* p, std::size_t, std::size_t m) {
          std::size_t good = 0;
          for (std::size_t i = 0; i < m; ++i) good += valid(p[i]) ? 1 : 0;
          invalid = invalid || good != m;
        },
        false);
    out.edge_weights = Samples<double>::view(weights, n, src.owner);
  } else {
    std::vector<double> weights = huge_vector<double>(e);
    if (r.count<double>() != e) r.fail("edge weights disagree with the edge count");
    r.items<double>(e, [&](std::size_t i, double w) {
      weights[i] = w;
      invalid = invalid || !valid(w);
    });
    out.edge_weights = Samples<double>(std::move(weights));
  }
  if (invalid) r.fail("an edge weight is negative or not finite");
  try {
    out.graph = GraphStorage(std::move(nodes), std::move(rowstart), std::move(targets));
  } catch (const Error& err) {
    r.fail(err.what());
  }
  if (r.count<std::uint8_t>() != e) r.fail("edge flags disagree with the edge count");
  // (Const access: the non-const data() of a Samples copies a view.)
  const std::uint32_t* rows = std::as_const(out.graph).row_starts().data();
  const GraphVertex* columns = std::as_const(out.graph).targets().data();
  const double* weights = std::as_const(out.edge_weights).data();
  double sum = 0.0;
  long transitions = 0;
  std::size_t source = 0;
  r.items<std::uint8_t>(e, [&](std::size_t i, std::uint8_t flag) {
    while (i >= rows[source + 1]) ++source;  // rows are ascending (checked above)
    const bool natural = is_natural_edge(source, columns[i]);
    const double weight = weights[i];
    if (natural != (flag != 0) || (natural && weight != 0))
      r.fail(natural ? "an edge from frame " + std::to_string(source) +
                           " to the next frame is not its natural edge of weight 0"
                     : "a natural edge from frame " + std::to_string(source) + " is not a step to the next frame");
    if (!natural) {
      sum += weight;
      ++transitions;
    }
  });
  out.transition_weight = transitions > 0 ? sum / static_cast<double>(transitions) : 0.0;
}

void write_speech(ArchiveWriter& w, const MotionGraph& g) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(g.speech_dims));
  w.aligned(g.speech.data(), g.speech.size());
  w.aligned(g.activity.data(), g.activity.size());
}

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void read_speech(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g) {
  const std::uint32_t dims = r.pod<std::uint32_t>();
  if (dims > 64) r.fail("implausible speech feature count");
  g.speech_dims = static_cast<int>(dims);
  const auto [speech, speech_n] = r.aligned<float>();
  if (speech_n != static_cast<std::size_t>(g.motion.frame_count) * dims)
    r.fail("speech features disagree with frames x features");
  bool finite = true;
  r.in_place<float>(speech_n,
                    [&](const float* p, std::size_t, std::size_t n) { finite = finite && count_finite(p, n) == n; });
  if (!finite) r.fail("a speech feature is not finite");
  const auto [activity, activity_n] = r.aligned<float>();
  if (activity_n != 0 && activity_n != static_cast<std::size_t>(g.motion.frame_count))
    r.fail("motion activity disagrees with the frame count");
  bool valid = true;
  r.in_place<float>(activity_n, [&](const float* p, std::size_t, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) valid = valid && std::isfinite(p[i]) && p[i] >= 0.0f;
  });
  if (!valid) r.fail("a motion activity is negative or not finite");
  g.speech = Samples<float>::view(speech, speech_n, src.owner);
  g.activity = Samples<float>::view(activity, activity_n, src.owner);
}

void write_reference_facts(ArchiveWriter& w, const MotionGraph& g) {
  const CaptureFacts& c = g.capture;
  w.pod<std::uint8_t>(c.known ? 1 : 0);
  w.pod(c.largest_root_step);
  w.pod(c.root_lo);
  w.pod(c.root_hi);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(c.knee_hinges.size()));
  for (const glm::dvec3& h : c.knee_hinges) w.pod(h);
  w.aligned(c.foot_flags.data(), c.foot_flags.size());
  w.aligned(g.beat_cost.data(), g.beat_cost.size());
}

void read_reference_facts(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g) {
  CaptureFacts& c = g.capture;
  const std::uint8_t known = r.pod<std::uint8_t>();
  if (known > 1) r.fail("the reference facts are neither known nor unknown");
  c.known = known == 1;
  c.largest_root_step = r.pod<double>();
  c.root_lo = r.pod<glm::dvec3>();
  c.root_hi = r.pod<glm::dvec3>();
  const std::uint32_t legs = r.pod<std::uint32_t>();
  if (!c.known && legs != 0) r.fail("the reference facts are unknown but describe legs");
  const std::size_t skeleton_legs = c.known ? find_legs(g.motion.skeleton).size() : 0;
  if (legs != skeleton_legs)
    r.fail("the reference facts describe " + std::to_string(legs) + " legs, its skeleton has " +
           std::to_string(skeleton_legs));
  if (c.known && !(std::isfinite(c.largest_root_step) && c.largest_root_step >= 0.0))
    r.fail("the largest root step is negative or not finite");
  if (c.known && !(finite(c.root_lo) && finite(c.root_hi) && c.root_lo.x <= c.root_hi.x && c.root_lo.y <= c.root_hi.y &&
                   c.root_lo.z <= c.root_hi.z))
    r.fail("the root's extent is not finite or its low end lies above its high end");
  for (std::uint32_t l = 0; l < legs; ++l) {
    const glm::dvec3 h = r.pod<glm::dvec3>();
    const double length = glm::length(h);
    if (!finite(h) || !(length == 0.0 || std::abs(length - 1.0) <= 1e-9)) r.fail("a knee hinge is not a unit axis");
    c.knee_hinges.push_back(h);
  }
  const std::size_t frames = static_cast<std::size_t>(g.frame_count());
  const auto [flags, flags_n] = r.aligned<std::uint8_t>();
  if (flags_n != (legs > 0 ? frames : 0)) r.fail("foot contacts disagree with the frame count");
  const unsigned known_bits = (1u << (2 * legs)) - 1;
  bool valid = true;
  r.in_place<std::uint8_t>(flags_n, [&](const std::uint8_t* p, std::size_t, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) valid = valid && (p[i] & ~known_bits) == 0;
  });
  if (!valid) r.fail("a foot contact has bits of no leg");
  c.foot_flags = Samples<std::uint8_t>::view(flags, flags_n, src.owner);
  const auto [costs, costs_n] = r.aligned<float>();
  if (costs_n != (c.known && !g.activity.empty() ? frames : 0)) r.fail("beat end costs disagree with the frame count");
  r.in_place<float>(costs_n, [&](const float* p, std::size_t, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) valid = valid && p[i] >= 0.0f && p[i] <= 1.0f;
  });
  if (!valid) r.fail("a beat end cost is not a number from 0 to 1");
  g.beat_cost = Samples<float>::view(costs, costs_n, src.owner);
}

void write_body(ArchiveWriter& w, const SmplxBody& b) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(b.expression_dims));
  w.aligned(b.expressions.data(), b.expressions.size());
  w.vec(b.betas);
  w.str(b.gender);
  w.str(b.model);
}

void read_body(ArchiveReader& r, MotionGraph& g) {
  SmplxBody& b = g.body;
  const std::uint32_t dims = r.pod<std::uint32_t>();
  if (dims > 10000) r.fail("implausible face coefficient count");
  b.expression_dims = static_cast<int>(dims);
  const std::size_t face_n = r.aligned<double>().second;
  if (face_n != static_cast<std::size_t>(g.motion.frame_count) * dims)
    r.fail("the face disagrees with frames x coefficients");
  b.expressions.reserve(face_n);
  r.in_place<double>(face_n, [&](const double* p, std::size_t, std::size_t n) {
    b.expressions.insert(b.expressions.end(), p, p + n);
  });
  b.betas = r.vec<double>();
  if (b.betas.size() > 10000) r.fail("implausible betas count");
  for (const std::vector<double>* v : {&b.expressions, &b.betas})
    for (double x : *v)
      if (!std::isfinite(x)) r.fail("a face or shape value is not finite");
  b.gender = r.str();
  b.model = r.str();
}

void write_layers(ArchiveWriter& w, const MotionGraph& g) {
  w.pod<std::uint8_t>(static_cast<std::uint8_t>(g.up));
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(g.lower_joints.size()));
  for (const std::string& name : g.lower_joints) w.str(name);
  const Stance& st = g.stance;
  w.pod<std::uint8_t>(st.known ? 1 : 0);
  w.pod(st.leg_length);
  w.pod(st.still_speed);
  w.aligned(st.pose);
  w.aligned(st.place);
  w.aligned(st.speed);
  w.aligned(st.planted);
  w.aligned(g.spikes);
}

void read_layers(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g) {
  const std::uint8_t up = r.pod<std::uint8_t>();
  if (up > static_cast<std::uint8_t>(UpAxis::Z)) r.fail("unknown up axis");
  g.up = static_cast<UpAxis>(up);
  const std::uint32_t names = r.pod<std::uint32_t>();
  if (names > static_cast<std::uint32_t>(g.motion.joint_count())) r.fail("more lower joints than joints");
  for (std::uint32_t i = 0; i < names; ++i) {
    g.lower_joints.push_back(r.str());
    if (g.motion.skeleton.find(g.lower_joints.back()) < 0) r.fail("a lower joint is not a joint of its skeleton");
  }
  Stance& st = g.stance;
  const std::uint8_t known = r.pod<std::uint8_t>();
  if (known > 1) r.fail("the stance is neither known nor unknown");
  st.known = known == 1;
  st.leg_length = r.pod<double>();
  st.still_speed = r.pod<float>();
  if (st.known &&
      !(std::isfinite(st.leg_length) && st.leg_length > 0.0 && std::isfinite(st.still_speed) && st.still_speed >= 0.0f))
    r.fail("the stance's leg length or still speed is not a positive finite number");
  const std::size_t frames = st.known ? static_cast<std::size_t>(g.frame_count()) : 0;
  bool valid = true;
  // Each list's count, then its values, in the order written.
  auto floats = [&](std::size_t expected) {
    const auto [p, n] = r.aligned<float>();
    if (n != expected) r.fail("the stance disagrees with the frame count");
    r.in_place<float>(n, [&](const float* q, std::size_t, std::size_t m) { valid = valid && count_finite(q, m) == m; });
    return Samples<float>::view(p, n, src.owner);
  };
  st.pose = floats(frames * kStanceDims);
  st.place = floats(frames * 2);
  st.speed = floats(frames);
  const auto [planted, planted_n] = r.aligned<std::uint8_t>();
  if (planted_n != frames) r.fail("the stance disagrees with the frame count");
  r.in_place<std::uint8_t>(planted_n, [&](const std::uint8_t* q, std::size_t, std::size_t m) {
    for (std::size_t i = 0; i < m; ++i) valid = valid && q[i] <= 1;
  });
  if (!valid) r.fail("a stance value is not finite or a stance flag is not 0 or 1");
  st.planted = Samples<std::uint8_t>::view(planted, planted_n, src.owner);
  const auto [spikes, spikes_n] = r.aligned<std::uint8_t>();
  if (spikes_n != 0 && spikes_n != static_cast<std::size_t>(g.frame_count()))
    r.fail("the jerk spikes disagree with the frame count");
  r.in_place<std::uint8_t>(spikes_n, [&](const std::uint8_t* q, std::size_t, std::size_t m) {
    for (std::size_t i = 0; i < m; ++i) valid = valid && q[i] <= 1;
  });
  if (!valid) r.fail("a jerk spike flag is not 0 or 1");
  g.spikes = Samples<std::uint8_t>::view(spikes, spikes_n, src.owner);
}

}  // namespace gmg
