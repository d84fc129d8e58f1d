// A face of its own for new speech: the jaw and the expressions chosen by the new speech at the
// rate faces change, independently of the path the body plays. The new speech is cut into units
// (its phones, from a transcript's phones tier, else short windows: engine/face/units.h); each
// unit's candidates are reference stretches of the same phone in a like context, or sounding alike
// (engine/face/candidates.h), scored against the jaw the reference's own speech predicts
// (engine/face/jaw_model.h); the cheapest sequence with its joins (engine/face/selection.h) is
// warped onto the units and cross-faded at its cuts (engine/face/warp.h). Blends are convex, so
// every expression stays inside the reference's range. It draws no random numbers.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/face/params.h"
#include "engine/face/warp.h"
#include "engine/motion/motion.h"
#include "engine/motion/npz.h"
#include "graph/motion_graph.h"
#include "text/phones.h"

namespace gmg {

struct FaceTrack {
  std::vector<FaceSource> sources;  // one per output frame; empty: the face follows the body
  bool from_phones = false;         // units were the new speech's phones
  int units = 0;
  int cuts = 0;         // joins of stretches that do not follow each other in the reference
  std::string follows;  // "speech" or "body"
  std::string why;      // why the face follows the body ("" when it follows the speech)
};

// Whether g can give a face track: a face (expressions) or a jaw joint, and its face speech known.
// "" when it can, else why not (for the report).
std::string face_track_unavailable(const MotionGraph& g);

// What a reenactment's face follows with g, for `gmg inspect`: "none (...)" without a face or a
// jaw, "along the body (<why>)" when face_track_unavailable, else "the new speech: " and what the
// graph keeps for it (expressions per frame, a jaw, its phones or "sound only").
std::string face_track_summary(const MotionGraph& g);

// The face track of new speech of `frames` frames, given its face features (audio/face_features.h,
// frames x kDims) and its phones (seconds; null or empty: none). With params.mode Body or when
// face_track_unavailable, a track that follows the body (no sources).
FaceTrack face_track(const MotionGraph& g, const std::vector<float>& features, const std::vector<text::Phone>* phones,
                     int frames, const FaceParams& params);

// Puts the track on an output: body.expressions (when the graph has a face) and the jaw joint's
// rotation in `motion` (when its skeleton has one and the graph a jaw), frame by frame from the
// reference. Nothing for a track that follows the body. motion and body must have the track's
// frame count.
void apply_face_track(const MotionGraph& g, const FaceTrack& track, Motion& motion, SmplxBody& body);

// The report's "face_track": what the face follows, from what units, how many cuts, or why it
// follows the body.
nlohmann::ordered_json face_track_report(const FaceTrack& track);

}  // namespace gmg
