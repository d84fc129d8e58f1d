#include "engine/face/face_track.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/face/candidates.h"
#include "engine/face/jaw_model.h"
#include "engine/face/reference_face.h"
#include "engine/face/selection.h"
#include "engine/face/units.h"
#include "engine/motion/body_parts.h"

namespace gmg {

std::string face_track_unavailable(const MotionGraph& g) {
  const bool jaw = jaw_joint(g.motion.skeleton) >= 0;
  if (!g.body.has_face() && !jaw) return "the reference has no face (no expressions and no jaw joint)";
  if (!g.face_speech.known()) return "the graph keeps no face speech (built by an older gmg: rebuild it)";
  if (jaw && g.face_speech.jaw.empty()) return "the graph keeps no jaw opening (rebuild it)";
  return "";
}

std::string face_track_summary(const MotionGraph& g) {
  const std::string why = face_track_unavailable(g);
  if (!g.body.has_face() && jaw_joint(g.motion.skeleton) < 0) return "none (" + why + ")";
  if (!why.empty()) return "along the body (" + why + ")";
  std::string out = "the new speech: ";
  if (g.body.has_face()) out += std::to_string(g.body.expression_dims) + " expressions, ";
  if (!g.face_speech.jaw.empty()) out += "the jaw, ";
  out += g.face_speech.phones.empty()
             ? "by sound only (the reference's transcripts have no phones tier)"
             : "by phones (" + std::to_string(g.face_speech.phones.size()) + " reference phones) and sound";
  return out;
}

FaceTrack face_track(const MotionGraph& g, const std::vector<float>& features, const std::vector<text::Phone>* phones,
                     int frames, const FaceParams& params) {
  face_params_validate(params);
  FaceTrack t;
  t.follows = "body";
  if (params.mode == FaceMode::Body) {
    t.why = "face_mode=body";
    return t;
  }
  t.why = face_track_unavailable(g);
  if (!t.why.empty() || frames <= 0) return t;
  const ReferenceFace r = reference_face(g);
  const std::size_t n = static_cast<std::size_t>(frames);
  if (features.size() != n * static_cast<std::size_t>(r.dims))
    throw Error("face track: the new speech's face features do not cover its frames");
  FaceTarget target;
  target.frames = frames;
  target.z.resize(features.size());
  for (std::size_t f = 0; f < n; ++f)
    for (int d = 0; d < r.dims; ++d) {
      const std::size_t i = f * static_cast<std::size_t>(r.dims) + static_cast<std::size_t>(d);
      target.z[i] =
          static_cast<float>((features[i] - r.mean[static_cast<std::size_t>(d)]) / r.sd[static_cast<std::size_t>(d)]);
    }
  t.from_phones = phones && !phones->empty() && !r.phones.empty();
  const std::vector<FaceUnit> units = face_units(t.from_phones ? phones : nullptr, r.fps, frames, params);
  if (r.has_jaw()) {
    const JawModel model = fit_jaw_model(r, t.from_phones);
    std::vector<TimedViseme> timed;
    for (const FaceUnit& u : units)
      if (u.phone && !u.symbol.empty()) timed.push_back({u.start, u.end, text::viseme_of(u.symbol)});
    target.jaw = predict_jaw(model, target.z, r.dims, frame_visemes(timed, frames));
  }
  const std::vector<std::vector<FaceCandidate>> candidates = face_candidates(r, units, target, params);
  const std::vector<int> chosen_index = select_face_stretches(r, candidates, params);
  std::vector<FaceCandidate> chosen;
  chosen.reserve(units.size());
  for (std::size_t i = 0; i < units.size(); ++i) {
    chosen.push_back(candidates[i][static_cast<std::size_t>(chosen_index[i])]);
    if (i > 0 && face_join_cost(r, chosen[i - 1], chosen[i], params) > 0.0) ++t.cuts;
  }
  t.units = static_cast<int>(units.size());
  t.sources = face_sources(r, units, chosen, frames, params.crossfade_s * r.fps);
  t.follows = "speech";
  return t;
}

namespace {

// The reference's value at fractional frame time s, linearly between its two nearest frames.
template <typename Get>
auto at_time(double s, int frames, Get get) {
  const int f0 = std::clamp(static_cast<int>(std::floor(s)), 0, frames - 1);
  const int f1 = std::min(frames - 1, f0 + 1);
  return get(f0, f1, std::clamp(s - f0, 0.0, 1.0));
}

}  // namespace

nlohmann::ordered_json face_track_report(const FaceTrack& track) {
  nlohmann::ordered_json j;
  j["follows"] = track.follows;
  if (track.follows == "speech") {
    j["units"] = track.from_phones ? "phones" : "audio windows";
    j["unit_count"] = track.units;
    j["cuts"] = track.cuts;
  } else {
    j["why"] = track.why;
  }
  return j;
}

void apply_face_track(const MotionGraph& g, const FaceTrack& track, Motion& motion, SmplxBody& body) {
  if (track.sources.empty()) return;
  const int frames = static_cast<int>(track.sources.size());
  const int total = g.frame_count();
  if (g.body.has_face()) {
    const int dims = g.body.expression_dims;
    if (body.expression_dims != dims || body.expressions.size() != static_cast<std::size_t>(frames) * dims)
      throw Error("face track: the output's face does not have the track's frames");
    const double* e = g.body.expressions.data();
    for (int f = 0; f < frames; ++f) {
      const FaceSource& s = track.sources[static_cast<std::size_t>(f)];
      double* out = &body.expressions[static_cast<std::size_t>(f) * static_cast<std::size_t>(dims)];
      for (int d = 0; d < dims; ++d) {
        const auto value = [&](double time) {
          return at_time(time, total, [&](int f0, int f1, double a) {
            return (1.0 - a) * e[static_cast<std::size_t>(f0) * dims + d] +
                   a * e[static_cast<std::size_t>(f1) * dims + d];
          });
        };
        out[d] = s.w > 0.0 ? (1.0 - s.w) * value(s.a) + s.w * value(s.b) : value(s.a);
      }
    }
  }
  const int jaw = jaw_joint(motion.skeleton);
  if (jaw >= 0 && jaw_joint(g.motion.skeleton) == jaw && !g.face_speech.jaw.empty()) {
    if (motion.frame_count != frames) throw Error("face track: the output motion does not have the track's frames");
    const auto rotation = [&](double time) {
      return at_time(time, total, [&](int f0, int f1, double a) {
        return glm::slerp(g.motion.rotation(f0, jaw), g.motion.rotation(f1, jaw), a);
      });
    };
    for (int f = 0; f < frames; ++f) {
      const FaceSource& s = track.sources[static_cast<std::size_t>(f)];
      const glm::dquat q = s.w > 0.0 ? glm::slerp(rotation(s.a), rotation(s.b), s.w) : rotation(s.a);
      motion.rotations[motion.index(f, jaw)] = glm::normalize(q);
    }
  }
}

}  // namespace gmg
