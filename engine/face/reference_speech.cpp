#include "engine/face/reference_speech.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "audio/face_features.h"
#include "engine/core/error.h"
#include "engine/motion/body_parts.h"
#include "engine/motion/rotation.h"

namespace gmg {

FaceSpeech face_speech_of(const MotionGraph& g, const std::vector<ClipFaceSpeech>& clips) {
  constexpr int kDims = audio::FaceFeatures::kDims;
  FaceSpeech out;
  if (clips.size() != g.clips.size()) return out;  // clips the graph dropped: not known
  bool features = !clips.empty();
  for (std::size_t c = 0; c < clips.size(); ++c) {
    const std::size_t want = static_cast<std::size_t>(g.clips[c].frame_count) * kDims;
    if (!clips[c].features.empty() && clips[c].features.size() != want)
      throw Error(g.clips[c].name + ": its face features do not cover its frames");
    features = features && !clips[c].features.empty();
  }
  if (features) {
    out.feature_dims = kDims;
    std::vector<float>& v = out.features.vec();
    v.reserve(static_cast<std::size_t>(g.frame_count()) * kDims);
    for (const ClipFaceSpeech& c : clips) v.insert(v.end(), c.features.begin(), c.features.end());
  }
  const int jaw = jaw_joint(g.motion.skeleton);
  if (jaw >= 0) {
    std::vector<float>& a = out.jaw.vec();
    a.reserve(static_cast<std::size_t>(g.frame_count()));
    for (int f = 0; f < g.frame_count(); ++f)
      a.push_back(static_cast<float>(rotation_angle(g.motion.rotation(f, jaw))));
  }
  std::map<std::string, std::uint32_t> index;
  for (std::size_t c = 0; c < clips.size(); ++c) {
    const ClipInfo& clip = g.clips[c];
    const double first = clip.first_frame, last = clip.first_frame + clip.frame_count;
    double previous_end = first;
    for (const text::Phone& p : clips[c].phones) {
      const double start = std::max(previous_end, first + p.start * g.motion.fps);
      const double end = std::min(last, first + p.end * g.motion.fps);
      if (!(end > start)) continue;  // past the motion's end, or inside the phone before
      const auto [it, added] = index.try_emplace(p.symbol, static_cast<std::uint32_t>(out.symbols.size()));
      if (added) out.symbols.push_back(p.symbol);
      out.phones.push_back({start, end, it->second});
      previous_end = end;
    }
  }
  return out;
}

}  // namespace gmg
