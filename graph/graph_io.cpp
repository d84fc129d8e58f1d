// Saving and loading built graphs: the file's header and checksum around a payload of sections
// (graph/graph_sections.h, graph/graph_motion_sections.h), written and read with the archive of
// graph/graph_archive.h. The layout and its versions: docs/graph_format.md.
#include <algorithm>
#include <cstring>
#include <functional>
#include <memory>
#include <utility>

#include "engine/core/checksum.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/graph_archive.h"
#include "graph/graph_io.h"
#include "graph/graph_motion_sections.h"
#include "graph/graph_sections.h"

namespace gmg {
namespace {

void write_payload(ArchiveWriter& w, const MotionGraph& g, std::uint32_t version) {
  write_params(w, g.params);
  write_skeleton(w, g.motion.skeleton);
  write_clips(w, g.clips);
  write_motion_header(w, g.motion);
  write_nodes(w, g);
  write_edges(w, g, version);
  write_speech(w, g);
  if (version >= 9)
    write_key_pose_sums(w, g);
  else
    w.aligned(g.key_poses);
  if (version >= 8) write_key_sketch(w, g.key_sketch);
  write_reference_facts(w, g);
  if (version >= 11) write_layers(w, g);
  write_body(w, g.body);
  if (version >= 12) write_face_speech(w, g);
  write_motion(w, g.motion, version >= 9 ? &g.key_poses : nullptr);
}

MotionGraph read_payload(ArchiveReader& r, const ArchiveSource& src, const std::string& path, std::uint32_t version,
                         MotionCheck mode, const std::function<void(std::size_t)>& summed_to,
                         const std::function<Error()>& damaged) {
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
  if (version >= 11) read_layers(r, src, g);
  read_body(r, g);
  if (version >= 12) read_face_speech(r, src, g);
  read_motion(r, g, path, mode, summed_to, damaged, version >= 9 ? &tail : nullptr);
  if (!r.done()) r.fail("trailing bytes after the motion");
  return g;
}

MotionGraph parse_graph(const ArchiveSource& src, const std::string& path, MotionCheck mode) {
  const char* bytes = src.data;
  const std::size_t total = src.size;
  if (total < sizeof kGraphMagic || std::memcmp(bytes, kGraphMagic, sizeof kGraphMagic) != 0)
    throw Error(path + ": not a gmg graph file (build one with 'gmg build')");
  if (total < sizeof kGraphMagic + sizeof(std::uint32_t))
    throw Error(error_at_byte(path, 8, "graph file is truncated"));
  std::uint32_t version = 0;
  std::memcpy(&version, bytes + 8, sizeof version);
  if (version < kOldestGraphFormatRead || version > kGraphFormatVersion)
    throw Error(path + ": graph file format version " + std::to_string(version) + ", this gmg reads versions " +
                std::to_string(kOldestGraphFormatRead) + " to " + std::to_string(kGraphFormatVersion) +
                ": rebuild it with 'gmg build'");
  if (total < kGraphHeaderBytes + sizeof(std::uint64_t))
    throw Error(error_at_byte(path, 12, "graph file is truncated"));
  std::uint64_t size = 0, summed = 0;
  std::memcpy(&size, bytes + 12, sizeof size);
  std::memcpy(&summed, bytes + 20, sizeof summed);
  const std::size_t present = total - kGraphHeaderBytes - sizeof(std::uint64_t);
  if (size != present)
    throw Error(error_at_byte(path, 12,
                              "graph file is truncated or has trailing bytes (payload " + std::to_string(size) +
                                  " bytes declared, " + std::to_string(present) + " present)"));
  if (summed > present)
    throw Error(error_at_byte(path, 20, "damaged graph file: its checksum covers more than the payload"));
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes + kGraphHeaderBytes + present, sizeof sum);
  auto damaged = [&] {
    if (src.file) src.file->check_unchanged();  // a file cut short while it was read reads as zeros
    return Error(path + ": graph file is damaged (checksum mismatch)");
  };
  // One pass checks the fields and sums the bytes (ArchiveReader) up to the motion, where the sum is
  // checked; the motion is checked by blocks (read_motion). A damaged file may fail a field's check
  // before its sum is known: then the part the checksum covers is summed, and a wrong checksum is
  // what is said.
  // A file of an older version whose fields fail their checks may be a newer file whose version
  // field is damaged: the error says which version it was read as.
  const std::string note = version == kGraphFormatVersion ? std::string()
                                                          : " (read as format version " + std::to_string(version) +
                                                                ", which its header gives; this gmg reads versions " +
                                                                std::to_string(kOldestGraphFormatRead) + " to " +
                                                                std::to_string(kGraphFormatVersion) + ")";
  ArchiveReader r(bytes + kGraphHeaderBytes, present, path, src, note);
  auto summed_to = [&](std::size_t at) {
    if (at != summed) r.fail("its checksum does not end where the motion starts");
    if (r.checksum() != sum) throw damaged();
  };
  try {
    return naming_memory_errors(path, "reading the graph",
                                [&] { return read_payload(r, src, path, version, mode, summed_to, damaged); });
  } catch (const Error&) {
    Checksum checksum;
    in_chunks(src, bytes + kGraphHeaderBytes, static_cast<std::size_t>(summed),
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
  if (version < kOldestGraphFormatRead || version > kGraphFormatVersion)
    throw Error(path + ": cannot write graph file format version " + std::to_string(version));
  ArchiveWriter counter(nullptr);
  write_payload(counter, g, version);
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        ArchiveWriter w(&out);
        w.raw(kGraphMagic, sizeof kGraphMagic);
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
  ArchiveSource src{file->data(), file->size(), file.get(), file};
  MotionGraph g = parse_graph(src, path, motion);
  // No MADV_RANDOM: a reenactment reads the key poses and its paths' frames here and there, but
  // on a file not yet in the page cache the kernel's readahead makes its first run faster
  // (docs/decisions.md, "The graph file").
  g.source = std::move(file);
  g.check_unchanged();
  return g;
}

MotionGraph graph_parse(const std::string& bytes, const std::string& path) {
  // The arrays read in place need bytes that outlive the call.
  auto copy = std::make_shared<const std::string>(bytes);
  return parse_graph(ArchiveSource{copy->data(), copy->size(), nullptr, copy}, path, MotionCheck::OnLoad);
}

}  // namespace gmg
