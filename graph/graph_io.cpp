// Saving and loading built graphs.
//
// File format (version 3), little-endian:
//   8 bytes  "GMGRAPH\0"
//   u32      format version
//   u64      payload size in bytes
//   payload  params, skeleton, clips, motion, nodes, edges, speech features, activity (write_payload),
//            and in version 4 only, the SMPL-X body (write_body)
//   u64      checksum of the payload (engine/core/checksum.h)
// A graph without a body (BVH references) is written as version 3, so it stays readable by a gmg
// that predates the body; version 4 is version 3 with the body section appended.
// The large parts are flat arrays in the layout they have in memory (motion samples; the edges
// in compressed sparse row order: row starts, targets, weights, natural flags), so a load is
// one pass of copies at memory speed and a save one pass of writes. A file with another magic
// or version, a short or over-long payload or a wrong checksum is rejected before anything is
// used.
#include <cmath>
#include <cstring>
#include <fstream>

#include "engine/core/checksum.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "graph/graph_builder.h"
#include "graph/graph_io.h"

namespace gmg {
namespace {

constexpr char kMagic[8] = {'G', 'M', 'G', 'R', 'A', 'P', 'H', '\0'};
constexpr std::uint32_t kVersion = 3;      // 3: the reference speech features
constexpr std::uint32_t kBodyVersion = 4;  // 4: 3 and the SMPL-X body (shape, per-frame face)
constexpr std::size_t kHeader = sizeof kMagic + sizeof(std::uint32_t) + sizeof(std::uint64_t);

// Writes the payload to a stream, or only counts and checksums it (out == nullptr), so the
// header's size is known before the first byte is written and nothing is buffered.
class Writer {
 public:
  explicit Writer(std::ostream* out) : out_(out) {}
  void bytes(const void* data, std::size_t size) {
    if (out_ && size) out_->write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    sum_.add(data, size);
    size_ += size;
  }
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable<T>::value, "pod only");
    bytes(&v, sizeof(T));
  }
  void str(const std::string& s) {
    pod<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable<T>::value, "pod only");
    pod<std::uint64_t>(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  // A list written from a function of its index, in chunks (for arrays whose memory layout is not
  // the file's).
  template <typename T, typename F>
  void vec_of(std::size_t n, const F& at) {
    pod<std::uint64_t>(n);
    std::vector<T> chunk;
    for (std::size_t i = 0; i < n; i += kChunk) {
      chunk.clear();
      for (std::size_t j = i; j < std::min(n, i + kChunk); ++j) chunk.push_back(at(j));
      bytes(chunk.data(), chunk.size() * sizeof(T));
    }
  }
  std::uint64_t size() const { return size_; }
  std::uint64_t checksum() const { return sum_.value(); }

 private:
  static constexpr std::size_t kChunk = 1 << 16;
  std::ostream* out_;
  Checksum sum_;
  std::uint64_t size_ = 0;
};

class Reader {
 public:
  Reader(const char* data, std::size_t size, const std::string& path) : data_(data), size_(size), path_(path) {}
  template <typename T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string str() {
    const std::uint32_t n = pod<std::uint32_t>();
    need(n);
    std::string s(data_ + pos_, n);
    pos_ += n;
    return s;
  }
  // The count of a list of T, checked against the bytes left; the caller reads the items.
  template <typename T>
  std::size_t count() {
    const std::uint64_t n = pod<std::uint64_t>();
    if (n > (size_ - pos_) / sizeof(T)) fail("a list is longer than the file");
    return static_cast<std::size_t>(n);
  }
  template <typename T>
  std::vector<T> vec() {
    std::vector<T> v(count<T>());
    if (!v.empty()) std::memcpy(v.data(), data_ + pos_, v.size() * sizeof(T));
    pos_ += v.size() * sizeof(T);
    return v;
  }
  // n items of T converted one by one (for arrays whose memory layout is not the file's).
  template <typename T, typename F>
  void items(std::size_t n, const F& take) {
    need(n * sizeof(T));
    for (std::size_t i = 0; i < n; ++i) {
      T v;
      std::memcpy(&v, data_ + pos_ + i * sizeof(T), sizeof(T));
      take(i, v);
    }
    pos_ += n * sizeof(T);
  }
  bool done() const { return pos_ == size_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(error_at_byte(path_, static_cast<long long>(pos_ + kHeader), "damaged graph file: " + what));
  }

 private:
  void need(std::size_t n) {
    if (n > size_ - pos_) fail("unexpected end of data");
  }
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  const std::string& path_;
};

void write_params(Writer& w, const GraphParams& p) {
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

GraphParams read_params(Reader& r) {
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

void write_skeleton(Writer& w, const Skeleton& sk) {
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

Joint read_joint(Reader& r, std::uint32_t i, std::vector<int>& depth) {
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

// Every count within engine/core/limits.h.
Skeleton read_skeleton(Reader& r) {
  Skeleton sk;
  const std::uint32_t joints = r.pod<std::uint32_t>();
  if (joints == 0 || joints > static_cast<std::uint32_t>(limits::kMaxJoints)) r.fail("implausible joint count");
  std::vector<int> depth;
  for (std::uint32_t i = 0; i < joints; ++i) sk.joints.push_back(read_joint(r, i, depth));
  return sk;
}

void write_payload(Writer& w, const MotionGraph& g) {
  write_params(w, g.params);
  write_skeleton(w, g.motion.skeleton);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(g.clips.size()));
  for (const ClipInfo& c : g.clips) {
    w.str(c.name);
    w.pod<std::int32_t>(c.first_frame);
    w.pod<std::int32_t>(c.frame_count);
  }
  w.pod(g.motion.fps);
  w.pod<std::int32_t>(g.motion.frame_count);
  w.vec(g.motion.rotations);
  w.vec(g.motion.translations);

  // Nodes: every frame's kinds, then the labels of the keyword nodes only.
  const std::size_t n = static_cast<std::size_t>(g.frame_count());
  w.vec_of<std::uint8_t>(n, [&](std::size_t f) { return g.graph[f].kinds; });
  std::uint32_t labels = 0;
  for (std::size_t f = 0; f < n; ++f) labels += g.graph[f].keyword.empty() ? 0 : 1;
  w.pod(labels);
  for (std::size_t f = 0; f < n; ++f)
    if (!g.graph[f].keyword.empty()) {
      w.pod<std::uint32_t>(static_cast<std::uint32_t>(f));
      w.str(g.graph[f].keyword);
    }

  const auto& csr = g.graph.m_forward;
  w.vec(csr.m_rowstart);
  const std::size_t e = csr.m_column.size();
  w.vec_of<std::uint32_t>(e, [&](std::size_t i) { return static_cast<std::uint32_t>(csr.m_column[i]); });
  w.vec_of<double>(e, [&](std::size_t i) { return csr.m_edge_properties[i].weight; });
  w.vec_of<std::uint8_t>(e, [&](std::size_t i) { return std::uint8_t{csr.m_edge_properties[i].natural}; });
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(g.speech_dims));
  w.vec(g.speech);
  w.vec(g.activity);
}

bool has_body(const MotionGraph& g) {
  return g.body.has_face() || !g.body.betas.empty() || !g.body.gender.empty() || !g.body.model.empty();
}

// Version 4's section: face dims, face (frames x dims doubles), betas, gender, model.
void write_body(Writer& w, const SmplxBody& b) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(b.expression_dims));
  w.vec(b.expressions);
  w.vec(b.betas);
  w.str(b.gender);
  w.str(b.model);
}

void read_body(Reader& r, MotionGraph& g) {
  SmplxBody& b = g.body;
  const std::uint32_t dims = r.pod<std::uint32_t>();
  if (dims > 10000) r.fail("implausible face coefficient count");
  b.expression_dims = static_cast<int>(dims);
  b.expressions = r.vec<double>();
  if (b.expressions.size() != static_cast<std::size_t>(g.motion.frame_count) * dims)
    r.fail("the face disagrees with frames x coefficients");
  b.betas = r.vec<double>();
  if (b.betas.size() > 10000) r.fail("implausible betas count");
  for (const std::vector<double>* v : {&b.expressions, &b.betas})
    for (double x : *v)
      if (!std::isfinite(x)) r.fail("a face or shape value is not finite");
  b.gender = r.str();
  b.model = r.str();
}

// The speech features: none, or frames x dims finite values.
void read_speech(Reader& r, MotionGraph& g) {
  const std::uint32_t dims = r.pod<std::uint32_t>();
  if (dims > 64) r.fail("implausible speech feature count");
  g.speech_dims = static_cast<int>(dims);
  g.speech = r.vec<float>();
  if (g.speech.size() != static_cast<std::size_t>(g.motion.frame_count) * dims)
    r.fail("speech features disagree with frames x features");
  for (float v : g.speech)
    if (!std::isfinite(v)) r.fail("a speech feature is not finite");
  g.activity = r.vec<float>();
  if (!g.activity.empty() && g.activity.size() != static_cast<std::size_t>(g.motion.frame_count))
    r.fail("motion activity disagrees with the frame count");
  for (float v : g.activity)
    if (!std::isfinite(v) || v < 0.0f) r.fail("a motion activity is negative or not finite");
}

std::vector<NodeInfo> read_nodes(Reader& r, std::size_t frames) {
  std::vector<NodeInfo> nodes(frames);
  if (r.count<std::uint8_t>() != frames) r.fail("node count disagrees with the motion");
  bool unknown = false;
  r.items<std::uint8_t>(frames, [&](std::size_t f, std::uint8_t kinds) {
    nodes[f].kinds = kinds;
    unknown = unknown || (kinds & ~(kOnsetNode | kKeywordNode | kBreakNode)) != 0;
  });
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

GraphStorage read_edges(Reader& r, std::vector<NodeInfo> nodes) {
  std::vector<std::uint32_t> rowstart = r.vec<std::uint32_t>();
  const std::size_t e = r.count<std::uint32_t>();
  std::vector<std::size_t> targets(e);
  r.items<std::uint32_t>(e, [&](std::size_t i, std::uint32_t t) { targets[i] = t; });
  std::vector<EdgeInfo> edges(e);
  if (r.count<double>() != e) r.fail("edge weights disagree with the edge count");
  bool invalid = false;
  r.items<double>(e, [&](std::size_t i, double w) {
    edges[i].weight = w;
    invalid = invalid || !std::isfinite(w) || w < 0;
  });
  if (invalid) r.fail("an edge weight is negative or not finite");
  if (r.count<std::uint8_t>() != e) r.fail("edge flags disagree with the edge count");
  r.items<std::uint8_t>(e, [&](std::size_t i, std::uint8_t natural) { edges[i].natural = natural != 0; });
  try {
    return graph_storage_from_arrays(std::move(nodes), std::move(rowstart), std::move(targets), std::move(edges));
  } catch (const Error& err) {
    r.fail(err.what());
  }
}

// The clip table: contiguous clips (summed in 64 bits, so counts near 2^31 cannot wrap); the
// caller checks they cover the motion.
std::vector<ClipInfo> read_clips(Reader& r, long long& covered) {
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

void read_motion(Reader& r, Motion& m) {
  m.fps = r.pod<double>();
  m.frame_count = r.pod<std::int32_t>();
  if (!(m.fps >= limits::kMinFps && m.fps <= limits::kMaxFps))
    r.fail("frame rate " + format_number(m.fps) + " is outside " + format_number(limits::kMinFps) + " to " +
           format_number(limits::kMaxFps) + " fps");
  if (m.frame_count < 1 || m.frame_count > limits::kMaxFrames) r.fail("invalid frame count");
  m.rotations = r.vec<glm::dquat>();
  m.translations = r.vec<glm::dvec3>();
  const std::size_t joints = m.skeleton.joints.size();
  const std::size_t expected = static_cast<std::size_t>(m.frame_count) * joints;
  if (m.rotations.size() != expected || m.translations.size() != expected)
    r.fail("motion size disagrees with frames x joints");
  for (std::size_t k = 0; k < expected; ++k) {
    const glm::dquat& q = m.rotations[k];
    const glm::dvec3& t = m.translations[k];
    if (!std::isfinite(q.w + q.x + q.y + q.z + t.x + t.y + t.z) || std::abs(glm::dot(q, q) - 1.0) > 1e-6)
      r.fail("frame " + std::to_string(k / joints) + " holds a value that is not finite or not a unit rotation");
  }
}

// Natural edges are the capture's own frame steps: to the next frame, with weight 0.
void check_natural_edges(Reader& r, const GraphStorage& g) {
  const auto& csr = g.m_forward;
  for (std::size_t f = 0; f + 1 < csr.m_rowstart.size(); ++f)
    for (std::size_t i = csr.m_rowstart[f]; i < csr.m_rowstart[f + 1]; ++i) {
      const EdgeInfo& e = csr.m_edge_properties[i];
      if (e.natural && (csr.m_column[i] != f + 1 || e.weight != 0))
        r.fail("a natural edge from frame " + std::to_string(f) + " is not a step to the next frame of weight 0");
    }
}

MotionGraph read_payload(Reader& r, std::uint32_t version) {
  MotionGraph g;
  g.params = read_params(r);
  g.motion.skeleton = read_skeleton(r);
  long long covered = 0;
  g.clips = read_clips(r, covered);
  read_motion(r, g.motion);
  if (covered != g.motion.frame_count) r.fail("clips do not cover the motion");
  g.graph = read_edges(r, read_nodes(r, static_cast<std::size_t>(g.motion.frame_count)));
  check_natural_edges(r, g.graph);
  read_speech(r, g);
  if (version >= kBodyVersion) read_body(r, g);
  if (!r.done())
    r.fail(version >= kBodyVersion ? "trailing bytes after the body" : "trailing bytes after the speech features");
  return g;
}

MotionGraph parse_graph(const char* bytes, std::size_t total, const std::string& path) {
  if (total < sizeof kMagic || std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
    throw Error(path + ": not a gmg graph file (build one with 'gmg build')");
  if (total < kHeader + sizeof(std::uint64_t)) throw Error(error_at_byte(path, 8, "graph file is truncated"));
  std::uint32_t version = 0;
  std::memcpy(&version, bytes + 8, sizeof version);
  if (version != kVersion && version != kBodyVersion)
    throw Error(path + ": graph file format version " + std::to_string(version) + ", this gmg reads versions " +
                std::to_string(kVersion) + " and " + std::to_string(kBodyVersion) + ": rebuild it with 'gmg build'");
  std::uint64_t size = 0;
  std::memcpy(&size, bytes + 12, sizeof size);
  const std::size_t present = total - kHeader - sizeof(std::uint64_t);
  if (size != present)
    throw Error(error_at_byte(path, 12,
                              "graph file is truncated or has trailing bytes (payload " + std::to_string(size) +
                                  " bytes declared, " + std::to_string(present) + " present)"));
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes + kHeader + present, sizeof sum);
  if (sum != checksum_of(bytes + kHeader, present)) throw Error(path + ": graph file is damaged (checksum mismatch)");
  Reader r(bytes + kHeader, present, path);
  return naming_memory_errors(path, "reading the graph", [&] { return read_payload(r, version); });
}

}  // namespace

void graph_save(const std::string& path, const MotionGraph& g) {
  const bool body = has_body(g);
  Writer counter(nullptr);
  write_payload(counter, g);
  if (body) write_body(counter, g.body);
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        out.write(kMagic, sizeof kMagic);
        const std::uint32_t version = body ? kBodyVersion : kVersion;
        out.write(reinterpret_cast<const char*>(&version), sizeof version);
        const std::uint64_t size = counter.size();
        out.write(reinterpret_cast<const char*>(&size), sizeof size);
        Writer w(&out);
        write_payload(w, g);
        if (body) write_body(w, g.body);
        if (w.size() != size) throw Error(path + ": graph changed while it was written");
        const std::uint64_t sum = w.checksum();
        out.write(reinterpret_cast<const char*>(&sum), sizeof sum);
      },
      true);
}

MotionGraph graph_load(const std::string& path) {
  const MappedFile file(path);
  return parse_graph(file.data(), file.size(), path);
}

MotionGraph graph_parse(const std::string& bytes, const std::string& path) {
  return parse_graph(bytes.data(), bytes.size(), path);
}

}  // namespace gmg
