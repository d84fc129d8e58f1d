#include "engine/face/reference_face.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg {

double ReferenceFace::face_distance(int a, int b) const {
  const float* fa = &face[static_cast<std::size_t>(a) * static_cast<std::size_t>(face_dims)];
  const float* fb = &face[static_cast<std::size_t>(b) * static_cast<std::size_t>(face_dims)];
  int k = 0;
  double d = 0.0;
  if (has_jaw()) d += std::abs(fa[k] - fb[k]), ++k;
  if (k < face_dims) {
    double sum = 0.0;
    for (int i = k; i < face_dims; ++i) sum += static_cast<double>(fa[i] - fb[i]) * (fa[i] - fb[i]);
    d += std::sqrt(sum / (face_dims - k));
  }
  return d;
}

namespace {

// Mean and spread of column c of a frames x dims array (spread 1 for a constant column).
void column_stats(const float* v, std::size_t frames, int dims, int c, double& mean, double& sd) {
  double sum = 0.0, sq = 0.0;
  for (std::size_t f = 0; f < frames; ++f) sum += v[f * static_cast<std::size_t>(dims) + static_cast<std::size_t>(c)];
  mean = frames > 0 ? sum / static_cast<double>(frames) : 0.0;
  for (std::size_t f = 0; f < frames; ++f) {
    const double d = v[f * static_cast<std::size_t>(dims) + static_cast<std::size_t>(c)] - mean;
    sq += d * d;
  }
  sd = frames > 1 ? std::sqrt(sq / static_cast<double>(frames - 1)) : 0.0;
  if (!(sd > 1e-9)) sd = 1.0;
}

// The phones of the graph with the silences between those of one clip, and each one's neighbours.
void add_phones(const MotionGraph& g, ReferenceFace& r) {
  const FaceSpeech& fs = g.face_speech;
  r.has_phones.assign(g.clips.size(), 0);
  std::vector<FacePhone> spoken;
  for (const ReferencePhone& p : fs.phones) {
    const int clip = r.clip_of[static_cast<std::size_t>(std::min(r.frames - 1, static_cast<int>(p.start)))];
    r.has_phones[static_cast<std::size_t>(clip)] = 1;
    spoken.push_back({p.start, p.end, fs.symbols[p.symbol], "", "", clip});
  }
  for (std::size_t i = 0; i < spoken.size(); ++i) {
    const FacePhone& p = spoken[i];
    const bool first_of_clip = i == 0 || spoken[i - 1].clip != p.clip;
    const double gap_from = first_of_clip ? r.clip_first[static_cast<std::size_t>(p.clip)] : spoken[i - 1].end;
    if (p.start - gap_from >= 1.0)  // a silence of a frame or more
      r.phones.push_back({gap_from, p.start, "", first_of_clip ? "" : spoken[i - 1].symbol, p.symbol, p.clip});
    r.phones.push_back(p);
    const bool last_of_clip = i + 1 == spoken.size() || spoken[i + 1].clip != p.clip;
    if (last_of_clip && r.clip_end[static_cast<std::size_t>(p.clip)] - p.end >= 1.0)
      r.phones.push_back(
          {p.end, static_cast<double>(r.clip_end[static_cast<std::size_t>(p.clip)]), "", p.symbol, "", p.clip});
  }
  for (std::size_t i = 0; i < r.phones.size(); ++i) {
    FacePhone& p = r.phones[i];
    const bool joined_before = i > 0 && r.phones[i - 1].clip == p.clip && r.phones[i - 1].end == p.start;
    const bool joined_after =
        i + 1 < r.phones.size() && r.phones[i + 1].clip == p.clip && r.phones[i + 1].start == p.end;
    p.left = joined_before ? r.phones[i - 1].symbol : "";
    p.right = joined_after ? r.phones[i + 1].symbol : "";
  }
}

}  // namespace

ReferenceFace reference_face(const MotionGraph& g) {
  const FaceSpeech& fs = g.face_speech;
  if (!fs.known()) throw Error("face track: the graph has no face speech (rebuild it with this gmg)");
  ReferenceFace r;
  r.fps = g.motion.fps;
  r.frames = g.frame_count();
  r.dims = fs.feature_dims;
  const auto frames = static_cast<std::size_t>(r.frames);
  r.mean.resize(static_cast<std::size_t>(r.dims));
  r.sd.resize(static_cast<std::size_t>(r.dims));
  for (int d = 0; d < r.dims; ++d)
    column_stats(fs.features.data(), frames, r.dims, d, r.mean[static_cast<std::size_t>(d)],
                 r.sd[static_cast<std::size_t>(d)]);
  r.z.resize(frames * static_cast<std::size_t>(r.dims));
  for (std::size_t f = 0; f < frames; ++f)
    for (int d = 0; d < r.dims; ++d) {
      const std::size_t i = f * static_cast<std::size_t>(r.dims) + static_cast<std::size_t>(d);
      r.z[i] = static_cast<float>((fs.features[i] - r.mean[static_cast<std::size_t>(d)]) /
                                  r.sd[static_cast<std::size_t>(d)]);
    }
  r.clip_of.resize(frames);
  for (std::size_t c = 0; c < g.clips.size(); ++c) {
    const ClipInfo& clip = g.clips[c];
    r.clip_first.push_back(clip.first_frame);
    r.clip_end.push_back(clip.first_frame + clip.frame_count);
    std::fill(r.clip_of.begin() + clip.first_frame, r.clip_of.begin() + clip.first_frame + clip.frame_count,
              static_cast<int>(c));
  }
  double jaw_mean = 0.0;
  if (!fs.jaw.empty()) {
    r.jaw.assign(fs.jaw.data(), fs.jaw.data() + fs.jaw.size());
    column_stats(r.jaw.data(), frames, 1, 0, jaw_mean, r.jaw_sd);
  }
  if (g.body.has_face()) {
    r.expressions = g.body.expressions.data();
    r.expression_dims = g.body.expression_dims;
  }
  const int kept = std::min(ReferenceFace::kJoinExpressions, r.expression_dims);
  r.face_dims = (r.has_jaw() ? 1 : 0) + kept;
  r.face.resize(frames * static_cast<std::size_t>(r.face_dims));
  std::vector<double> e_mean(static_cast<std::size_t>(kept)), e_sd(static_cast<std::size_t>(kept));
  for (int k = 0; k < kept; ++k) {
    double sum = 0.0, sq = 0.0;
    for (std::size_t f = 0; f < frames; ++f) sum += r.expressions[f * static_cast<std::size_t>(r.expression_dims) + k];
    const double m = frames > 0 ? sum / static_cast<double>(frames) : 0.0;
    for (std::size_t f = 0; f < frames; ++f) {
      const double d = r.expressions[f * static_cast<std::size_t>(r.expression_dims) + k] - m;
      sq += d * d;
    }
    e_mean[static_cast<std::size_t>(k)] = m;
    const double sd = frames > 1 ? std::sqrt(sq / static_cast<double>(frames - 1)) : 0.0;
    e_sd[static_cast<std::size_t>(k)] = sd > 1e-9 ? sd : 1.0;
  }
  for (std::size_t f = 0; f < frames; ++f) {
    float* out = &r.face[f * static_cast<std::size_t>(r.face_dims)];
    int k = 0;
    if (r.has_jaw()) out[k++] = static_cast<float>(r.jaw[f] / r.jaw_sd);
    for (int e = 0; e < kept; ++e)
      out[k++] = static_cast<float>(
          (r.expressions[f * static_cast<std::size_t>(r.expression_dims) + e] - e_mean[static_cast<std::size_t>(e)]) /
          e_sd[static_cast<std::size_t>(e)]);
  }
  add_phones(g, r);
  return r;
}

}  // namespace gmg
