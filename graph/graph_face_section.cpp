// The face speech section of a graph file (format 12 on; docs/graph_format.md): what the face
// track reads of the reference's speech under every frame (graph/face_speech.h).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/math.h"
#include "graph/graph_sections.h"

namespace gmg {

void write_face_speech(ArchiveWriter& w, const MotionGraph& g) {
  const FaceSpeech& f = g.face_speech;
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(f.feature_dims));
  w.aligned(f.features);
  w.aligned(f.jaw);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(f.symbols.size()));
  for (const std::string& s : f.symbols) w.str(s);
  std::vector<double> starts, ends;
  std::vector<std::uint32_t> symbols;
  for (const ReferencePhone& p : f.phones) {
    starts.push_back(p.start);
    ends.push_back(p.end);
    symbols.push_back(p.symbol);
  }
  w.vec(starts);
  w.vec(ends);
  w.vec(symbols);
}

void read_face_speech(ArchiveReader& r, const ArchiveSource& src, MotionGraph& g) {
  FaceSpeech& f = g.face_speech;
  const auto frames = static_cast<std::size_t>(g.frame_count());
  const std::uint32_t dims = r.pod<std::uint32_t>();
  if (dims > 64) r.fail("implausible face feature count");
  f.feature_dims = static_cast<int>(dims);
  const auto [features, features_n] = r.aligned<float>();
  if (features_n != frames * dims) r.fail("the face features disagree with frames x features");
  bool finite = true;
  r.in_place<float>(features_n,
                    [&](const float* p, std::size_t, std::size_t n) { finite = finite && count_finite(p, n) == n; });
  if (!finite) r.fail("a face feature is not finite");
  const auto [jaw, jaw_n] = r.aligned<float>();
  if (jaw_n != 0 && jaw_n != frames) r.fail("the jaw's opening disagrees with the frame count");
  bool valid = true;
  r.in_place<float>(jaw_n, [&](const float* p, std::size_t, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) valid = valid && p[i] >= 0.0f && p[i] <= static_cast<float>(kPi);
  });
  if (!valid) r.fail("a jaw angle is not between 0 and pi");
  f.features = Samples<float>::view(features, features_n, src.owner);
  f.jaw = Samples<float>::view(jaw, jaw_n, src.owner);
  const std::uint32_t symbol_count = r.pod<std::uint32_t>();
  if (symbol_count > 10000) r.fail("implausible phone symbol count");
  for (std::uint32_t i = 0; i < symbol_count; ++i) {
    f.symbols.push_back(r.str());
    if (f.symbols.back().empty() || f.symbols.back().size() > 64) r.fail("a phone symbol is empty or too long");
  }
  const std::vector<double> starts = r.vec<double>(), ends = r.vec<double>();
  const std::vector<std::uint32_t> symbols = r.vec<std::uint32_t>();
  if (starts.size() != ends.size() || starts.size() != symbols.size()) r.fail("the phones' lists differ in length");
  double last_end = 0.0;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const ReferencePhone p{starts[i], ends[i], symbols[i]};
    if (!(std::isfinite(p.start) && std::isfinite(p.end) && p.start >= last_end && p.end >= p.start &&
          p.end <= static_cast<double>(frames)))
      r.fail("phone " + std::to_string(i + 1) + " is not inside the frames after the phone before it");
    if (p.symbol >= f.symbols.size()) r.fail("phone " + std::to_string(i + 1) + " has no symbol");
    f.phones.push_back(p);
    last_end = p.end;
  }
}

}  // namespace gmg
