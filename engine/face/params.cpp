#include "engine/face/params.h"

#include <string>
#include <utility>

#include "engine/core/error.h"

namespace gmg {

void face_params_validate(const FaceParams& p) {
  require_param(p.candidates >= 1 && p.candidates <= 500, "face_candidates must be in [1, 500]");
  require_param(p.unit_frames >= 1 && p.unit_frames <= 60, "face_unit_frames must be in [1, 60]");
  require_param(p.silence_unit_max_s >= 0.05 && p.silence_unit_max_s <= 10.0,
                "face_silence_unit_max_s must be in [0.05, 10] seconds");
  for (const auto& [value, name] : {std::pair{p.phone_weight, "face_phone_weight"},
                                    {p.context_weight, "face_context_weight"},
                                    {p.duration_weight, "face_duration_weight"},
                                    {p.audio_weight, "face_audio_weight"},
                                    {p.spectrum_weight, "face_spectrum_weight"},
                                    {p.jaw_weight, "face_jaw_weight"},
                                    {p.join_weight, "face_join_weight"},
                                    {p.join_cost, "face_join_cost"}})
    require_param(value >= 0.0 && value <= 100.0, std::string(name) + " must be in [0, 100]");
  require_param(p.crossfade_s >= 0.0 && p.crossfade_s <= 1.0, "face_crossfade_s must be in [0, 1] seconds");
}

}  // namespace gmg
