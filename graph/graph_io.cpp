// Saving and loading built graphs.
//
// File format (version 1), little-endian:
//   8 bytes  "GMGRAPH\0"
//   u32      format version
//   u64      payload size in bytes
//   payload  params, skeleton, motion, clips, nodes, edges (see write_payload)
//   u64      FNV-1a hash of the payload
// A file with another magic or version, a short or over-long payload or a wrong hash is
// rejected before anything is used.
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "graph/graph_io.h"

namespace gmg {
namespace {

constexpr char kMagic[8] = {'G', 'M', 'G', 'R', 'A', 'P', 'H', '\0'};
constexpr std::uint32_t kVersion = 1;

std::uint64_t fnv1a(const char* data, std::size_t size) {
  std::uint64_t h = 1469598103934665603ULL;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ULL;
  }
  return h;
}

class Writer {
 public:
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable<T>::value, "pod only");
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void str(const std::string& s) {
    pod<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    out_.append(s);
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    pod<std::uint64_t>(v.size());
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  const std::string& bytes() const { return out_; }

 private:
  std::string out_;
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
  template <typename T>
  std::vector<T> vec() {
    const std::uint64_t n = pod<std::uint64_t>();
    if (n > (size_ - pos_) / sizeof(T)) fail("a list is longer than the file");
    std::vector<T> v(static_cast<std::size_t>(n));
    if (n) std::memcpy(v.data(), data_ + pos_, static_cast<std::size_t>(n) * sizeof(T));
    pos_ += static_cast<std::size_t>(n) * sizeof(T);
    return v;
  }
  bool done() const { return pos_ == size_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(error_at_byte(path_, static_cast<long long>(pos_ + 20), "damaged graph file: " + what));
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

void write_payload(Writer& w, const MotionGraph& g) {
  const GraphParams& p = g.params;
  w.pod(p.lambda_pos);
  w.pod(p.lambda_vel);
  w.pod<std::int32_t>(p.l_cn);
  w.pod<std::int32_t>(p.l_pn);
  w.pod<std::uint8_t>(p.exclude_near ? 1 : 0);
  w.pod(p.min_onset_strength);
  w.pod(p.break_jump_factor);
  w.str(p.keywords);

  const Skeleton& sk = g.motion.skeleton;
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
  w.pod(g.motion.fps);
  w.pod<std::int32_t>(g.motion.frame_count);
  w.vec(g.motion.rotations);
  w.vec(g.motion.translations);

  w.pod<std::uint32_t>(static_cast<std::uint32_t>(g.clips.size()));
  for (const ClipInfo& c : g.clips) {
    w.str(c.name);
    w.pod<std::int32_t>(c.first_frame);
    w.pod<std::int32_t>(c.frame_count);
  }
  for (int f = 0; f < g.frame_count(); ++f) {
    w.pod(g.node(f).kinds);
    w.str(g.node(f).keyword);
  }
  w.pod<std::uint64_t>(boost::num_edges(g.graph));
  for (auto [it, end] = boost::edges(g.graph); it != end; ++it) {
    w.pod<std::int32_t>(static_cast<std::int32_t>(boost::source(*it, g.graph)));
    w.pod<std::int32_t>(static_cast<std::int32_t>(boost::target(*it, g.graph)));
    w.pod(g.graph[*it].weight);
    w.pod<std::uint8_t>(g.graph[*it].natural ? 1 : 0);
  }
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
  try {
    graph_params_validate(p);
  } catch (const Error& e) {
    r.fail(std::string("its build parameters are out of range (") + e.what() + ")");
  }
  return p;
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

// The skeleton and the frames; every count within engine/core/limits.h.
void read_motion(Reader& r, Motion& m) {
  const std::uint32_t joints = r.pod<std::uint32_t>();
  if (joints == 0 || joints > static_cast<std::uint32_t>(limits::kMaxJoints)) r.fail("implausible joint count");
  std::vector<int> depth;
  for (std::uint32_t i = 0; i < joints; ++i) m.skeleton.joints.push_back(read_joint(r, i, depth));
  m.fps = r.pod<double>();
  m.frame_count = r.pod<std::int32_t>();
  if (!(m.fps >= limits::kMinFps && m.fps <= limits::kMaxFps))
    r.fail("frame rate " + format_number(m.fps) + " is outside " + format_number(limits::kMinFps) + " to " +
           format_number(limits::kMaxFps) + " fps");
  if (m.frame_count < 1 || m.frame_count > limits::kMaxFrames) r.fail("invalid frame count");
  m.rotations = r.vec<glm::dquat>();
  m.translations = r.vec<glm::dvec3>();
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

// The clip table: contiguous clips covering every frame (summed in 64 bits, so counts near
// 2^31 cannot wrap).
std::vector<ClipInfo> read_clips(Reader& r, int frame_count) {
  std::vector<ClipInfo> clips;
  const std::uint32_t count = r.pod<std::uint32_t>();
  long long covered = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    ClipInfo c;
    c.name = r.str();
    c.first_frame = r.pod<std::int32_t>();
    c.frame_count = r.pod<std::int32_t>();
    if (c.first_frame != covered || c.frame_count < 1 || covered + c.frame_count > frame_count)
      r.fail("clip table inconsistent");
    covered += c.frame_count;
    clips.push_back(c);
  }
  if (covered != frame_count) r.fail("clips do not cover the motion");
  return clips;
}

void read_nodes_and_edges(Reader& r, MotionGraph& g) {
  const int frames = g.motion.frame_count;
  g.graph = GraphStorage(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    NodeInfo& n = g.graph[static_cast<std::size_t>(f)];
    n.kinds = r.pod<std::uint8_t>();
    n.keyword = r.str();
    if ((n.kinds & ~(kOnsetNode | kKeywordNode | kBreakNode)) != 0 ||
        ((n.kinds & kKeywordNode) != 0) != !n.keyword.empty())
      r.fail("node " + std::to_string(f) + " has unknown kinds or a keyword without its kind");
  }
  const std::uint64_t edges = r.pod<std::uint64_t>();
  for (std::uint64_t e = 0; e < edges; ++e) {
    const int a = r.pod<std::int32_t>();
    const int b = r.pod<std::int32_t>();
    const double w = r.pod<double>();
    const bool natural = r.pod<std::uint8_t>() != 0;
    if (a < 0 || b < 0 || a >= frames || b >= frames) r.fail("edge outside the graph");
    if (!std::isfinite(w) || w < 0 || (natural && (b != a + 1 || w != 0))) r.fail("edge with an invalid weight");
    boost::add_edge(static_cast<std::size_t>(a), static_cast<std::size_t>(b), EdgeInfo{w, natural}, g.graph);
  }
}

MotionGraph read_payload(Reader& r) {
  MotionGraph g;
  g.params = read_params(r);
  read_motion(r, g.motion);
  g.clips = read_clips(r, g.motion.frame_count);
  read_nodes_and_edges(r, g);
  if (!r.done()) r.fail("trailing bytes after the edges");
  return g;
}

}  // namespace

void graph_save(const std::string& path, const MotionGraph& g) {
  Writer w;
  write_payload(w, g);
  const std::string& payload = w.bytes();
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        out.write(kMagic, sizeof kMagic);
        const std::uint32_t version = kVersion;
        out.write(reinterpret_cast<const char*>(&version), sizeof version);
        const std::uint64_t size = payload.size();
        out.write(reinterpret_cast<const char*>(&size), sizeof size);
        out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
        const std::uint64_t hash = fnv1a(payload.data(), payload.size());
        out.write(reinterpret_cast<const char*>(&hash), sizeof hash);
      },
      true);
}

MotionGraph graph_parse(const std::string& bytes, const std::string& path) {
  constexpr std::size_t kHeader = sizeof kMagic + sizeof(std::uint32_t) + sizeof(std::uint64_t);
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw Error(path + ": not a gmg graph file (build one with 'gmg build')");
  if (bytes.size() < kHeader + sizeof(std::uint64_t)) throw Error(error_at_byte(path, 8, "graph file is truncated"));
  std::uint32_t version = 0;
  std::memcpy(&version, bytes.data() + 8, sizeof version);
  if (version != kVersion)
    throw Error(path + ": graph file format version " + std::to_string(version) + ", this gmg reads version " +
                std::to_string(kVersion) + ": rebuild it with 'gmg build'");
  std::uint64_t size = 0;
  std::memcpy(&size, bytes.data() + 12, sizeof size);
  if (size != bytes.size() - kHeader - sizeof(std::uint64_t))
    throw Error(error_at_byte(path, 12,
                              "graph file is truncated or has trailing bytes (payload " + std::to_string(size) +
                                  " bytes declared, " + std::to_string(bytes.size() - kHeader - 8) + " present)"));
  std::uint64_t hash = 0;
  std::memcpy(&hash, bytes.data() + kHeader + size, sizeof hash);
  if (hash != fnv1a(bytes.data() + kHeader, static_cast<std::size_t>(size)))
    throw Error(path + ": graph file is damaged (checksum mismatch)");
  Reader r(bytes.data() + kHeader, static_cast<std::size_t>(size), path);
  return naming_memory_errors(path, "reading the graph", [&] { return read_payload(r); });
}

MotionGraph graph_load(const std::string& path) { return graph_parse(read_file_bytes(path), path); }

}  // namespace gmg
