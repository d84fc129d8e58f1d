// Face track parameters (engine/face): what the jaw and the expressions follow, and how reference
// stretches are chosen and joined. The defaults were set on BEAT2 speaker scott (graph of
// 2_scott_0_1_1, new speech 2_scott_0_2_2 and 0_3_3, docs/method.md "The face").
#pragma once

#include <cstdint>

#include "engine/core/enum_names.h"

namespace gmg {

// What the face follows. Speech: a track of its own, chosen by the new speech (engine/face/
// face_track.h). Body: the reference face of the frames the body plays, on the body's clock
// (engine/assemble/channels.h), as before the face track existed.
enum class FaceMode : std::uint8_t { Speech, Body };
inline constexpr EnumName<FaceMode> kFaceModeNames[] = {{FaceMode::Speech, "speech"}, {FaceMode::Body, "body"}};

struct FaceParams {
  // Speech: the face track wherever the graph has a face and keeps its speech (a graph of format
  // 11 or older, or a reference without a face, plays the face along the body as before).
  FaceMode mode = FaceMode::Speech;
  // Reference stretches kept per unit of the new speech, the best by target cost. The selection's
  // time grows with its square.
  int candidates = 24;
  // Without phones, the new speech is cut into units of this many frames (4 at 30 fps: 133 ms, the
  // length of a syllable's half), and so are pauses longer than silence_unit_max_s with phones.
  int unit_frames = 4;
  double silence_unit_max_s = 0.4;
  // Target cost of a reference phone for a phone of the new speech: phone_weight for another phone
  // of the same viseme (twice that for another viseme), context_weight for each neighbour that
  // differs likewise (half of it for the same viseme), duration_weight times |log| of the ratio of
  // the two durations.
  double phone_weight = 2.0;
  double context_weight = 2.0;
  double duration_weight = 1.5;
  // Target cost of how the speech under a stretch sounds against the new speech under its unit
  // (audio/face_features.h, each feature over the reference's spread): the root mean square
  // difference, loudness weighted 1 and each voicing and spectrum feature spectrum_weight.
  double audio_weight = 1.0;
  double spectrum_weight = 0.3;
  // Target cost of the stretch's jaw against the jaw the reference's own speech predicts for the
  // new speech (engine/face/jaw_model.h), per the reference's spread of the jaw: what keeps the
  // jaw open on loud open vowels and closed on m, b and p.
  double jaw_weight = 2.0;
  // Cost of joining two stretches that are not one stretch of the reference: join_weight times
  // (the faces' difference where they meet + join_cost).
  double join_weight = 0.3;
  double join_cost = 0.2;
  // A join blends the two stretches over this many seconds either side of it (a linear cross-fade,
  // which keeps every expression inside the reference's range).
  double crossfade_s = 0.03;
};

// Throws gmg::Error naming the first key out of range.
void face_params_validate(const FaceParams& params);

}  // namespace gmg
