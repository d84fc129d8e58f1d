// Saving and loading built graphs.
//
// File format (version 10; 9 has unaligned row starts and targets, 8 also the key poses and the
// edge weights where the checksum covers them and unaligned weights, 7 also lacks the key sketch),
// little-endian:
//   8 bytes  "GMGRAPH\0"
//   u32      format version
//   u64      payload size in bytes
//   u64      how many of the payload's first bytes the checksum covers: all but the key poses' and
//            the motion's values
//   payload  params, skeleton, clips, the motion's frame rate and count, nodes, edges (row starts,
//            targets, weights, natural flags), speech features, activity, the key poses' count and
//            each key's checksum, their sketch (write_payload), the reference facts
//            (write_reference_facts: the assembly's capture facts and the frames' beat end costs,
//            graph/reference_facts.h), the SMPL-X body (write_body: empty for BVH references), and
//            last the motion (write_motion): frames per block, each block's checksum, then the key
//            poses, the rotations and the translations
//   u64      checksum of the payload's first bytes (XXH3-64, engine/core/checksum.h)
// The large parts are flat arrays in the layout they have in memory. The twelve largest (the
// motion's rotations and translations, the edges' row starts, targets and weights, the speech
// features, the motion activity, the key nodes' junction poses and their sketch, the foot
// contacts, the beat end costs and the body's face) each start on a 4096-byte boundary of the file
// (zero bytes pad up to it), so a loaded graph reads all but the face in place from the file's
// mapping (engine/core/files.h MappedFile): the pages of the file are shared by every process that
// reads it, and the load keeps none of them resident but the edges'.
//
// A load checks the file's checksum and every field of the part it covers in one pass. The
// motion, most of the file, has a checksum per block of frames instead, and the key poses one per
// key: the load checks all of them (MotionCheck::OnLoad) or leaves each block and key to be
// checked when first used (MotionCheck::OnUse, graph_check_frames and graph_check_key_poses), so
// that a reenactment from a long reference reads only the stretches it plays and the poses it
// ranks. The face is copied (SmplxBody holds its own arrays; a graph from BVH references has
// none). The nodes are copied (8 bytes a node). The edges' row starts and targets, whose values
// index other arrays, are validated by the load and then read in place through accessors that
// keep every index inside its array (graph/motion_graph.h GraphStorage), so a file rewritten in
// place under a running gmg can give wrong values, never an out-of-bounds read; the mapping then
// reports the change (MotionGraph::check_unchanged). The key and break frames and the mean
// transition weight are not stored: the load takes them from the nodes and edges it reads. A file
// with another magic or version (older versions included: 3 had no key poses and unaligned arrays,
// 4 no body, 5 no reference facts, 6 one checksum over everything), a short or over-long payload
// or a wrong checksum is rejected before anything is used.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "engine/core/checksum.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "engine/motion/body_parts.h"
#include "engine/motion/motion.h"
#include "graph/graph_builder.h"
#include "graph/graph_io.h"
#include "graph/key_poses.h"

namespace gmg {
namespace {

constexpr char kMagic[8] = {'G', 'M', 'G', 'R', 'A', 'P', 'H', '\0'};
constexpr std::uint32_t kVersion = kGraphFormatVersion;
constexpr std::size_t kAlign = 4096;  // the sections read in place start at multiples of it
// Magic, version, payload size, and how many of the payload's bytes the checksum covers.
constexpr std::size_t kHeader = sizeof kMagic + sizeof(std::uint32_t) + 2 * sizeof(std::uint64_t);
// Frames per checked block of the motion: 64 frames of 55 joints are 197 KB, so a reenactment that
// plays a stretch checks little more than it reads, and the table of a 19 h reference is 256 KB.
constexpr std::uint32_t kMotionBlockFrames = 64;

// A graph file is written in whole blocks of this many bytes from its start (engine/core/files.h
// BlockWriter): reenacting 77 s from a 19 h graph took 1.8 times the CPU time from the file written
// in the 4 MB pieces of its arrays, each after a few bytes of counts and padding, as from the same
// bytes read back from the disk or written in these blocks.
constexpr std::size_t kWriteBlock = std::size_t{16} << 20;

// Writes the payload to a stream, or only counts and checksums it (out == nullptr), so the
// header's size is known before the first byte is written. What it writes goes out in whole
// kWriteBlock blocks (the file's header first: raw), the rest at flush().
class Writer {
 public:
  explicit Writer(std::ostream* out) {
    if (out) out_.emplace(*out, kWriteBlock);
  }
  void bytes(const void* data, std::size_t size) {
    if (out_) out_->write(data, size);
    if (summing_) sum_.add(data, size);
    size_ += size;
  }
  // Bytes of the file outside the payload (its header and checksum): written, neither counted nor
  // summed.
  void raw(const void* data, std::size_t size) {
    if (out_) out_->write(data, size);
  }
  // Writes what is left.
  void flush() {
    if (out_) out_->flush();
  }
  // The checksum covers the bytes written so far and none after (the motion, checked by blocks).
  void stop_summing() {
    summing_ = false;
    summed_ = size_;
  }
  std::uint64_t summed() const { return summed_; }
  // Whether the bytes are written (not only counted).
  bool writes() const { return out_.has_value(); }
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
  // A list whose items start on a kAlign boundary of the file (after its count and zero padding).
  template <typename T>
  void aligned(const T* data, std::size_t n) {
    static_assert(std::is_trivially_copyable<T>::value, "pod only");
    pod<std::uint64_t>(n);
    static const char zeros[kAlign] = {};
    bytes(zeros, (kAlign - (kHeader + size_) % kAlign) % kAlign);
    bytes(data, n * sizeof(T));
  }
  // The same for samples, a few MB at a time, giving each piece's pages back after it when they
  // are read from a file's mapping (the spilled motion of a long build: engine/core/spill.h).
  template <typename T>
  void aligned(const Samples<T>& values) {
    pod<std::uint64_t>(values.size());
    static const char zeros[kAlign] = {};
    bytes(zeros, (kAlign - (kHeader + size_) % kAlign) % kAlign);
    constexpr std::size_t kPiece = (std::size_t{4} << 20) / sizeof(T);
    for (std::size_t i = 0; i < values.size(); i += kPiece) {
      const std::size_t m = std::min(kPiece, values.size() - i);
      bytes(values.data() + i, m * sizeof(T));
      values.release_pages(i, m);
    }
  }
  std::uint64_t size() const { return size_; }
  std::uint64_t checksum() const { return sum_.value(); }

 private:
  static constexpr std::size_t kChunk = 1 << 16;
  std::optional<BlockWriter> out_;
  Checksum sum_;
  std::uint64_t size_ = 0;
  bool summing_ = true;
  std::uint64_t summed_ = 0;
};

// Where the payload's bytes are: a mapped file (whose pages a pass gives back as it goes) or a
// buffer; `owner` keeps them alive for the arrays read in place.
struct Source {
  const char* data = nullptr;  // the whole file
  std::size_t size = 0;
  const MappedFile* file = nullptr;
  std::shared_ptr<const void> owner;
  void release(std::size_t offset, std::size_t n) const {
    if (file) file->release(offset, n);
  }
};

// Runs visit(chunk, count) over n items of T at p in chunks of a few MB, giving each chunk's pages
// back after it, so a pass over a large array does not leave it resident.
template <typename T, typename F>
void in_chunks(const Source& src, const T* p, std::size_t n, const F& visit) {
  constexpr std::size_t kChunk = (std::size_t{4} << 20) / sizeof(T);
  for (std::size_t i = 0; i < n; i += kChunk) {
    const std::size_t m = std::min(kChunk, n - i);
    visit(p + i, i, m);
    src.release(static_cast<std::size_t>(reinterpret_cast<const char*>(p + i) - src.data), m * sizeof(T));
  }
}

// n value-initialised values for a large array the load fills: allocated, advised to take huge
// pages (engine/core/files.h advise_huge_pages), and only then touched. The nodes and edges a load
// copies are its private memory (324 MiB for a 19 h reference), whose first touch in 4 KiB pages
// was a sixth of the CPU time of a reenactment from it.
template <typename T>
std::vector<T> huge_vector(std::size_t n) {
  std::vector<T> v;
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
  v.resize(n);
  return v;
}

// Reads the payload front to back, adding every byte it takes to the checksum as it goes, so one
// pass both checks and reads the file: the large arrays are validated chunk by chunk while they are
// summed, and each chunk's pages are given back after it.
class Reader {
 public:
  Reader(const char* data, std::size_t size, const std::string& path, const Source& src)
      : data_(data), size_(size), path_(path), src_(src) {}
  template <typename T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    consume(sizeof(T));
    return v;
  }
  std::string str() {
    const std::uint32_t n = pod<std::uint32_t>();
    need(n);
    std::string s(data_ + pos_, n);
    consume(n);
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
    consume(v.size() * sizeof(T));
    return v;
  }
  // n items of T converted one by one (for arrays whose memory layout is not the file's).
  template <typename T, typename F>
  void items(std::size_t n, const F& take) {
    need(n * sizeof(T));
    constexpr std::size_t kChunk = 8192;
    for (std::size_t i = 0; i < n; i += kChunk) {
      const std::size_t m = std::min(kChunk, n - i);
      for (std::size_t j = 0; j < m; ++j) {
        T v;
        std::memcpy(&v, data_ + pos_ + j * sizeof(T), sizeof(T));
        take(i + j, v);
      }
      consume(m * sizeof(T));
    }
  }
  // The start of a list written by Writer::aligned: its count and zero padding. Its items are
  // next, at the pointer returned; read them with in_place.
  template <typename T>
  std::pair<const T*, std::size_t> aligned() {
    const std::uint64_t n = pod<std::uint64_t>();
    const std::size_t pad = (kAlign - (kHeader + pos_) % kAlign) % kAlign;
    need(pad);
    for (std::size_t i = 0; i < pad; ++i)
      if (data_[pos_ + i] != 0) fail("padding that is not zero");
    consume(pad);
    if (n > (size_ - pos_) / sizeof(T)) fail("a list is longer than the file");
    return {reinterpret_cast<const T*>(data_ + pos_), static_cast<std::size_t>(n)};
  }
  // The n items of T that follow (an aligned list's): visit(chunk, first, count) over chunks of a
  // few MB, each summed after its visit and (`release`) its pages given back, so a pass over a large
  // array does not leave it resident. The items stay readable in place (they live as long as the
  // bytes).
  template <typename T, typename F>
  void in_place(std::size_t n, const F& visit, bool release = true) {
    need(n * sizeof(T));
    const T* p = reinterpret_cast<const T*>(data_ + pos_);
    constexpr std::size_t kChunk = (std::size_t{4} << 20) / sizeof(T);
    for (std::size_t i = 0; i < n; i += kChunk) {
      const std::size_t m = std::min(kChunk, n - i);
      visit(p + i, i, m);
      const std::size_t offset = static_cast<std::size_t>(data_ + pos_ - src_.data);
      consume(m * sizeof(T));
      if (release) src_.release(offset, m * sizeof(T));
    }
  }
  bool done() const { return pos_ == size_; }
  // What keeps the bytes alive, for the arrays read in place.
  const std::shared_ptr<const void>& owner() const { return src_.owner; }
  // The checksum of every byte read so far (up to stop_summing).
  std::uint64_t checksum() const { return sum_.value(); }
  // The bytes from here on are not summed (the motion, checked by blocks); returns the bytes
  // summed.
  std::size_t stop_summing() {
    summing_ = false;
    return pos_;
  }
  // Passes over the n items of T that follow without reading them (the motion's values, checked
  // by blocks: read_motion).
  template <typename T>
  void skip(std::size_t n) {
    need(n * sizeof(T));
    consume(n * sizeof(T));
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(error_at_byte(path_, static_cast<long long>(pos_ + kHeader), "damaged graph file: " + what));
  }

 private:
  void need(std::size_t n) {
    if (n > size_ - pos_) fail("unexpected end of data");
  }
  void consume(std::size_t n) {
    if (summing_) sum_.add(data_ + pos_, n);
    pos_ += n;
  }
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  const std::string& path_;
  const Source& src_;
  Checksum sum_;
  bool summing_ = true;
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

// The body: face dims, the face (frames x dims doubles, aligned), betas, gender, model; all empty
// for a graph of BVH references.
void write_body(Writer& w, const SmplxBody& b) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(b.expression_dims));
  w.aligned(b.expressions.data(), b.expressions.size());
  w.vec(b.betas);
  w.str(b.gender);
  w.str(b.model);
}

// The reference facts (graph/reference_facts.h): whether they are known (0 for a graph made by
// hand without them: then nothing else is), the largest root step, the root's extent (low, high),
// the legs' knee hinges (u32 count, then 3 doubles each), the foot contacts (u8 a frame, aligned)
// and the beat end costs (f32 a frame, aligned).
void write_reference_facts(Writer& w, const MotionGraph& g) {
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

// The checksum of the frames of one motion block: their rotations, then their translations.
std::uint64_t motion_block_sum(const Motion& m, std::size_t first, std::size_t frames) {
  const std::size_t joints = m.skeleton.joints.size();
  Checksum c;
  c.add(m.rotations.data() + first * joints, frames * joints * sizeof(glm::dquat));
  c.add(m.translations.data() + first * joints, frames * joints * sizeof(glm::dvec3));
  return c.value();
}

// Blocks whose pages a pass over the motion gives back together.
constexpr std::size_t kReleaseBlocks = 32;

// Gives back the pages of motion values from .. to - 1 (of both arrays) when they are read in place
// from a file's mapping, from the page boundary at or before `from` (blocks do not end on page
// boundaries: a stretch's last page, part of the next block's, goes with the next stretch).
void release_motion(const Motion& m, std::size_t from, std::size_t to) {
  auto back_to_page = [](std::size_t value, std::size_t size) { return value * size / kAlign * kAlign / size; };
  const std::size_t r = back_to_page(from, sizeof(glm::dquat)), t = back_to_page(from, sizeof(glm::dvec3));
  m.rotations.release_pages(r, to - r);
  m.translations.release_pages(t, to - t);
}

// The motion, last: frames per block, each block's checksum (the last values the file's checksum
// covers), then the rotations and the translations (aligned), which the blocks' checksums cover.
// Counting (nothing written), the checksums are zeros of the same size.
void write_motion(Writer& w, const Motion& m, const Samples<double>* key_poses) {
  const std::size_t frames = static_cast<std::size_t>(m.frame_count), joints = m.skeleton.joints.size();
  std::vector<std::uint64_t> sums((frames + kMotionBlockFrames - 1) / kMotionBlockFrames);
  std::size_t stretch = 0;  // the first block whose pages have not been given back
  for (std::size_t b = 0; b < sums.size() && w.writes(); ++b) {
    const std::size_t first = b * kMotionBlockFrames, n = std::min<std::size_t>(kMotionBlockFrames, frames - first);
    sums[b] = motion_block_sum(m, first, n);
    if (b + 1 - stretch == kReleaseBlocks || b + 1 == sums.size()) {  // a long build's motion is spilled to a file
      release_motion(m, stretch * kMotionBlockFrames * joints, (first + n) * joints);
      stretch = b + 1;
    }
  }
  w.pod<std::uint32_t>(kMotionBlockFrames);
  w.vec(sums);
  w.stop_summing();
  if (key_poses) w.aligned(*key_poses);
  w.aligned(m.rotations);
  w.aligned(m.translations);
}

// Format 9's key poses, where the file's checksum covers them: their count of values and each key's
// checksum (key_pose_sum; zeros when counting). The values follow the motion's block checksums,
// outside the file's checksum (write_motion).
void write_key_pose_sums(Writer& w, const MotionGraph& g) {
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  const std::size_t keys = g.key_poses.empty() ? 0 : g.key_poses.size() / dims;
  std::vector<std::uint64_t> sums(keys);
  std::size_t stretch = 0;  // the first key whose pages have not been given back
  for (std::size_t k = 0; k < keys && w.writes(); ++k) {
    sums[k] = checksum_of(g.key_poses.data() + k * dims, dims * sizeof(double));
    if ((k + 1 - stretch) * dims * sizeof(double) >= (std::size_t{4} << 20) || k + 1 == keys) {
      g.key_poses.release_pages(stretch * dims, (k + 1 - stretch) * dims);  // spilled by a long build
      stretch = k + 1;
    }
  }
  w.pod<std::uint64_t>(g.key_poses.size());
  w.vec(sums);
}

// The key poses' sketch: axes per part (u32), the basis (u64 count, doubles), the scale, the
// values (aligned: read in place).
void write_key_sketch(Writer& w, const KeyPoseSketch& s) {
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(s.axes));
  w.vec(s.basis);
  w.pod(s.scale);
  w.aligned(s.values.data(), s.values.size());
}

void write_payload(Writer& w, const MotionGraph& g, std::uint32_t version) {
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

  // Nodes: every frame's kinds, then the labels of the keyword nodes only.
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
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(g.speech_dims));
  w.aligned(g.speech.data(), g.speech.size());
  w.aligned(g.activity.data(), g.activity.size());
  if (version >= 9)
    write_key_pose_sums(w, g);
  else
    w.aligned(g.key_poses);
  if (version >= 8) write_key_sketch(w, g.key_sketch);
  write_reference_facts(w, g);
  write_body(w, g.body);
  write_motion(w, g.motion, version >= 9 ? &g.key_poses : nullptr);
}

// How many of p[0 .. n) are finite. x - x is 0 for a finite x and NaN for an infinite or NaN one,
// and a count without an early exit vectorises: the key poses' pass (650 MB at 19 h, 55 joints)
// ran at a value per cycle with std::isfinite and a short-circuit, a load's largest cost.
template <typename T>
std::size_t count_finite(const T* p, std::size_t n) {
  std::size_t good = 0;
  for (std::size_t i = 0; i < n; ++i) good += (p[i] - p[i] == T(0)) ? 1 : 0;
  return good;
}

// The speech features: none, or frames x dims finite values.
void read_speech(Reader& r, const Source& src, MotionGraph& g) {
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

// The key poses' sketch (write_key_sketch): none (axes 0: a graph made by hand may have key poses
// without one), or `axes` (1 to 64, at most half the pose's
// values) per part, an orthonormal basis zero off its part, a finite scale and keys x 2 axes
// finite values, read in place.
void read_key_sketch(Reader& r, const Source& src, MotionGraph& g, bool has_key_poses) {
  KeyPoseSketch& s = g.key_sketch;
  const std::size_t axes = r.pod<std::uint32_t>();
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton)), half = dims / 2;
  if (axes > 64 || axes > half) r.fail("implausible key sketch axes");
  if (axes > 0 && !has_key_poses) r.fail("a key sketch without key poses");
  s.axes = static_cast<int>(axes);
  s.basis = r.vec<double>();
  if (s.basis.size() != 2 * axes * dims) r.fail("the key sketch's basis disagrees with its axes x pose values");
  s.scale = r.pod<double>();
  if (!(s.scale >= 0.0 && std::isfinite(s.scale))) r.fail("the key sketch's scale is negative or not finite");
  // Orthonormal rows (within 1e-12), each zero off its part: what makes the bound a bound.
  for (std::size_t i = 0; i < 2 * axes; ++i) {
    const double* row = s.basis.data() + i * dims;
    const bool positions = i < axes;
    for (std::size_t v = 0; v < dims; ++v)
      if (!std::isfinite(row[v]) || (row[v] != 0.0 && (v < half) != positions))
        r.fail("the key sketch's basis is not zero off its part");
    for (std::size_t k = 0; k <= i; ++k) {
      const double* other = s.basis.data() + k * dims;
      double dot = 0.0;
      for (std::size_t v = 0; v < dims; ++v) dot += row[v] * other[v];
      if (!(std::abs(dot - (k == i ? 1.0 : 0.0)) <= 1e-12)) r.fail("the key sketch's basis is not orthonormal");
    }
  }
  const auto [values, n] = r.aligned<double>();
  if (n != g.keys.size() * 2 * axes) r.fail("the key sketch's values disagree with key nodes x axes");
  bool finite = true;
  r.in_place<double>(n,
                     [&](const double* p, std::size_t, std::size_t m) { finite = finite && count_finite(p, m) == m; });
  if (!finite) r.fail("a key sketch value is not finite");
  s.values = Samples<double>::view(values, n, src.owner);
}

// The key nodes' junction poses: none, or keys x junction_pose_dims finite values.
void read_key_poses(Reader& r, const Source& src, MotionGraph& g) {
  const auto [poses, n] = r.aligned<double>();
  if (n != 0 && n != g.keys.size() * static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton)))
    r.fail("key poses disagree with key nodes x pose values");
  bool finite = true;
  r.in_place<double>(n,
                     [&](const double* p, std::size_t, std::size_t m) { finite = finite && count_finite(p, m) == m; });
  if (!finite) r.fail("a key pose value is not finite");
  g.key_poses = Samples<double>::view(poses, n, src.owner);
}

// Format 9's key pose count and checksums (write_key_pose_sums), in the part the file's checksum
// covers; the values are read after the motion's block checksums (read_motion).
struct KeyPoseTail {
  std::size_t values = 0;
  std::shared_ptr<KeyPoseChecks> checks;
};

KeyPoseTail read_key_pose_sums(Reader& r, const std::string& path, const MotionGraph& g) {
  KeyPoseTail t;
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  const std::uint64_t n = r.pod<std::uint64_t>();
  if (n != 0 && n != g.keys.size() * dims) r.fail("key poses disagree with key nodes x pose values");
  t.values = static_cast<std::size_t>(n);
  t.checks = std::make_shared<KeyPoseChecks>();
  t.checks->path = path;
  t.checks->sums = r.vec<std::uint64_t>();
  if (t.checks->sums.size() != (n == 0 ? 0 : g.keys.size())) r.fail("key pose checksums disagree with the key nodes");
  return t;
}

// What checking key poses found.
struct KeyCheck {
  bool sound = true;
  bool damaged = false;  // the key's checksum is wrong (else: a value is not finite)
  std::size_t key = 0;   // the first key that is not sound
};

// Checks the poses of keys k0 .. k1 - 1 against their checksums and for finite values; stops at the
// first that fails. `release`: the pages are given back every few MB (a pass over all of them
// leaves nothing resident).
KeyCheck check_key_poses(const MotionGraph& g, const KeyPoseChecks& kc, std::size_t k0, std::size_t k1, bool release) {
  const std::size_t dims = static_cast<std::size_t>(junction_pose_dims(g.motion.skeleton));
  KeyCheck out;
  std::size_t stretch = k0;  // the first key whose pages have not been given back
  for (std::size_t k = k0; k < k1; ++k) {
    const double* pose = g.key_poses.data() + k * dims;
    if (checksum_of(pose, dims * sizeof(double)) != kc.sums[k] || count_finite(pose, dims) != dims) {
      out.sound = false;
      out.damaged = checksum_of(pose, dims * sizeof(double)) != kc.sums[k];
      out.key = k;
      return out;
    }
    if (release && ((k + 1 - stretch) * dims * sizeof(double) >= (std::size_t{4} << 20) || k + 1 == k1)) {
      g.key_poses.release_pages(stretch * dims, (k + 1 - stretch) * dims);
      stretch = k + 1;
    }
  }
  return out;
}

// Which key pose check_key_poses did not find sound, for errors.
std::string key_pose_named(const MotionGraph& g, const KeyCheck& c) {
  return "the junction pose of key node " + std::to_string(c.key) + " (frame " + std::to_string(g.keys[c.key]) + ")";
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Reads write_reference_facts' section: all of it, or (a graph made by hand) none of it. Each
// value is checked as the assembly and the planner use it.
void read_reference_facts(Reader& r, const Source& src, MotionGraph& g) {
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

// Reads write_body's section (the face is copied: SmplxBody owns its arrays).
void read_body(Reader& r, MotionGraph& g) {
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

// The nodes, and into g their index (MotionGraph::keys, breaks) taken on the way.
std::vector<NodeInfo> read_nodes(Reader& r, std::size_t frames, MotionGraph& g) {
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

// The edges, and the mean weight of the unnatural ones (MotionGraph::transition_weight, summed in
// edge order as mean_transition_weight does). Each edge's natural flag must be is_natural_edge's:
// a natural edge steps to the next frame with weight 0, a transition never steps to the next frame.
// Format 10's row starts and targets and format 9's weights are read in place (aligned, their
// pages kept mapped for the flags' pass that follows); older formats' are copied.
void read_edges(Reader& r, const Source& src, std::uint32_t version, std::vector<NodeInfo> nodes, MotionGraph& out) {
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

// The motion's frame rate and frame count (its values are the file's last section: read_motion).
void read_motion_header(Reader& r, Motion& m) {
  m.fps = r.pod<double>();
  m.frame_count = r.pod<std::int32_t>();
  if (!(m.fps >= limits::kMinFps && m.fps <= limits::kMaxFps))
    r.fail("frame rate " + format_number(m.fps) + " is outside " + format_number(limits::kMinFps) + " to " +
           format_number(limits::kMaxFps) + " fps");
  if (m.frame_count < 1 || m.frame_count > limits::kMaxFrames) r.fail("invalid frame count");
}

// What checking motion blocks found.
struct BlockCheck {
  bool sound = true;
  bool damaged = false;                         // a block's checksum is wrong (else: a value is bad)
  std::size_t first_frame = 0, last_frame = 0;  // the damaged block's frames
  std::size_t bad_frame = 0;                    // the first frame with a value that is not sound
};

// Checks blocks b0 .. b1 - 1 of g's motion: each block's checksum, then its values (unit
// rotations, finite translations); stops at the first that fails. `release`: each block's pages
// are given back after it (a pass over all of a served graph's motion leaves nothing resident).
BlockCheck check_motion_blocks(const Motion& m, const MotionBlocks& mb, std::size_t b0, std::size_t b1, bool release) {
  const std::size_t frames = static_cast<std::size_t>(m.frame_count), joints = m.skeleton.joints.size();
  const std::size_t per = static_cast<std::size_t>(mb.block_frames);
  // A unit rotation: its squared norm within 1e-6 of 1, which no rotation with an infinite or NaN
  // part has (the comparison with NaN is false). s - s is 0 for a finite sum and NaN for an
  // infinite or NaN one (std::isfinite, a call, would keep the loop scalar). Each block is checked
  // as a whole (a count with no early exit, so the loops vectorise) and searched for its first bad
  // value only when it has one.
  auto unit = [](const glm::dquat& q) { return std::abs(glm::dot(q, q) - 1.0) <= 1e-6; };
  auto finite = [](const glm::dvec3& v) {
    const double s = v.x + v.y + v.z;
    return s - s == 0.0;
  };
  BlockCheck out;
  std::size_t stretch = b0;  // the first block whose pages have not been given back
  for (std::size_t b = b0; b < b1; ++b) {
    const std::size_t first = b * per, n = std::min(per, frames - first);
    const glm::dquat* q = m.rotations.data() + first * joints;
    const glm::dvec3* t = m.translations.data() + first * joints;
    const std::size_t values = n * joints;
    if (motion_block_sum(m, first, n) != mb.sums[b]) {
      out.sound = false;
      out.damaged = true;
      out.first_frame = first;
      out.last_frame = first + n - 1;
      return out;
    }
    std::size_t good = 0;
    for (std::size_t k = 0; k < values; ++k) good += (unit(q[k]) ? 1 : 0) + (finite(t[k]) ? 1 : 0);
    if (good != 2 * values) {
      std::size_t k = 0;
      while (unit(q[k]) && finite(t[k])) ++k;
      out.sound = false;
      out.bad_frame = first + k / joints;
      return out;
    }
    if (release && (b + 1 - stretch == kReleaseBlocks || b + 1 == b1)) {
      release_motion(m, stretch * per * joints, (first + n) * joints);
      stretch = b + 1;
    }
  }
  return out;
}

// The motion, the payload's last section (write_motion). `summed_to(bytes)` is called where the
// file's checksum stops, before any motion value is read; it checks the checksum, so the block
// checksums are the file's. The motion's values are then checked by blocks, all of them now
// (MotionCheck::OnLoad, or a graph that lacks what a reenactment would otherwise compute from
// every frame) or each when first used (graph_check_frames).
template <typename SummedTo, typename Damaged>
void read_motion(Reader& r, MotionGraph& g, const std::string& path, MotionCheck mode, const SummedTo& summed_to,
                 const Damaged& damaged, KeyPoseTail* key_poses) {
  Motion& m = g.motion;
  const std::uint32_t per = r.pod<std::uint32_t>();
  if (per < 1 || per > (1u << 20)) r.fail("implausible motion block size");
  const std::size_t frames = static_cast<std::size_t>(m.frame_count), joints = m.skeleton.joints.size();
  const std::size_t blocks = (frames + per - 1) / per;
  auto mb = std::make_shared<MotionBlocks>();
  mb->path = path;
  mb->block_frames = static_cast<int>(per);
  mb->sums = r.vec<std::uint64_t>();
  if (mb->sums.size() != blocks) r.fail("motion block checksums disagree with the frame count");
  summed_to(r.stop_summing());
  if (key_poses) {  // format 9: the key poses, each checked now (OnLoad) or when first read (OnUse)
    const auto [poses, n] = r.aligned<double>();
    if (n != key_poses->values) r.fail("key poses disagree with key nodes x pose values");
    r.skip<double>(n);
    g.key_poses = Samples<double>::view(poses, n, r.owner());
    KeyPoseChecks& kc = *key_poses->checks;
    kc.checked.assign(kc.sums.size(), 0);
    if (mode == MotionCheck::OnUse) {
      if (!kc.sums.empty()) g.unchecked_key_poses = key_poses->checks;
    } else {
      const KeyCheck c = check_key_poses(g, kc, 0, kc.sums.size(), true);
      if (c.damaged) throw damaged();
      if (!c.sound) r.fail(key_pose_named(g, c) + " holds a value that is not finite");
    }
  }
  // Sizes are checked before values: the rotations' count, then the translations'.
  const std::size_t expected = frames * joints;
  const auto rotations = r.aligned<glm::dquat>();
  if (rotations.second != expected) r.fail("motion size disagrees with frames x joints");
  r.skip<glm::dquat>(expected);
  const auto translations = r.aligned<glm::dvec3>();
  if (translations.second != expected) r.fail("motion size disagrees with frames x joints");
  r.skip<glm::dvec3>(expected);
  m.rotations = Samples<glm::dquat>::view(rotations.first, expected, r.owner());
  m.translations = Samples<glm::dvec3>::view(translations.first, expected, r.owner());
  mb->checked.assign(blocks, 0);
  const bool computed_from_motion = !g.capture.known || (g.key_poses.empty() && !g.keys.empty());
  if (mode == MotionCheck::OnUse && !computed_from_motion) {
    g.unchecked_motion = std::move(mb);
    return;
  }
  const BlockCheck c = check_motion_blocks(m, *mb, 0, blocks, true);
  if (c.damaged) throw damaged();
  if (!c.sound)
    r.fail("frame " + std::to_string(c.bad_frame) + " holds a value that is not finite or not a unit rotation");
}

template <typename SummedTo, typename Damaged>
MotionGraph read_payload(Reader& r, const Source& src, const std::string& path, std::uint32_t version, MotionCheck mode,
                         const SummedTo& summed_to, const Damaged& damaged) {
  MotionGraph g;
  g.params = read_params(r);
  g.motion.skeleton = read_skeleton(r);
  long long covered = 0;
  g.clips = read_clips(r, covered);
  read_motion_header(r, g.motion);
  if (covered != g.motion.frame_count) r.fail("clips do not cover the motion");
  read_edges(r, src, version, read_nodes(r, static_cast<std::size_t>(g.motion.frame_count), g), g);
  read_speech(r, src, g);
  KeyPoseTail tail;
  if (version >= 9)
    tail = read_key_pose_sums(r, path, g);
  else
    read_key_poses(r, src, g);
  if (version >= 8) read_key_sketch(r, src, g, version >= 9 ? tail.values > 0 : !g.key_poses.empty());
  read_reference_facts(r, src, g);
  read_body(r, g);
  read_motion(r, g, path, mode, summed_to, damaged, version >= 9 ? &tail : nullptr);
  if (!r.done()) r.fail("trailing bytes after the motion");
  return g;
}

MotionGraph parse_graph(const Source& src, const std::string& path, MotionCheck mode) {
  const char* bytes = src.data;
  const std::size_t total = src.size;
  if (total < sizeof kMagic || std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
    throw Error(path + ": not a gmg graph file (build one with 'gmg build')");
  if (total < sizeof kMagic + sizeof(std::uint32_t)) throw Error(error_at_byte(path, 8, "graph file is truncated"));
  std::uint32_t version = 0;
  std::memcpy(&version, bytes + 8, sizeof version);
  if (version < kOldestGraphFormatRead || version > kVersion)
    throw Error(path + ": graph file format version " + std::to_string(version) + ", this gmg reads versions " +
                std::to_string(kOldestGraphFormatRead) + " to " + std::to_string(kVersion) +
                ": rebuild it with 'gmg build'");
  if (total < kHeader + sizeof(std::uint64_t)) throw Error(error_at_byte(path, 12, "graph file is truncated"));
  std::uint64_t size = 0, summed = 0;
  std::memcpy(&size, bytes + 12, sizeof size);
  std::memcpy(&summed, bytes + 20, sizeof summed);
  const std::size_t present = total - kHeader - sizeof(std::uint64_t);
  if (size != present)
    throw Error(error_at_byte(path, 12,
                              "graph file is truncated or has trailing bytes (payload " + std::to_string(size) +
                                  " bytes declared, " + std::to_string(present) + " present)"));
  if (summed > present)
    throw Error(error_at_byte(path, 20, "damaged graph file: its checksum covers more than the payload"));
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes + kHeader + present, sizeof sum);
  auto damaged = [&] {
    if (src.file) src.file->check_unchanged();  // a file cut short while it was read reads as zeros
    return Error(path + ": graph file is damaged (checksum mismatch)");
  };
  // One pass checks the fields and sums the bytes (Reader) up to the motion, where the sum is
  // checked; the motion is checked by blocks (read_motion). A damaged file may fail a field's check
  // before its sum is known: then the part the checksum covers is summed, and a wrong checksum is
  // what is said.
  Reader r(bytes + kHeader, present, path, src);
  auto summed_to = [&](std::size_t at) {
    if (at != summed) r.fail("its checksum does not end where the motion starts");
    if (r.checksum() != sum) throw damaged();
  };
  try {
    return naming_memory_errors(path, "reading the graph",
                                [&] { return read_payload(r, src, path, version, mode, summed_to, damaged); });
  } catch (const Error&) {
    Checksum checksum;
    in_chunks(src, bytes + kHeader, static_cast<std::size_t>(summed),
              [&](const char* p, std::size_t, std::size_t n) { checksum.add(p, n); });
    if (sum != checksum.value()) throw damaged();
    throw;
  }
}

}  // namespace

void MotionGraph::check_unchanged() const {
  if (source) source->check_unchanged();
}

void graph_save(const std::string& path, const MotionGraph& g, std::uint32_t version) {
  if (version < kOldestGraphFormatRead || version > kVersion)
    throw Error(path + ": cannot write graph file format version " + std::to_string(version));
  Writer counter(nullptr);
  write_payload(counter, g, version);
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        Writer w(&out);
        w.raw(kMagic, sizeof kMagic);
        w.raw(&version, sizeof version);
        const std::uint64_t size = counter.size(), summed = counter.summed();
        w.raw(&size, sizeof size);
        w.raw(&summed, sizeof summed);
        write_payload(w, g, version);
        if (w.size() != size || w.summed() != summed) throw Error(path + ": graph changed while it was written");
        const std::uint64_t sum = w.checksum();
        w.raw(&sum, sizeof sum);
        w.flush();
      },
      true);
}

MotionGraph graph_load(const std::string& path, MotionCheck motion) {
  auto file = std::make_shared<const MappedFile>(path);
  Source src{file->data(), file->size(), file.get(), file};
  MotionGraph g = parse_graph(src, path, motion);
  // No MADV_RANDOM: a reenactment reads the key poses and its paths' frames here and there, but
  // on a file not yet in the page cache the kernel's readahead makes its first run 1.8 times as
  // fast (19 h graph: 3.0 s against 5.4 s, docs/performance.md) for the same later runs.
  g.source = std::move(file);
  g.check_unchanged();
  return g;
}

MotionGraph graph_parse(const std::string& bytes, const std::string& path) {
  // The arrays read in place need bytes that outlive the call.
  auto copy = std::make_shared<const std::string>(bytes);
  return parse_graph(Source{copy->data(), copy->size(), nullptr, copy}, path, MotionCheck::OnLoad);
}

void graph_check_key_poses(const MotionGraph& g, std::size_t first, std::size_t last) {
  KeyPoseChecks* kc = g.unchecked_key_poses.get();
  if (!kc || kc->sums.empty() || first >= kc->sums.size() || first > last) return;
  last = std::min(last, kc->sums.size() - 1);
  const std::lock_guard<std::mutex> lock(kc->mutex);
  for (std::size_t k = first; k <= last; ++k) {
    if (kc->checked[k]) continue;
    const KeyCheck c = check_key_poses(g, *kc, k, k + 1, false);
    if (c.damaged) {
      g.check_unchanged();  // a file cut short or rewritten since the load
      throw Error(kc->path + ": graph file is damaged (checksum mismatch in " + key_pose_named(g, c) + ")");
    }
    if (!c.sound)
      throw Error(kc->path + ": damaged graph file: " + key_pose_named(g, c) + " holds a value that is not finite");
    kc->checked[k] = 1;
  }
}

void graph_check_frames(const MotionGraph& g, int first, int last) {
  MotionBlocks* mb = g.unchecked_motion.get();
  if (!mb || g.frame_count() < 1) return;
  const int per = mb->block_frames;
  const int lo = std::clamp(first, 0, g.frame_count() - 1), hi = std::clamp(last, 0, g.frame_count() - 1);
  if (lo > hi) return;
  const std::lock_guard<std::mutex> lock(mb->mutex);
  bool read = false;
  for (std::size_t b = static_cast<std::size_t>(lo / per); b <= static_cast<std::size_t>(hi / per); ++b) {
    if (mb->checked[b]) continue;
    read = true;
    const BlockCheck c = check_motion_blocks(g.motion, *mb, b, b + 1, false);
    if (c.damaged) {
      g.check_unchanged();  // a file cut short or rewritten since the load
      throw Error(mb->path + ": graph file is damaged (checksum mismatch in frames " + std::to_string(c.first_frame) +
                  " to " + std::to_string(c.last_frame) + ")");
    }
    if (!c.sound)
      throw Error(mb->path + ": damaged graph file: frame " + std::to_string(c.bad_frame) +
                  " holds a value that is not finite or not a unit rotation");
    mb->checked[b] = 1;
  }
  // The pages read are given back, all of the motion's: a read maps the page cache's whole large
  // folio around it (2 MB here), more than the block it reads.
  if (read) motion_release_pages(g.motion);
}

}  // namespace gmg
